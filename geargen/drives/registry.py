"""Every drive kind (:class:`geargen.drives.kind.DriveKind`), by name, derived from the kinds
registered in :mod:`geargen.drives.keys` (one line per kind, there): each kind's ``DRIVE`` is read
from the ``kind.py`` of its keys module's package (``geargen/drives/<kind>/kind.py``), in KEYS'
order. The kinds are imported here, above the design loader, not by the keys registry: the loader
reads the keys without loading a kind's placement and hardware (which import the loader: no
cycle). ``tests/test_import_cycles.py`` counts these imports as edges."""

from __future__ import annotations

from importlib import import_module

from geargen.drives.keys import KEYS
from geargen.drives.kind import DriveKind

#: the module of a kind's package that holds its DriveKind (``DRIVE``)
KIND_MODULE = "kind"

DRIVES: dict[str, DriveKind] = {name: import_module(f"{keys.__package__}.{KIND_MODULE}").DRIVE
                                for name, keys in KEYS.items()}

__all__ = ["DRIVES", "KIND_MODULE"]
