"""Gear families: each family of gear in a folder of its own, ``geargen/families/<kind>/``, one file
per layer role (spec, geometry, solid, pair, data, options, drawing) and its ``family.py``, the
:class:`geargen.families.family.GearFamily` listed in :mod:`geargen.families.registry`.
docs/adding-a-family.md says which files a new family touches."""
