"""Drive kinds: each kind of anti-backlash drive in a folder of its own, ``geargen/drives/<kind>/``.

A kind's folder holds:

- ``keys.py``: its ``[layout]`` and ``[parts]`` keys and their rules (design layer: the loader
  reads them through :mod:`geargen.drives.keys`, which imports nothing else);
- ``place.py``: its gears placed from the design (:class:`geargen.model.Layout`);
- ``hardware.py``: its non-gear parts and joints laid out as data (:mod:`geargen.model.components`);
- ``kind.py``: its :class:`geargen.drives.kind.DriveKind`, what the resolver and the verdict call
  (placement, hardware, extra verdict rows, starter file);

and registers in two lines: its keys module in :data:`geargen.drives.keys.KEYS` (which the loader
reads), its kind in :mod:`geargen.drives.registry`. Upstream stages (a planetary stage) live alike in their own folder.
:mod:`geargen.drives.resolver` resolves a design (gears placed, hardware laid out); nothing else
asks which drive a design is: :func:`geargen.drives.keys.kind_of` answers once.
"""
