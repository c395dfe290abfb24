"""One entry point to build any gear kind's solid: :func:`build_part`, through the spec's family
(:mod:`geargen.families.registry`): each family's ``build`` takes ``(spec, check, tolerance)`` and
returns an object with ``shape``, ``name``, ``spec`` and ``length_unit`` (a
:class:`geargen.cad.gear_solid.GearSolid` or the family's own)."""

from __future__ import annotations

from geargen.families.registry import family_of


def build_part(spec, check: bool = False, tolerance: float | None = None):
    """Build ``spec``'s solid with its family's builder; ``check`` validates it (BuildError if not
    one valid closed solid); ``tolerance``: the spline fit tolerance of a family fitted to a sampled
    tooth profile (None: its default)."""
    return family_of(spec).build(spec, check=check, tolerance=tolerance)


def toothed_solid(toothed):
    """The family's solid (shape, spec, its own mesher) of a toothed component of a drive's hardware
    (:class:`geargen.model.components.Toothed`; a bevel gear is cut with its spec's back, which the
    component carries)."""
    return build_part(toothed.spec, check=True)


__all__ = ["build_part", "toothed_solid"]
