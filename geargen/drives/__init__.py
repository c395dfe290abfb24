"""Drive kinds: each kind of anti-backlash drive in a folder of its own, ``geargen/drives/<kind>/``.

A kind's folder holds:

- ``keys.py``: its ``[layout]`` and ``[parts]`` keys and their rules (design layer: the loader
  reads them through :mod:`geargen.drives.keys`, which imports nothing else);
- ``place.py``: its gears placed from the design (:class:`geargen.model.Layout`);
- ``hardware.py``: its non-gear parts and joints laid out as data (:mod:`geargen.model.components`);
- ``kind.py``: its :class:`geargen.drives.kind.DriveKind`, what the resolver and the verdict call
  (placement, hardware, extra verdict rows, starter file);

and registers in one line, the import of its keys module in :mod:`geargen.drives.keys`: the loader
reads :data:`geargen.drives.keys.KEYS`, and :data:`geargen.drives.registry.DRIVES` takes each
registered kind's ``kind.py`` from the same module's package. Upstream stages (a planetary stage)
live alike in their own folder (not registered: the only stage kind).
:mod:`geargen.drives.resolver` resolves a design (gears placed, hardware laid out); nothing else
asks which drive a design is: :func:`geargen.drives.keys.kind_of` answers once.
"""
