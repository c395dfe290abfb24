"""Kernel helpers every solid builder shares: B-spline curves and surfaces from numpy poles, vertices,
edges and wires put together with a ``BRep_Builder``, booleans, the one solid of a shape, its
volume, the kernel's message level. One home for them (issue 26): the builders import these public names rather than
each other's private ones.

Conventions: mm; poles ``(n, 2)``, ``(n, 3)`` or ``(nu, nv, 3)`` float arrays; knots as distinct
values with their multiplicities (as :class:`geargen.profile.bspline_fit.SplineFit` holds them).
"""

from __future__ import annotations

import functools

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse
from OCP.BRepGProp import BRepGProp
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Pnt2d
from OCP.GProp import GProp_GProps
from OCP.Message import Message, Message_Gravity
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TColgp import TColgp_Array1OfPnt, TColgp_Array1OfPnt2d, TColgp_Array2OfPnt
from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Shape, TopoDS_Shell, TopoDS_Solid, TopoDS_Vertex, TopoDS_Wire
from OCP.TopTools import TopTools_ListOfShape

from geargen.errors import BuildError

#: edge/vertex tolerance given to the kernel (mm)
KERNEL_TOLERANCE = 1e-7

#: whether the kernel's parallel algorithms may run in this process: not in one forked from a
#: process that may have started the kernel's thread pool (its threads are not copied by the fork,
#: and a parallel boolean or mesh waits for them for ever); :func:`forked` says so in the child
_threads_usable = True


def forked() -> None:
    """Called in a forked process: from now on the kernel's operations run on this thread alone."""
    global _threads_usable
    _threads_usable = False


def threads_usable() -> bool:
    """Whether the kernel's parallel algorithms may run in this process (see :func:`forked`)."""
    return _threads_usable


#: the z axis through the origin (every gear's axis), and the origin of a plane's pcurves
Z_AXIS = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
ORIGIN_2D = gp_Pnt2d(0, 0)


def occ_knots(knots, mults):
    """The kernel's knot and multiplicity arrays of distinct ``knots`` with multiplicities ``mults``."""
    return _occ_knots_of(tuple(float(t) for t in knots), tuple(int(m) for m in mults))


@functools.lru_cache(maxsize=256)
def _occ_knots_of(knots: tuple, mults: tuple):
    """The kernel's knot and multiplicity arrays (shared: the kernel copies them into each spline)."""
    k = TColStd_Array1OfReal(1, len(knots))
    m = TColStd_Array1OfInteger(1, len(knots))
    for i, (t, mult) in enumerate(zip(knots, mults)):
        k.SetValue(i + 1, float(t))
        m.SetValue(i + 1, int(mult))
    return k, m


def bspline_curve_3d(poles: np.ndarray, knots, mults, degree: int) -> Geom_BSplineCurve:
    """The space B-spline curve with ``(n, 3)`` poles."""
    arr = TColgp_Array1OfPnt(1, len(poles))
    for i, (x, y, z) in enumerate(poles.tolist()):
        arr.SetValue(i + 1, gp_Pnt(x, y, z))
    return Geom_BSplineCurve(arr, *occ_knots(knots, mults), degree)


def bspline_curve_2d(poles: np.ndarray, knots, mults, degree: int) -> Geom2d_BSplineCurve:
    """The plane B-spline curve (a pcurve) with ``(n, 2)`` poles."""
    arr = TColgp_Array1OfPnt2d(1, len(poles))
    for i, (x, y) in enumerate(poles.tolist()):
        arr.SetValue(i + 1, gp_Pnt2d(x, y))
    return Geom2d_BSplineCurve(arr, *occ_knots(knots, mults), degree)


def bspline_surface(poles: np.ndarray, u_knots, u_mults, u_degree: int, v_knots, v_mults,
                    v_degree: int) -> Geom_BSplineSurface:
    """The B-spline surface with ``(nu, nv, 3)`` poles."""
    nu, nv = poles.shape[:2]
    arr = TColgp_Array2OfPnt(1, nu, 1, nv)
    for i, row in enumerate(poles.tolist()):
        for j, (x, y, z) in enumerate(row):
            arr.SetValue(i + 1, j + 1, gp_Pnt(x, y, z))
    ku, mu = occ_knots(u_knots, u_mults)
    kv, mv = occ_knots(v_knots, v_mults)
    return Geom_BSplineSurface(arr, ku, kv, mu, mv, u_degree, v_degree)


def make_vertex(builder: BRep_Builder, x: float, y: float, z: float) -> TopoDS_Vertex:
    """A vertex at (x, y, z) with the kernel tolerance."""
    v = TopoDS_Vertex()
    builder.MakeVertex(v, gp_Pnt(x, y, z), KERNEL_TOLERANCE)
    return v


def make_edge(builder: BRep_Builder, curve, v0, v1, p0: float, p1: float) -> TopoDS_Edge:
    """The edge of ``curve`` from parameter ``p0`` (vertex ``v0``) to ``p1`` (vertex ``v1``)."""
    e = TopoDS_Edge()
    builder.MakeEdge(e, curve, KERNEL_TOLERANCE)
    builder.Add(e, v0.Oriented(TopAbs_FORWARD))
    builder.Add(e, v1.Oriented(TopAbs_REVERSED))
    builder.Range(e, p0, p1)
    return e


def make_wire(builder: BRep_Builder, edges, orientations=None) -> TopoDS_Wire:
    """The closed wire of ``edges`` in order, each turned to ``orientations[i]`` when given."""
    w = TopoDS_Wire()
    builder.MakeWire(w)
    for i, e in enumerate(edges):
        builder.Add(w, e if orientations is None else e.Oriented(orientations[i]))
    w.Closed(True)
    return w


def closed_shell(builder: BRep_Builder, faces) -> TopoDS_Shell:
    """The closed shell of ``faces`` (each already oriented outward)."""
    shell = TopoDS_Shell()
    builder.MakeShell(shell)
    for face in faces:
        builder.Add(shell, face)
    shell.Closed(True)
    return shell


def closed_solid(builder: BRep_Builder, faces) -> TopoDS_Solid:
    """The solid bounded by the closed shell of ``faces`` (:func:`closed_shell`)."""
    solid = TopoDS_Solid()
    builder.MakeSolid(solid)
    builder.Add(solid, closed_shell(builder, faces))
    return solid


def single_solid(shape: TopoDS_Shape) -> TopoDS_Shape:
    """The one solid ``shape`` holds; BuildError when it holds none or several."""
    exp = TopExp_Explorer(shape, TopAbs_SOLID)
    solids = []
    while exp.More():
        solids.append(exp.Current())
        exp.Next()
    if len(solids) != 1:
        raise BuildError(f"expected one solid, got {len(solids)}")
    return TopoDS.Solid_s(solids[0])


def volume(shape: TopoDS_Shape) -> float:
    """Volume (mm^3) by the kernel's volume integration (``VolumeProperties``; negative for a solid
    turned inside out). :func:`geargen.cad.gear_solid.solid_volume` integrates spline faces to a
    stated accuracy instead."""
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def boolean(op, args, tools, parallel: bool | None = None, fuzzy: float | None = None, glue=None,
            failure: str | None = None) -> TopoDS_Shape:
    """The result of the boolean ``op`` (a ``BRepAlgoAPI_Fuse``, ``_Cut`` or ``_Common``) of ``args``
    with ``tools``; the kernel's own default for each option left unset (``parallel``, ``fuzzy``
    value, ``glue`` a ``BOPAlgo_GlueEnum`` for solids that only touch). BuildError ``failure``
    (default: the operation's name) if the kernel fails."""
    a, t = TopTools_ListOfShape(), TopTools_ListOfShape()
    for s in args:
        a.Append(s)
    for s in tools:
        t.Append(s)
    op.SetArguments(a)
    op.SetTools(t)
    if parallel is not None:
        op.SetRunParallel(parallel and _threads_usable)
    if fuzzy is not None:
        op.SetFuzzyValue(fuzzy)
    if glue is not None:
        op.SetGlue(glue)
    op.Build()
    if not op.IsDone():
        raise BuildError(failure or f"boolean operation {type(op).__name__} failed")
    return op.Shape()


def fused_solid(shapes: list[TopoDS_Shape], failure: str, fuzzy: float | None = None, glue=None) -> TopoDS_Shape:
    """The one solid ``shapes`` fuse into, faces and edges of one surface merged."""
    fused = boolean(BRepAlgoAPI_Fuse(), shapes[:1], shapes[1:], fuzzy=fuzzy, glue=glue, failure=failure)
    unify = ShapeUpgrade_UnifySameDomain(fused, True, True, False)
    unify.Build()
    return single_solid(unify.Shape())


def quiet_kernel() -> None:
    """Keep the kernel's transfer statistics off standard output (warnings and worse still print)."""
    printers = Message.DefaultMessenger_s().Printers()
    if printers.Size() > 0:
        printers.First().SetTraceLevel(Message_Gravity.Message_Warning)


__all__ = ["KERNEL_TOLERANCE", "Z_AXIS", "ORIGIN_2D", "occ_knots", "bspline_curve_3d", "bspline_curve_2d",
           "bspline_surface", "make_vertex", "make_edge", "make_wire", "closed_shell", "closed_solid", "single_solid", "volume", "boolean", "fused_solid",
           "quiet_kernel"]
