"""Solids of the resolved drive's components: one builder per body kind, deciding nothing.

Each :class:`geargen.model.bodies.Body` kind is built with the kernel primitives of
:mod:`geargen.cad.parts` exactly as its data says; the sizes, positions and every rule about them
were decided when the drive was resolved (:mod:`geargen.drives`). A toothed component (a bevel
gear of a motor drive) is built by its family's builder.
"""

from __future__ import annotations

from typing import Any

from OCP.TopoDS import TopoDS_Shape

from geargen.cad import parts as P
from geargen.model.bodies import Body


def _build(body: Body) -> TopoDS_Shape:
    k, a = body.kind, body.args
    if k == "cylinder":
        return P.cylinder(*a)
    if k == "shaft":
        return P.shaft(*a)
    if k == "box":
        corner, size = a
        return P.box(*size, corner)
    if k == "frustum":
        return P.frustum(*a)
    if k == "bearing":
        return P.bearing(*a)
    if k == "servo_motor":
        return P.servo_motor(*a)
    if k == "blade_flexure":
        return P.blade_flexure(*a)
    if k == "compression_spring":
        return P.compression_spring(*a)
    if k == "plate_with_holes":
        size, holes, corner = a
        return P.plate_with_holes(*size, list(holes), corner=corner)
    if k == "link_tray":
        dims, bosses = a
        return P.link_tray(*dims, list(bosses))
    if k == "link_cover":
        dims, seats = a
        return P.link_cover(*dims, list(seats))
    if k == "quill":
        (d, length), bores, lug = a
        return P.quill(d, length, list(bores), *lug)
    if k == "split_collar":
        return P.split_collar(*a)
    if k == "fuse":
        bodies, what = a
        return P.fuse([_build(b) for b in bodies], what)
    if k == "cut":
        base, tools = a
        return P.cut(_build(base), *[_build(t) for t in tools])
    if k == "translate":
        return P.translate(_build(a[0]), a[1])
    if k == "single":
        return P.one_valid_solid(_build(a[0]), a[1])
    raise ValueError(f"no builder for body kind {k!r}")


class SolidBuilder:
    """Builds component bodies; a shared article (``Component.shared``) is built once per drive and
    its one solid placed as often as it occurs."""

    def __init__(self):
        self._shared: dict[Body, TopoDS_Shape] = {}
        self._exact: dict[int, Any] = {}  # id(shape) -> what meshes it exactly (the shape kept in it)

    def body(self, body: Body, shared: bool = False) -> TopoDS_Shape:
        if not shared:
            return _build(body)
        if body not in self._shared:
            self._shared[body] = _build(body)
        return self._shared[body]

    def component(self, component) -> TopoDS_Shape:
        if component.toothed is not None:  # its family's solid, kept: its own mesher meshes the shape
            from geargen.cad.families import toothed_solid
            solid = toothed_solid(component.toothed)
            self._exact[id(solid.shape)] = solid
            return solid.shape
        return self.body(component.body, component.shared)

    def exact(self, component, shape: TopoDS_Shape) -> Any:
        """What meshes ``shape``, the component's solid (:meth:`component`), from its exact geometry: a
        toothed component's family solid (a bevel gear's), a compression spring's
        :class:`geargen.cad.parts.SpringSolid` (one per solid); None for any other."""
        if id(shape) not in self._exact:
            body = component.body
            if body is None or body.kind != "compression_spring":
                return None
            self._exact[id(shape)] = P.SpringSolid(shape, body.args)
        return self._exact[id(shape)]

    def envelope(self, component) -> Any:
        return None if component.envelope is None else _build(component.envelope)


__all__ = ["SolidBuilder"]
