"""The built solids as CadQuery objects, for :mod:`geargen.api` (CQ-editor, ocp_vscode, a user's own model).

The rest of :mod:`geargen.cad` works on the kernel's shapes directly; this module only wraps
them: a :class:`cadquery.Shape` holds the same ``TopoDS_Shape`` (nothing is copied or rebuilt),
and a :class:`cadquery.Assembly` has the tree of the assembly STEP
(:func:`geargen.cad.assembly.assembly_document`): the root named after the design, one
sub-assembly ``<group>_assembly`` per group, each part named as in the build, in its own frame,
placed by its matrix and coloured as in the STEP. Lengths are mm, as every shape geargen builds.
Importing this module imports CadQuery (about a second the first time).
"""

from __future__ import annotations

from typing import Iterable

import cadquery as cq

from geargen.cad.assembly import PlacedPart, location
from geargen.errors import BuildError


def shape(kernel_shape) -> cq.Shape:
    """``kernel_shape`` (a ``TopoDS_Shape``) as the CadQuery class of its type: a one-solid gear
    becomes a :class:`cadquery.Solid`, a compound a :class:`cadquery.Compound`."""
    return cq.Shape.cast(kernel_shape)


def placed_shape(part: PlacedPart) -> cq.Shape:
    """``part`` moved into the assembly frame, as it is in its STEP file and in the assembly."""
    return shape(part.world())


def assembly(name: str, parts: Iterable[PlacedPart]) -> cq.Assembly:
    """``parts`` as a :class:`cadquery.Assembly` with the assembly STEP's tree, names, placements
    and colours (RGBA). Parts that share a shape share one ``cadquery.Shape``, as they share one
    product in the STEP."""
    parts = list(parts)
    names = [p.name for p in parts]
    if len(set(names)) != len(names):
        raise BuildError(f"assembly {name}: part names are not unique")
    groups: dict[str, cq.Assembly] = {}
    wrapped: dict[int, cq.Shape] = {}
    for p in parts:
        if p.group not in groups:
            groups[p.group] = cq.Assembly(name=f"{p.group}_assembly")
        solid = wrapped.setdefault(id(p.shape), shape(p.shape))
        groups[p.group].add(solid, name=p.name, loc=cq.Location(location(p.matrix)), color=cq.Color(*p.colour))
    root = cq.Assembly(name=name)
    for group in groups.values():
        root.add(group)
    return root


__all__ = ["shape", "placed_shape", "assembly"]
