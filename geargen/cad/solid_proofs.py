"""Facts about solids read from their own faces, for the assembly's overlap check
(:func:`geargen.cad.assembly.pairwise_overlaps`): which solids are right prisms along z and the
volume two of them share (a planar boolean of their end faces times their common height), and the
smallest distance between two sets of faces, measured face pair by face pair behind lower bounds.

Nothing here reads a design or a spec: every fact comes from the faces' surfaces (type, axis,
poles), vertices and geometric bounding boxes, so the overlap check stays a check on the solids.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.BRepGProp import BRepGProp
from OCP.Bnd import Bnd_Box
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cylinder, GeomAbs_Plane, GeomAbs_SurfaceOfExtrusion
from OCP.gp import gp_Trsf, gp_Vec
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_FACE, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Shape
from OCP.TopTools import TopTools_IndexedMapOfShape

from geargen.cad import parts as P
from geargen.cad.kernel import KERNEL_TOLERANCE, boolean

#: how far a face's direction may be from exactly along or across z (as a sine or cosine) and
#: still count as such: float noise of a placement's rotation matrix is ~1e-16; 1e-9 rad moves a
#: point by 1e-7 mm (the kernel's tolerance) at 100 mm from the axis, the size of these parts
ANGULAR_TOLERANCE = 1e-9


def explore(shape, kind):
    """The sub-shapes of ``shape`` of type ``kind`` (``TopAbs_FACE`` ...), in the kernel's order."""
    exp = TopExp_Explorer(shape, kind)
    while exp.More():
        yield exp.Current()
        exp.Next()


def face_box(face) -> Bnd_Box:
    """The face's bounding box from its geometry (B-spline poles, analytic bounds), not from a
    possibly coarse mesh: it holds the whole face."""
    box = Bnd_Box()
    BRepBndLib.Add_s(face, box, False)
    return box


# ---------------------------------------------------------------- right prisms along z


@dataclass(frozen=True)
class Prism:
    """A solid proven a right prism along z: its end faces at ``z0`` (``cap``, moved to z = 0)
    swept from ``z0`` to ``z1`` (mm)."""

    cap: TopoDS_Shape
    z0: float
    z1: float


def _bspline_along_z(surface) -> bool:
    """A B-spline surface whose one parameter direction is of degree 1 with two poles per row, each
    row the same step along z and of equal weights: the surface is a curve swept straight along z."""
    nu, nv = surface.NbUPoles(), surface.NbVPoles()
    if not (surface.VDegree() == 1 and nv == 2 or surface.UDegree() == 1 and nu == 2):
        return False
    poles = np.array([[surface.Pole(i, j).Coord() for j in range(1, nv + 1)] for i in range(1, nu + 1)])
    if surface.IsURational() or surface.IsVRational():
        weights = np.array([[surface.Weight(i, j) for j in range(1, nv + 1)] for i in range(1, nu + 1)])
    else:  # every weight 1
        weights = np.ones((nu, nv))
    for degree, count, step, w in ((surface.VDegree(), nv, poles[:, -1] - poles[:, 0], weights[:, -1] - weights[:, 0]),
                                   (surface.UDegree(), nu, poles[-1] - poles[0], weights[-1] - weights[0])):
        if degree != 1 or count != 2:
            continue
        # every row moved by the same (0, 0, h): exact to the kernel's tolerance
        if np.abs(step[:, :2]).max() <= KERNEL_TOLERANCE and np.ptp(step[:, 2]) <= KERNEL_TOLERANCE \
                and abs(step[0, 2]) > KERNEL_TOLERANCE and np.abs(w).max() <= 1e-12 * np.abs(weights).max():
            return True
    return False


def _along_z(adaptor) -> bool:
    """The face's surface is unchanged by a move along z (every point's vertical line lies on it)."""
    kind = adaptor.GetType()
    if kind == GeomAbs_Plane:
        return abs(adaptor.Plane().Axis().Direction().Z()) <= ANGULAR_TOLERANCE
    if kind == GeomAbs_Cylinder:
        return abs(abs(adaptor.Cylinder().Axis().Direction().Z()) - 1.0) <= ANGULAR_TOLERANCE
    if kind == GeomAbs_SurfaceOfExtrusion:
        return abs(abs(adaptor.Direction().Z()) - 1.0) <= ANGULAR_TOLERANCE
    if kind == GeomAbs_BSplineSurface:
        return _bspline_along_z(adaptor.BSpline())  # the adaptor's copy carries the face's placement
    return False


def z_prism(shape: TopoDS_Shape) -> Prism | None:
    """``shape`` as a right prism along z, if its own faces prove it one, else None.

    The proof: one solid; every face either a plane across z at the lowest or highest such plane
    (an end face) or a surface unchanged by a move along z; every vertex on one of the two end
    planes; the geometric bounding box between them. A closed boundary made of such faces cuts
    every plane z = c between the ends in the same region (the sides are vertical, nothing else
    bounds it), so the solid is that region, its lower end faces, swept from end to end.
    """
    solids = list(explore(shape, TopAbs_SOLID))
    if len(solids) != 1:
        return None
    caps: list[tuple[float, object]] = []
    for face in explore(solids[0], TopAbs_FACE):
        adaptor = BRepAdaptor_Surface(TopoDS.Face_s(face))
        if adaptor.GetType() == GeomAbs_Plane and \
                abs(abs(adaptor.Plane().Axis().Direction().Z()) - 1.0) <= ANGULAR_TOLERANCE:
            caps.append((adaptor.Plane().Location().Z(), face))
        elif not _along_z(adaptor):
            return None
    if not caps:
        return None
    z0, z1 = min(z for z, _ in caps), max(z for z, _ in caps)
    if z1 - z0 <= KERNEL_TOLERANCE:
        return None
    # end faces only at the two ends; a plane across z in between would be a step
    if any(min(abs(z - z0), abs(z - z1)) > KERNEL_TOLERANCE for z, _ in caps):
        return None
    vertices = TopTools_IndexedMapOfShape()  # each vertex once (the explorer visits one per edge and face)
    TopExp.MapShapes_s(solids[0], TopAbs_VERTEX, vertices)
    for i in range(1, vertices.Extent() + 1):
        z = BRep_Tool.Pnt_s(TopoDS.Vertex_s(vertices.FindKey(i))).Z()
        if min(abs(z - z0), abs(z - z1)) > KERNEL_TOLERANCE:
            return None
    box = Bnd_Box()
    BRepBndLib.Add_s(solids[0], box, False)
    _, _, zmin, _, _, zmax = box.Get()
    slack = KERNEL_TOLERANCE + box.GetGap() + 1e-9  # the box is enlarged by the shape's tolerance
    if zmin < z0 - slack or zmax > z1 + slack:
        return None
    lower = [face for z, face in caps if abs(z - z0) <= KERNEL_TOLERANCE]
    down = gp_Trsf()
    down.SetTranslation(gp_Vec(0.0, 0.0, -z0))
    return Prism(P.compound(lower).Moved(TopLoc_Location(down)), z0, z1)


def prism_common_volume(a: Prism, b: Prism) -> float:
    """The volume (mm^3) two right prisms along z share: the area their end regions share times
    the height their z spans share (0 if they only touch)."""
    height = min(a.z1, b.z1) - max(a.z0, b.z0)
    if height <= 0.0:
        return 0.0
    common = boolean(BRepAlgoAPI_Common(), [a.cap], [b.cap], parallel=False, failure="planar boolean common failed")
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(common, props)
    return abs(props.Mass()) * height


# ---------------------------------------------------------------- distance between face sets


def _box_array(boxes) -> np.ndarray:
    return np.array([b.Get() for b in boxes], dtype=float).reshape(-1, 6)


def _corners(boxes: np.ndarray) -> np.ndarray:
    """The eight corners ``(n, 8, 3)`` of each box ``(n, 6)`` (xmin, ymin, zmin, xmax, ymax, zmax)."""
    pick = np.array([[i, j, k] for i in (0, 3) for j in (1, 4) for k in (2, 5)])
    return boxes[:, pick]


def surfaces_of(faces) -> list:
    """For each face the surface the distance bounds use: ``("plane", point, normal)``,
    ``("cylinder", point on the axis, axis direction, radius)`` (numpy, mm), or ``None`` (a spline
    or any other surface: bounded by its box only)."""
    out = []
    for face in faces:
        adaptor = BRepAdaptor_Surface(TopoDS.Face_s(face))
        kind = adaptor.GetType()
        if kind == GeomAbs_Plane:
            axis = adaptor.Plane().Axis()
            out.append(("plane", _xyz(axis.Location()), _xyz(axis.Direction())))
        elif kind == GeomAbs_Cylinder:
            cyl = adaptor.Cylinder()
            out.append(("cylinder", _xyz(cyl.Axis().Location()), _xyz(cyl.Axis().Direction()), cyl.Radius()))
        else:
            out.append(None)
    return out


def _xyz(p) -> np.ndarray:
    return np.array((p.X(), p.Y(), p.Z()))


def _surface_bounds(surfaces: list, boxes_other: np.ndarray) -> np.ndarray:
    """For each surface of ``surfaces`` (:func:`surfaces_of`) a lower bound (mm) of the distance
    from it to anything inside each box of ``boxes_other``; 0 where nothing is proven.

    A plane: the box's corners all on one side bound the distance by the nearest corner's. A
    cylinder (axis, radius R): points of a box whose corners all lie within r < R of the axis
    are at least R - r from the cylinder (distance to a line is convex: its largest value on a
    box is at a corner); for an axis along z, points of a box whose xy rectangle stays farther
    than r > R from the axis are at least r - R from it."""
    out = np.zeros((len(surfaces), len(boxes_other)))
    if not len(boxes_other):
        return out
    corners = _corners(boxes_other)
    for i, surface in enumerate(surfaces):
        if surface is None:
            continue
        if surface[0] == "plane":
            _, p, n = surface
            signed = (corners - p) @ n
            lo, hi = signed.min(axis=1), signed.max(axis=1)
            out[i] = np.where(lo > 0, lo, np.where(hi < 0, -hi, 0.0))
        else:
            _, p, u, radius = surface
            rel = corners - p
            radial = np.linalg.norm(rel - (rel @ u)[..., None] * u, axis=-1)
            bound = np.maximum(radius - radial.max(axis=1), 0.0)
            if abs(abs(u[2]) - 1.0) <= ANGULAR_TOLERANCE:
                dx = np.maximum(np.maximum(boxes_other[:, 0] - p[0], p[0] - boxes_other[:, 3]), 0.0)
                dy = np.maximum(np.maximum(boxes_other[:, 1] - p[1], p[1] - boxes_other[:, 4]), 0.0)
                bound = np.maximum(bound, np.hypot(dx, dy) - radius)
            out[i] = bound
    return out


def pair_bounds(surfaces_a: list, boxes_a: np.ndarray, surfaces_b: list, boxes_b: np.ndarray) -> np.ndarray:
    """A lower bound ``(len(boxes_a), len(boxes_b))`` (mm) of the distance between each face of one
    set and each of the other (their surfaces, :func:`surfaces_of`, and geometric boxes ``(n, 6)``):
    the gap between the boxes, and a plane's or a cylinder's distance to the other face's box
    (:func:`_surface_bounds`)."""
    gap = np.maximum(np.maximum(boxes_b[None, :, :3] - boxes_a[:, None, 3:], boxes_a[:, None, :3] - boxes_b[None, :, 3:]), 0.0)
    bound = np.linalg.norm(gap, axis=-1)
    bound = np.maximum(bound, _surface_bounds(surfaces_a, boxes_b))
    return np.maximum(bound, _surface_bounds(surfaces_b, boxes_a).T)


def face_set_distance(faces_a: list, faces_b: list, surfaces_a: list | None = None, boxes_a: np.ndarray | None = None,
                      surfaces_b: list | None = None, boxes_b: np.ndarray | None = None) -> float:
    """The smallest distance (mm) between the faces ``faces_a`` and the faces ``faces_b`` (as the
    kernel measures two compounds of them), within ``KERNEL_TOLERANCE``. Their surfaces
    (:func:`surfaces_of`) and geometric boxes may be given (else found here).

    Each pair of faces gets a lower bound from the solids' own geometry (:func:`pair_bounds`). The
    pairs are measured exactly (``BRepExtrema_DistShapeShape``) from the smallest bound up, and
    the search stops when the next bound is no smaller than the best distance found less the
    kernel's tolerance: no pair left can come closer than that. If the kernel fails on a pair,
    the two compounds are measured at once, as before."""
    surfaces_a = surfaces_of(faces_a) if surfaces_a is None else surfaces_a
    surfaces_b = surfaces_of(faces_b) if surfaces_b is None else surfaces_b
    boxes_a = _box_array([face_box(f) for f in faces_a]) if boxes_a is None else boxes_a
    boxes_b = _box_array([face_box(f) for f in faces_b]) if boxes_b is None else boxes_b
    bound = pair_bounds(surfaces_a, boxes_a, surfaces_b, boxes_b)
    # a contact found ends the search, so among equal bounds (faces in contact all bound 0) the
    # likeliest contact goes first: planes and cylinders before splines; of two analytic faces the
    # boxes sharing most volume (a shaft in its bore, a ring gear's rim in its housing), of a spline
    # and another the boxes sharing least (a flat seat under a spring's coil)
    cost = np.array([s is None for s in surfaces_a], dtype=int)[:, None] + np.array([s is None for s in surfaces_b])
    shared = np.prod(np.maximum(np.minimum(boxes_a[:, None, 3:], boxes_b[None, :, 3:]) -
                                np.maximum(boxes_a[:, None, :3], boxes_b[None, :, :3]), 0.0), axis=-1)
    best = math.inf
    flat = bound.ravel()
    for k in np.lexsort((np.where(cost == 0, -shared, shared).ravel(), cost.ravel(), flat)):
        if flat[k] >= best - KERNEL_TOLERANCE:
            break
        i, j = divmod(int(k), bound.shape[1])
        dist = BRepExtrema_DistShapeShape(faces_a[i], faces_b[j])
        if not dist.IsDone():
            whole = BRepExtrema_DistShapeShape(P.compound(faces_a), P.compound(faces_b))
            return float(whole.Value()) if whole.IsDone() else math.inf
        best = min(best, float(dist.Value()))
    return best


# ---------------------------------------------------------------- solids that share no volume


class SolidFacts:
    """What the overlap check learns about one shape, each fact made once: its faces with their
    geometric boxes, its box, whether it is a right prism along z (:func:`z_prism`)."""

    def __init__(self, shape: TopoDS_Shape):
        self.shape = shape
        self._prism: Prism | None | bool = False  # False: not asked yet
        self._faces: tuple[list, np.ndarray] | None = None
        self._surfaces: list | None = None
        self._kernel_box: Bnd_Box | None = None

    @property
    def prism(self) -> Prism | None:
        if self._prism is False:
            self._prism = z_prism(self.shape)
        return self._prism

    @property
    def faces(self) -> tuple[list, np.ndarray]:
        """The faces and their geometric boxes ``(n, 6)``."""
        if self._faces is None:
            faces = list(explore(self.shape, TopAbs_FACE))
            self._faces = (faces, _box_array([face_box(f) for f in faces]))
        return self._faces

    @property
    def surfaces(self) -> list:
        """Each face's plane or cylinder (:func:`surfaces_of`)."""
        if self._surfaces is None:
            self._surfaces = surfaces_of(self.faces[0])
        return self._surfaces

    @property
    def kernel_box(self) -> Bnd_Box:
        """The kernel's box of the whole shape (``BRepBndLib.Add``, a mesh's where there is one);
        the caller may enlarge a copy."""
        if self._kernel_box is None:
            self._kernel_box = Bnd_Box()
            BRepBndLib.Add_s(self.shape, self._kernel_box, True)
        return self._kernel_box

    def faces_meeting(self, box) -> tuple[list, list, np.ndarray]:
        """The faces whose geometric box meets ``box`` (a ``Bnd_Box`` or an array (6,)), with
        their surfaces and boxes."""
        faces, boxes = self.faces
        if isinstance(box, Bnd_Box):
            if box.IsVoid():
                return [], [], boxes[:0]
            box = np.array(box.Get())
        keep = np.all(boxes[:, :3] <= box[3:], axis=1) & np.all(boxes[:, 3:] >= box[:3], axis=1)
        surfaces = self.surfaces
        return [f for f, k in zip(faces, keep) if k], [s for s, k in zip(surfaces, keep) if k], boxes[keep]

    @property
    def box(self) -> np.ndarray:
        """The box around all faces (xmin, ymin, zmin, xmax, ymax, zmax)."""
        boxes = self.faces[1]
        return np.concatenate([boxes[:, :3].min(axis=0), boxes[:, 3:].max(axis=0)])


def _inside(point, shape) -> bool:
    """``point`` is inside (or on) one of the solids of ``shape``."""
    from OCP.BRepClass3d import BRepClass3d_SolidClassifier
    from OCP.TopAbs import TopAbs_OUT
    return any(BRepClass3d_SolidClassifier(solid, point, KERNEL_TOLERANCE).State() != TopAbs_OUT
               for solid in explore(shape, TopAbs_SOLID))


def share_no_volume(a: SolidFacts, b: SolidFacts) -> bool:
    """True when the solids' own faces prove that ``a`` and ``b`` share no volume; False when
    nothing is proven (they may still share none).

    The proof: every face of one that could reach the other (its box meets the other's box) is
    farther than the kernel's tolerance from every such face of the other (:func:`pair_bounds`),
    so the two boundaries do not meet; then each boundary piece (a shell) lies wholly inside or
    wholly outside the other solid, and one vertex of each shell found outside the other solid
    puts the whole shell outside. Two solids whose boundaries do not meet and whose every shell is
    outside the other share nothing (what they share would need a boundary of its own, made of
    pieces of theirs lying inside the other)."""
    from OCP.TopAbs import TopAbs_SHELL
    fa, sa, ba = a.faces_meeting(b.box)
    fb, sb, bb = b.faces_meeting(a.box)
    if fa and fb and pair_bounds(sa, ba, sb, bb).min() <= KERNEL_TOLERANCE:
        return False
    for this, other in ((a, b), (b, a)):
        for shell in explore(this.shape, TopAbs_SHELL):
            vertex = next(explore(shell, TopAbs_VERTEX), None)
            if vertex is None:
                return False
            point = BRep_Tool.Pnt_s(TopoDS.Vertex_s(vertex))
            # outside the box of the other's faces (which holds that solid) is outside it: no classifier
            box = other.box
            outside_box = any(c < lo - KERNEL_TOLERANCE or c > hi + KERNEL_TOLERANCE
                              for c, lo, hi in zip(point.Coord(), box[:3], box[3:]))
            if not outside_box and _inside(point, other.shape):
                return False
    return True
