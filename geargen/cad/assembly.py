"""The assembly model: every part placed, the assembly STEP (tree, names, colours), overlap checks.

A :class:`PlacedPart` is a solid in its own frame plus a 4x4 placement (numpy, mm) into the
assembly frame of :mod:`geargen.pipeline` (output gear's centre at the origin, +x the symmetry
line towards the input, +z the gear axes). Per-part STEP/STL files are written in the assembly
frame, so they overlay into the assembly (each part's placement is in the manifest; its inverse
brings the part back to its own machining frame).

The non-gear parts are laid out by the drive's hardware (:func:`carriage_parts`,
:func:`beam_pinion_parts`, :func:`split_pinion_parts`) from the ``[parts]`` section (sizes the paper
does not give, written in the design file) and the stiffness step's sections (blade flexures,
springs, beam-spring pinion, shafts). Every contact that is meant to be there (a shaft in its
bore, a bearing on its shaft, a spring on its seat) is listed in ``intended_contacts``; the
overlap check fails on any other pair of parts that share volume.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable, Mapping

import numpy as np
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepGProp import BRepGProp
from OCP.Bnd import Bnd_Box
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Trsf
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Shape

from geargen.cad import parts as P
from geargen.cad.gear_solid import build_cluster, build_gear, solid_volume
from geargen.design.cluster import ClusterSpec
from geargen.design.parts import parts_settings
from geargen.errors import BuildError, DesignError
from geargen.units import MM_PER_IN

# ---------------------------------------------------------------- colours (r, g, b, alpha)

COLOURS: dict[str, tuple[float, float, float, float]] = {
    "gear": (0.72, 0.74, 0.78, 1.0),
    "gear_output": (0.55, 0.60, 0.70, 1.0),
    "gear_input": (0.85, 0.65, 0.30, 1.0),
    "gear_cluster": (0.45, 0.62, 0.80, 1.0),
    "bevel": (0.80, 0.55, 0.25, 1.0),
    "shaft": (0.35, 0.35, 0.38, 1.0),
    "bearing": (0.20, 0.45, 0.30, 1.0),
    "motor": (0.12, 0.12, 0.14, 1.0),
    "carriage": (0.78, 0.80, 0.84, 1.0),
    "flexure": (0.25, 0.35, 0.75, 1.0),
    "spring": (0.90, 0.78, 0.15, 1.0),
    "reference": (0.70, 0.70, 0.72, 0.25),
    "stop": (0.80, 0.20, 0.20, 1.0),
    "friction": (0.85, 0.35, 0.10, 1.0),
    "housing": (0.62, 0.64, 0.60, 0.35),
    "quill": (0.50, 0.54, 0.60, 1.0),
}


# ---------------------------------------------------------------- placements


def transform(translate=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), angle: float = 0.0) -> np.ndarray:
    """4x4 placement: a rotation by ``angle`` (rad) about ``axis`` through the origin, then a translation."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    c, s = math.cos(angle), math.sin(angle)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    r = np.eye(3) * c + s * k + (1 - c) * np.outer(a, a)
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = translate
    return m


def _trsf(m: np.ndarray) -> gp_Trsf:
    t = gp_Trsf()
    t.SetValues(*(float(v) for v in m[0]), *(float(v) for v in m[1]), *(float(v) for v in m[2]))
    return t


def location(m: np.ndarray) -> TopLoc_Location:
    """The kernel's location of the 4x4 placement ``m`` (mm)."""
    return TopLoc_Location(_trsf(m))


@dataclass
class PlacedPart:
    """A part: ``shape`` in its own frame, ``matrix`` (4, 4) into the assembly frame (mm).

    ``group`` is the sub-assembly it belongs to (the STEP tree), ``kind`` a colour key of
    :data:`COLOURS`, ``role`` what it is for the report ("gear", "reference", ...).
    """

    name: str
    shape: TopoDS_Shape
    matrix: np.ndarray
    group: str
    kind: str
    role: str = "part"
    description: str = ""
    solid: Any = None  # the GearSolid of a gear (profile, spec), for the checks
    notes: tuple[str, ...] = ()  # what building it reported (an undercut, ...), for the build's report
    # a simple solid holding the part (own frame): the overlap check's first, cheap test (a helical
    # spring's tube); gears have theirs from ``solid`` (:func:`part_envelope`)
    envelope: TopoDS_Shape | None = None
    _world: TopoDS_Shape | None = field(default=None, repr=False)

    @property
    def colour(self) -> tuple[float, float, float, float]:
        return COLOURS.get(self.kind, COLOURS["gear"])

    def world(self) -> TopoDS_Shape:
        """The part moved into the assembly frame (cached; it shares the geometry of ``shape``)."""
        if self._world is None:
            self._world = self.shape.Moved(location(self.matrix))
        return self._world


@dataclass
class PartSet:
    """All non-gear parts of an assembly (and, after :func:`all_parts`, the gears too)."""

    parts: list[PlacedPart]
    intended_contacts: list[tuple[str, str, str]]  # (part, part, why)
    notes: list[str] = field(default_factory=list)
    dimensions: dict[str, Any] = field(default_factory=dict)  # key sizes for the report (mm)
    # how the parts hold together (geargen.checks.structure): held by the machine (or supported
    # outside the model), never turning, turning besides the gears, contacts that roll (a mesh)
    ground: tuple[str, ...] = ()
    stationary: tuple[str, ...] = ()
    rotating: tuple[str, ...] = ()
    rolling: tuple[tuple[str, str], ...] = ()
    # meshing pairs among these parts (part, part, why): checked by their mesh checker, not the overlap check
    meshing: tuple[tuple[str, str, str], ...] = ()

    def part(self, name: str) -> PlacedPart:
        for p in self.parts:
            if p.name == name:
                return p
        raise KeyError(name)


# ---------------------------------------------------------------- gears


def gear_parts(layout, tolerance: float | None = None) -> dict[str, PlacedPart]:
    """Build every toothed part of ``layout`` (``geargen.pipeline.Layout``); identical specs are
    built once and placed as often as needed. ``tolerance`` (mm) is the gear builder's spline
    tolerance (None: its default). Returns parts by name."""
    import warnings
    cache: dict[Any, Any] = {}
    out: dict[str, PlacedPart] = {}
    for g in layout.gears:
        key = g.spec
        if key not in cache:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                if isinstance(g.spec, ClusterSpec):
                    solid = build_cluster(g.spec, tolerance)
                elif g.spec.kind == "internal":  # a planetary stage's ring
                    from geargen.cad.internal_solid import build_internal
                    solid = build_internal(g.spec, tolerance)
                elif getattr(g.spec, "kind", "external") == "external":
                    solid = build_gear(g.spec, tolerance)
                else:  # another family's part (the rack of a rack drive): its own builder
                    from geargen.cad.families import build_part
                    solid = build_part(g.spec)
            # undercut and the like: reported with the build, not printed
            cache[key] = (solid, tuple(dict.fromkeys(str(w.message) for w in caught)))
        solid, notes = cache[key]
        m = transform((g.centre[0], g.centre[1], g.z), (0, 0, 1), g.rotation)
        kind = "gear_output" if "output" in g.roles else "gear_input" if "input" in g.roles or \
            "pinion_stiff" in g.roles else "gear_cluster"
        desc = _gear_text(g.spec)
        out[g.name] = PlacedPart(g.name, solid.shape, m, g.group, kind, "gear", desc, solid,
                                 tuple(f"{g.name}: {n}" for n in notes))
    return out


def _gear_text(spec) -> str:
    if isinstance(spec, ClusterSpec):
        return f"cluster {spec.large.teeth}/{spec.small.teeth} T"
    helix = f", helix {math.degrees(spec.helix_angle):.4g} deg {spec.hand}" if spec.is_helical else ""
    return f"{spec.teeth} T, m_n {spec.module:.4g} mm{helix}, face {spec.face_width:.4g} mm"


# ---------------------------------------------------------------- the [parts] section

def non_gear_parts(layout, stiffness=None) -> PartSet:
    """The non-gear parts of ``layout``'s design, placed, with the intended contacts: built by
    the drive's hardware (:func:`geargen.design.parts.hardware_of`)."""
    s = parts_settings(layout.design)
    builder = {"carriage": carriage_parts, "beam_pinion": beam_pinion_parts, "split_pinion": split_pinion_parts}
    if s["hardware"] == "axial_preload":
        from geargen.cad.axial_parts import axial_preload_parts  # it imports this module's helpers
        return axial_preload_parts(layout, s, stiffness)
    if s["hardware"] == "rack_drive":
        from geargen.cad.rack_drive_parts import rack_drive_parts  # it imports this module's helpers
        return rack_drive_parts(layout, s, stiffness)
    return builder[s["hardware"]](layout, s, stiffness)


# ---------------------------------------------------------------- helpers


class _Parts:
    """Collects parts and contacts while the hardware lays them out."""

    def __init__(self):
        self.parts: list[PlacedPart] = []
        self.contacts: list[tuple[str, str, str]] = []
        self.notes: list[str] = []
        self.dims: dict[str, Any] = {}
        self._shapes: dict[tuple, Any] = {}
        self.ground: list[str] = []
        self.stationary: list[str] = []
        self.rotating: list[str] = []
        self.rolling: list[tuple[str, str]] = []
        self.meshing: list[tuple[str, str, str]] = []  # meshes among the parts (the bevel pair)

    def shared(self, builder, *args):
        """``builder(*args)``, built once per assembly: parts made alike (two bearings of one size,
        three blades) share one shape, which the assembly STEP writes as one product and the
        kernel meshes once."""
        key = (builder, args)
        if key not in self._shapes:
            self._shapes[key] = builder(*args)
        return self._shapes[key]

    def add(self, name, shape, matrix, group, kind, role="part", description="", envelope=None):
        self.parts.append(PlacedPart(name, shape, matrix, group, kind, role, description, envelope=envelope))
        return name

    def touch(self, a: str, b: str, why: str):
        self.contacts.append((a, b, why))

    def done(self) -> PartSet:
        fixed = [g for g in self.ground if g not in self.rotating] + self.stationary  # a spindle turns
        return PartSet(self.parts, self.contacts, self.notes, self.dims, tuple(self.ground),
                       tuple(dict.fromkeys(fixed)), tuple(self.rotating), tuple(self.rolling),
                       tuple(self.meshing))


def _at(x=0.0, y=0.0, z=0.0) -> np.ndarray:
    return transform((x, y, z))


def _along_x(x, y, z, towards_minus: bool = False) -> np.ndarray:
    """Local +z along world +x (or -x), local origin at (x, y, z)."""
    return transform((x, y, z), (0, 1, 0), -math.pi / 2 if towards_minus else math.pi / 2)


def _bore(spec) -> float:
    s = spec.large if isinstance(spec, ClusterSpec) else spec
    return s.hub.bore_diameter


# ---------------------------------------------------------------- robot joint (Fig. 10)


def carriage_parts(layout, s: Mapping[str, Any], stiffness=None) -> PartSet:
    """Motor, bevel pair, carriage on three blade flexures, two preload springs, shafts, bearings,
    and the link as a reference tray, around the gears of the robot joint (Fig. 10).

    Heights: the cluster's large gear from z = 0 (see :mod:`geargen.pipeline`). The carriage (a
    plate under the input gear, a post and an arm holding the input's upper bearing, a saddle
    for the motor, an end wall the springs push on) hangs on three vertical blades standing on
    the link's floor; the motor lies along +x, its bevel pinion driving the bevel gear on the
    input shaft. Bearings are rings a ``bearing_clearance`` from the gear faces; the lower ones
    of clusters and output stand by their outer rings on bosses of the link floor, relieved under
    the inner ring and the shaft end (the upper ones sit in the removed cover, as in the paper's
    figure).
    """
    from geargen.design.stiffness import stiffness_design
    from geargen.core.flexures import spring_total_coils

    design = layout.design
    sd = stiffness_design(design)
    if sd.flexures is None or sd.springs is None:
        raise DesignError("flexures", "the robot joint's carriage needs [flexures] and [springs]", "both sections")
    fl, sp = sd.flexures, sd.springs
    if sp.installed_length is None:
        raise DesignError("springs.installed_length", "missing (the springs' length in the model)", "a length")
    out = _Parts()
    g = {p.name: p for p in layout.gears}
    inp, outg = g["input"], g["output"]
    # each cluster: one part, or its large and small gear as two parts on one shaft
    members = {side: [p for p in layout.gears if p.group == f"cluster_{side}"] for side in ("a", "b")}
    clusters = [members["a"][0], members["b"][0]]
    gap = s["bearing_clearance"]
    x_in = inp.centre[0]

    # --- shafts and bearings, where the model places them (geargen.model.shafts: the stiffness reads the same)
    from geargen.model.shafts import carriage_arm_top, carriage_shafts
    placed_shafts = carriage_shafts(layout, s)

    def shaft_with_bearings(sh, group, what, gears, contact):
        part = out.add(sh.name, out.shared(P.shaft, sh.diameter, sh.length), _at(*sh.centre, sh.z_lo), group, "shaft",
                       description=what)
        for gear in gears:
            out.touch(part, gear, contact)
        for b in sh.bearings:
            ring = out.add(b.name, out.shared(P.bearing, b.bore, b.outer_diameter, b.width), _at(*sh.centre, b.z), group,
                           "bearing", description=f"{b.bore:.4g} x {b.outer_diameter:.4g} x {b.width:.4g} mm")
            out.touch(ring, part, "bearing on its shaft")
        return part

    for side in ("a", "b"):
        sh = placed_shafts[f"cluster_{side}"]
        shaft_with_bearings(sh, f"cluster_{side}", f"d {sh.diameter:.4g} mm", [m.name for m in members[side]],
                            "cluster gear on its shaft (pressed and bonded)")
    oshaft = shaft_with_bearings(placed_shafts["output"], "output", f"joint shaft d {placed_shafts['output'].diameter:.4g} mm",
                                 ["output"], "shaft in the output gear's bore")
    bw, bod = s["cluster_bearing_width"], s["cluster_bearing_outer_diameter"]
    zb_lo, zb_hi = (b.z for b in placed_shafts["cluster_a"].bearings)
    obw, obod = s["output_bearing_width"], s["output_bearing_outer_diameter"]
    zo_lo, zo_hi = (b.z for b in placed_shafts["output"].bearings)

    from geargen.design.stages import stages
    stage_list = stages(design)
    ish = placed_shafts["input"]
    ibod = s["input_bearing_outer_diameter"]
    d_in = _bore(inp.spec)
    t = s["carriage_plate_thickness"]
    half_w = s["carriage_width"] / 2
    z_plate_top = ish.supports()[0].z  # the lower bearing stands on the base plate
    z_plate_bot = z_plate_top - t
    z_arm_top = carriage_arm_top(ish, s)
    z_arm_bot = z_arm_top - t
    r_in = inp.gears[0].tip_radius
    post_x0 = x_in + max(r_in, ibod / 2) + gap
    post_x1 = post_x0 + t
    arm_half = max(ibod / 2 + gap, d_in)
    spring_r = (sp.mean_coil_diameter + sp.wire_diameter) / 2
    wall_half = s["spring_y_offset"] + spring_r + gap
    holes = []  # through the carriage: (x, y, diameter, z0, z1)
    if stage_list:
        drive = _stage_drive(out, layout, s, placed_shafts, stage_list, z_arm_top, post_x0, post_x1)
        pieces = drive["pieces"]
        holes += drive["holes"]
    else:
        drive = _bevel_drive(out, layout, s, ish, x_in, d_in, z_arm_top)
        pieces = [P.box_between((drive["saddle_x0"], -half_w * 0.6, z_plate_top),
                                (drive["x_end"] - gap, half_w * 0.6, drive["z_axis"] - drive["motor_r"]))]
    x_motor_end, z_top_parts = drive["x_end"], drive["z_top"]
    if "motor_mount" not in drive:  # else the drive's own part holds the motor
        out.touch("servo_motor", "carriage", "motor on its mount")
    # the input shaft and its bearings (placed by the model), up through the carriage arm to the
    # gear that drives it
    ishaft = out.add("input_shaft", out.shared(P.shaft, d_in, drive["input_top"] - ish.z_lo), _at(x_in, 0, ish.z_lo),
                     "carriage", "shaft", description=f"d {d_in:.4g} mm")
    out.touch(ishaft, "input", "shaft in the input gear's bore")
    for b in ish.bearings:
        ring = out.add(b.name, out.shared(P.bearing, b.bore, b.outer_diameter, b.width), _at(x_in, 0, b.z), "carriage",
                       "bearing", description=f"{b.bore:.4g} x {b.outer_diameter:.4g} x {b.width:.4g} mm")
        out.touch(ring, ishaft, "bearing on its shaft")

    # --- the carriage, one solid
    x_wall0 = x_motor_end + 2 * gap
    x_wall1 = x_wall0 + t
    z_wall_top = max(z_arm_top, spring_r + gap)
    x_arm1 = max([post_x1] + [p["x_end"] for p in drive.get("arm", ())])
    arm_y = max([arm_half] + [p["half"] for p in drive.get("arm", ())])
    pieces += [
        P.box_between((x_in - arm_half - t, -half_w, z_plate_bot), (x_wall0, half_w, z_plate_top)),  # base plate
        P.box_between((post_x0, -arm_half, z_plate_top), (post_x1, arm_half, z_arm_bot)),  # post
        P.box_between((x_in - arm_half, -arm_y, z_arm_bot), (x_arm1, arm_y, z_arm_top)),  # arm
        P.box_between((x_wall0, -wall_half, z_plate_bot), (x_wall1, wall_half, z_wall_top)),  # spring wall
    ]
    body = P.fuse(pieces, "carriage")
    # through the arm and the base plate under the input shaft: each bearing bears on the carriage by
    # its outer ring only (the hole reaches the ring's middle diameter), the turning shaft runs clear
    relief = max(P.ring_relief(ibod, d_in), d_in + 2 * gap)
    holes += [(x_in, 0.0, relief, z0, z1) for z0, z1 in ((z_arm_bot, z_arm_top), (z_plate_bot, z_plate_top))]
    body = P._single(P.cut(body, *[P.translate(P.cylinder(d, z1 - z0), (x, y, z0)) for x, y, d, z0, z1 in holes]),
                     "carriage")
    carriage = out.add("carriage", body, np.eye(4), "carriage", "carriage",
                       description="carries motor, " + ("stages" if stage_list else "bevel pair")
                                   + " and input gear; rides on the blades")
    for name in ("input_bearing_lower", "input_bearing_upper"):
        out.touch(name, carriage, "outer ring held by the carriage")

    # --- three blade flexures under the carriage, standing on the link floor
    z_floor = z_plate_bot - fl.length
    xs = np.linspace(x_in - arm_half, x_wall0 - 2 * gap, fl.count)
    for i, x in enumerate(xs, start=1):
        b = out.add(f"blade_flexure_{i}", out.shared(P.blade_flexure, fl.thickness, fl.length, fl.width), _at(x, 0, z_floor),
                    "flexures", "flexure", description=f"{fl.thickness:.4g} x {fl.width:.4g} x {fl.length:.4g} mm blade")
        out.touch(b, carriage, "blade clamped to the carriage")
        out.touch(b, "link", "blade clamped to the link floor")

    # --- two compression springs between the carriage's wall and the link's end wall
    coils = spring_total_coils(sp.active_coils, sp.end_type)
    tube = P.coil_envelope(sp.wire_diameter, sp.mean_coil_diameter, sp.installed_length)
    if s["spring_model"] == "helix":
        # the wire lies within the tube (its section, normal to the helix, stays within d/2 radially)
        spring_shape, spring_envelope = P.compression_spring(sp.wire_diameter, sp.mean_coil_diameter,
                                                             sp.installed_length, coils), tube
    else:
        spring_shape, spring_envelope = tube, None
    z_spring = (z_plate_bot + z_wall_top) / 2
    for i, y in enumerate((s["spring_y_offset"], -s["spring_y_offset"]), start=1):
        sp_name = out.add(f"preload_spring_{i}", spring_shape, _along_x(x_wall1, y, z_spring), "preload", "spring",
                          description=f"d {sp.wire_diameter:.4g} mm wire, D {sp.mean_coil_diameter:.4g} mm, "
                                      f"{coils:g} coils at {sp.installed_length:.4g} mm", envelope=spring_envelope)
        out.touch(sp_name, carriage, "spring seat on the carriage")
        out.touch(sp_name, "link", "spring seat on the link's end wall")

    # --- the link: a tray around everything, bosses under the lower bearings and shafts
    wall, floor = s["link_wall"], s["link_floor"]
    x_end_inner = x_wall1 + sp.installed_length
    length = x_end_inner + wall
    z_top = max(z_top_parts, zo_hi + obw, zb_hi + bw) + s["link_top_clearance"]
    z_bottom = z_floor - floor
    # each boss holds its bearing's outer ring: the relief keeps the inner ring and the rotating
    # shaft end clear of the stationary link
    d_os, d_cs = (placed_shafts[k].diameter for k in ("output", "cluster_a"))
    bosses = [(0.0, 0.0, obod, zo_lo - z_floor, P.ring_relief(obod, d_os))]
    bosses += [(c.centre[0], c.centre[1], bod, zb_lo - z_floor, P.ring_relief(bod, d_cs)) for c in clusters]
    radius = s["link_radius"]
    link = P.link_tray(radius, length, z_top - z_bottom, wall, floor, bosses)
    out.ground.append("link")
    out.stationary.append(carriage)
    out.add("link", link, _at(0, 0, z_bottom), "link", "reference", "reference",
            "robot link envelope (reference body, covers removed)")
    for name in ("output_bearing_lower", "cluster_bearing_lower_a", "cluster_bearing_lower_b"):
        out.touch(name, "link", "outer ring on a boss of the link floor")
    # --- the cover over the link's round end: seats for the upper bearings' outer rings, its rim on
    # the walls; it stops short of the bevel pinion and motor that rise above it
    uppers = [(placed_shafts[k], placed_shafts[k].supports()[-1]) for k in ("output", "cluster_a", "cluster_b")]
    z_cover = max(b.z + b.width for _, b in uppers)
    # parts the drive lays wholly above the cover (a planetary stage's) may overhang it
    over = set(drive.get("over_cover", ()))
    for p in out.parts:
        if p.name in over and not _bbox(p.world()).Get()[2] >= z_cover + floor:
            raise BuildError(f"{p.name} reaches down to the link cover (its top {z_cover + floor:.4g} mm)")
    x_end = min((_x_min_above(p.world(), z_cover, (-radius, -radius, z_bottom), (length, radius, z_top))
                 for p in out.parts if p.group == "carriage" and p.name not in over), default=length) - gap
    reach = max(sh.centre[0] + b.outer_diameter / 2 for sh, b in uppers)
    if not x_end > reach:
        key = "parts.stage_bearing_width" if stage_list else "parts.input_shaft_to_bevel"
        raise DesignError(key, f"the carriage rises above the upper bearings within {reach - x_end:.4g} mm of them: "
                          "no room for the link cover's seats",
                          "smaller cluster bearings" + ("" if stage_list else ", or a longer input_shaft_to_bevel"))
    seats = [(sh.centre[0], sh.centre[1], b.outer_diameter, z_cover - (b.z + b.width),
              P.ring_relief(b.outer_diameter, sh.diameter)) for sh, b in uppers]
    cover = out.add("link_cover", P.link_cover(radius, wall, x_end, floor, seats), _at(0, 0, z_cover), "link",
                    "housing", description="link cover over the round end: holds the upper bearings' outer rings")
    out.touch(cover, "link", "cover rim on the link's walls")
    out.ground.append(cover)
    for _, b in uppers:
        out.touch(cover, b.name, "outer ring in the cover's seat")
    out.dims.update(link=dict(radius=radius, length=length, height=z_top - z_bottom, wall=wall, floor=floor,
                              bosses=bosses, z_bottom=z_bottom, cover=dict(z=z_cover, x_end=x_end, seats=seats)),
                    carriage=dict(x_min=x_in - arm_half - t, x_max=x_wall1, travel=layout.carriage_travel),
                    blade_x=list(map(float, xs)), spring_total_coils=coils, **drive.get("dims", {}))
    out.notes.append(drive["note"])
    return out.done()


def _x_min_above(shape, z: float, lo, hi) -> float:
    """The smallest x of ``shape`` above height ``z`` within the box ``lo``..``hi`` (inf: none)."""
    above = BRepAlgoAPI_Common(shape, P.box_between((lo[0] - 1, lo[1] - 1, z), (hi[0] + 1, hi[1] + 1, hi[2] + 1))).Shape()
    box = _bbox(above)
    return math.inf if box.IsVoid() else box.Get()[0]


def _bevel_back_face(spec) -> float:
    """Distance from the apex, along the axis, of the plane through the heel's root circle: the
    toothed body of :func:`geargen.cad.bevel_solid.build_bevel` lies nearer the apex than it, only
    the blank's spherical back (inside the root cone) reaches beyond."""
    from geargen.core.bevel import bevel_geometry
    g = bevel_geometry(spec)
    return spec.cone_distance * math.cos(g.root_cone_angle)


def _bevel_part(spec):
    """A bevel gear's solid (apex at the origin, axis +z, the teeth on +z) with its back flat at
    :func:`_bevel_back_face` (the spherical cap behind the root circle is blank, not tooth: it
    would reach the parts behind the heel). When that leaves the axis bare (the toe sphere lies
    beyond the back face: a gear of large cone angle), a web joins the toothed ring to the bore:
    a disc from the middle of the face, (R_i + R_e)/2 cos delta_f from the apex, to the back
    face, its rim half way between the toe sphere and the root cone there, so it stays inside
    the root cone (no tooth surface is touched) and runs into the ring."""
    from geargen.cad.bevel_solid import build_bevel
    from geargen.core.bevel import bevel_geometry
    shape = build_bevel(spec, check=True).shape
    r = spec.cone_distance * 1.1
    back = _bevel_back_face(spec)
    ri, re = spec.toe_cone_distance, spec.cone_distance
    if ri >= back:
        root = bevel_geometry(spec).root_cone_angle
        a0 = (ri + re) / 2 * math.cos(root)
        rim = (math.sqrt(ri * ri - a0 * a0) + a0 * math.tan(root)) / 2
        web = P.translate(P.cylinder(2 * rim, r - a0, spec.bore_diameter), (0, 0, a0))
        shape = P.fuse([shape, web], spec.name)
    return P._single(P.cut(shape, P.box(2 * r, 2 * r, r, (-r, -r, back))), spec.name)


def _bevel_drive(out: _Parts, layout, s: Mapping[str, Any], ish, x_in: float, d_in: float,
                 z_arm_top: float) -> dict[str, Any]:
    """The motor lying along +x on the carriage, driving the input shaft through a toothed bevel
    pair (the robot joint, Fig. 10): the bevel gear's heel (pitch circle) ``input_shaft_to_bevel``
    above the input's mid-face (the placed input shaft's load), the two apexes at the pitch cones'
    common apex, the motor's stub ending on the pinion's back face. The pinion's teeth sit in the
    middle of the gear's spaces (the pair's backlash split to both sides); the pair is a mesh,
    checked on the exact outlines (:func:`geargen.checks.bevel_placed.check_placed_bevel_pair`)."""
    from geargen.model.bevel_drive import bevel_drive
    placed = bevel_drive(layout, dict(s))
    gear_spec, pinion_spec = placed.gear, placed.pinion
    module = s["bevel_module"] or 25.4 / s["bevel_diametral_pitch_per_in"]
    bev = P.bevel_pair_geometry(s["bevel_pinion_teeth"], s["bevel_gear_teeth"], module, s["bevel_face_width"])
    gap = s["bearing_clearance"]
    z_heel = ish.loads["bevel_gear"]
    z_apex = z_heel + bev.apex_height("gear")
    apex = (x_in, 0.0, z_apex)
    # one home: the toothed gears' cones and apex are the pitch-cone model's
    for spec, which in ((gear_spec, "gear"), (pinion_spec, "pinion")):
        radius, cone = bev._cone(which)
        if abs(spec.pitch_cone_angle - cone) > 1e-12 or abs(spec.reference_diameter / 2 - radius) > 1e-9 \
                or abs(spec.cone_distance - bev.cone_distance) > 1e-9:
            raise BuildError(f"{spec.name}: its cones differ from the bevel pair's pitch cones")
    if not np.allclose(placed.apex, apex, rtol=0, atol=1e-9) or abs(placed.z_heel - z_heel) > 1e-9:
        raise BuildError("bevel pair: the placed apex is not the pitch cones' apex")
    if not math.isclose(gear_spec.bore_diameter, d_in):
        raise BuildError("bevel gear: its bore is not the input shaft")
    # the gear's back face (its heel root circle's plane) must clear the carriage arm under it
    lowest = z_arm_top + gap + (_bevel_back_face(gear_spec) - bev.apex_height("gear"))
    if z_heel < lowest - 1e-9:
        shift = (lowest - z_heel) / (MM_PER_IN if layout.design.length_unit == "in" else 1.0)
        raise DesignError("parts.input_shaft_to_bevel", f"puts the bevel gear's back (its heel root circle) into the "
                          f"carriage arm under it", f"at least {shift:.4g} {layout.design.length_unit} more")
    gear_shape, pinion_shape = _bevel_part(gear_spec), _bevel_part(pinion_spec)
    gear_matrix, pinion_matrix = placed.gear_matrix, placed.pinion_matrix
    bevel_gear = out.add("bevel_gear", gear_shape, gear_matrix, "carriage", "bevel",
                         description=f"bevel gear {bev.gear_teeth} T, pitch cone {math.degrees(bev.pitch_angle_gear):.4g} deg, "
                                     f"spherical involute")
    pinion = out.add("bevel_pinion", pinion_shape, pinion_matrix, "carriage", "bevel",
                     description=f"bevel pinion {bev.pinion_teeth} T, pitch cone {math.degrees(bev.pitch_angle_pinion):.4g} deg, "
                                 f"spherical involute")
    out.meshing.append((bevel_gear, pinion, "meshing bevel gears: checked by the bevel mesh checker"))
    out.touch("input_shaft", bevel_gear, "shaft in the bevel gear's bore")
    out.rolling.append((bevel_gear, pinion))
    out.rotating += [bevel_gear, pinion]
    # motor along +x, its stub ending on the pinion's back face
    stub = s["motor_shaft_length"]
    x_pinion_back = x_in + _bevel_back_face(pinion_spec)
    x_flange = x_pinion_back + stub
    motor_r = s["motor_body_diameter"] / 2
    motor = out.add("servo_motor", P.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], s["motor_shaft_diameter"], stub),
                    _along_x(x_flange, 0, z_apex), "carriage", "motor", description="servo motor with encoder (envelope)")
    out.touch(motor, pinion, "motor shaft stub on the bevel pinion")
    x_end = x_flange + s["motor_flange_thickness"] + s["motor_body_length"]
    # the input shaft fills the gear's bore up to the toe, or its web's face
    rb = d_in / 2
    back = _bevel_back_face(gear_spec)
    if gear_spec.toe_cone_distance >= back:
        from geargen.core.bevel import bevel_geometry
        input_top = z_apex - (gear_spec.toe_cone_distance + gear_spec.cone_distance) / 2 \
            * math.cos(bevel_geometry(gear_spec).root_cone_angle)
    else:
        input_top = z_apex - math.sqrt(gear_spec.toe_cone_distance ** 2 - rb * rb)
    return dict(x_end=x_end, z_axis=z_apex, motor_r=motor_r, z_top=z_apex + motor_r,
                saddle_x0=x_flange + s["motor_flange_thickness"] + gap, input_top=input_top,
                dims=dict(bevel=bev, bevel_apex=apex),
                note=f"bevel pair {bev.pinion_teeth}:{bev.gear_teeth} (ratio {bev.ratio:.4g}), spherical-involute "
                     f"teeth, thinning {gear_spec.thinning:.4g} mm each; "
                     f"motor to output ratio {bev.ratio * layout.ratio['train']:.6g}")


def _stage_drive(out: _Parts, layout, s: Mapping[str, Any], placed_shafts, stage_list, z_arm_top: float,
                 post_x0: float, post_x1: float) -> dict[str, Any]:
    """The motor standing on the carriage's bridge, driving the input through the design's
    [stages]: each stage shaft between a lower bearing standing on the carriage arm (extended
    under it) and an upper one under the bridge; two side columns on the base plate carry the
    bridge clear of every stage gear; the first driver sits on the motor's shaft, which comes
    down through the bridge."""
    if stage_list[-1].kind == "planetary":
        from geargen.cad.planetary_parts import planetary_drive
        return planetary_drive(out, layout, s, placed_shafts, stage_list[-1], post_x0)
    gap, t = s["bearing_clearance"], s["carriage_plate_thickness"]
    g = {p.name: p for p in layout.gears}
    shafts = [placed_shafts[k] for k in sorted(k for k in placed_shafts if k.startswith("stage_"))]
    sob, sbw = s["stage_bearing_outer_diameter"], s["stage_bearing_width"]
    for sh in shafts:
        part = out.add(sh.name, out.shared(P.shaft, sh.diameter, sh.length), _at(*sh.centre, sh.z_lo), "carriage",
                       "shaft", description=f"stage shaft d {sh.diameter:.4g} mm")
        for gear in sh.loads:
            out.touch(part, gear, "stage gear on its shaft")
        for b in sh.bearings:
            ring = out.add(b.name, out.shared(P.bearing, b.bore, b.outer_diameter, b.width), _at(*sh.centre, b.z),
                           "carriage", "bearing", description=f"{b.bore:.4g} x {b.outer_diameter:.4g} x {b.width:.4g} mm")
            out.touch(ring, part, "bearing on its shaft")
            out.touch(ring, "carriage", "outer ring seated on the carriage")
    out.touch("input_shaft", stage_list[-1].driven, "shaft in the driving stage gear's bore")
    # the motor on the bridge, its shaft down through it into the first driver's bore
    first = g[stage_list[0].driver]
    d_motor = _bore(first.spec)
    if not d_motor > 0:
        raise DesignError(f"gears.{first.name}.bore_diameter", "missing: the gear sits on the motor shaft", "> 0")
    gears_top = max(g[n].height[1] for st in stage_list for n in (st.driver, st.driven))
    z_bridge0 = gears_top + gap + sbw
    z_bridge1 = z_bridge0 + t
    stub = z_bridge1 - first.height[0]
    motor = out.add("servo_motor", P.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], d_motor, stub),
                    _at(*first.centre, z_bridge1), "carriage", "motor",
                    description="servo motor with encoder (envelope), standing on the carriage's bridge")
    out.touch(motor, first.name, "first stage driver on the motor shaft")
    # the stage gears' reach: the columns stand outside it, the bridge and arm reach the shafts
    stage_gears = [g[n] for st in stage_list for n in (st.driver, st.driven)]
    reach_y = max(abs(p.centre[1]) + p.gears[0].tip_radius for p in stage_gears)
    y_col = reach_y + gap
    xs = [sh.centre[0] for sh in shafts] + [first.centre[0]]
    r_seat = max(sob, s["motor_flange"]) / 2 + gap
    # the columns rise beside the stage gears from the base plate, past the loop's gears (beyond
    # their tips along +x)
    x_col = max([post_x0] + [p.centre[0] + p.gears[0].tip_radius + gap for p in layout.gears
                             if p.group.startswith("cluster_") or p.group == "output"])
    x_b0, x_b1 = min(min(xs) - r_seat, x_col), max(xs) + r_seat
    half = y_col + t
    pieces = [P.box_between((x_b0, -half, z_bridge0), (x_b1, half, z_bridge1))]  # bridge
    z_plate_top = placed_shafts["input"].supports()[0].z
    for sign in (1, -1):
        y0, y1 = sorted((sign * y_col, sign * half))
        pieces.append(P.box_between((x_col, y0, z_plate_top - t), (x_col + t, y1, z_bridge0)))
    # the base plate reaches out under the columns only (the loop's bearing bosses stand beside it)
    pieces.append(P.box_between((x_col, -half, z_plate_top - t), (x_col + t, half, z_plate_top)))
    holes = [(sh.centre[0], sh.centre[1], P.ring_relief(sob, sh.diameter), z_arm_top - t, z_arm_top) for sh in shafts]
    holes += [(sh.centre[0], sh.centre[1], P.ring_relief(sob, sh.diameter), z_bridge0, z_bridge1) for sh in shafts]
    holes.append((first.centre[0], first.centre[1], d_motor + 2 * gap, z_bridge0, z_bridge1))
    arm = [dict(x_end=max(sh.centre[0] for sh in shafts) + sob / 2 + gap if shafts else post_x1,
                half=max([abs(sh.centre[1]) + sob / 2 + gap for sh in shafts], default=0.0))]
    ratio = layout.ratio
    return dict(pieces=pieces, holes=holes, arm=arm, x_end=x_b1, z_top=z_bridge1,
                input_top=g[stage_list[-1].driven].height[1],
                note=f"{len(stage_list)} stage(s) before the input on the carriage ({ratio['text']})")


# ---------------------------------------------------------------- C-axis (Fig. 12)


def beam_pinion_parts(layout, s: Mapping[str, Any], stiffness=None) -> PartSet:
    """Spindle stub, the long beam-spring pinion with its shaft, bearings, coupling, gearhead and
    motor, and per dual pinion: its shaft, two bearings in a sliding quill, the frictional preload
    interface (a locking ring clamping the large gear to the shaft), a locknut on the bearings'
    inner rings, and the engaged and retracted travel stops that meet the quill's lug; the
    housing block the quills slide in (the ground), and the drive column bolted to it that
    carries the long pinion's bearing plates and the motor plate.

    Heights: the pinions engage the bull gear moving along +z and slide out along -z, away from
    it (the large gears stay in mesh with the long pinion). The long pinion's bearings are
    symmetric about its engaged mesh (zero slope there) at the span the beam-spring helper
    sized (``StiffnessSummary.beam``); the stops come from the engagement helper (lead and
    strokes, ``StiffnessSummary.engagement``). The housing block's top is a clearance below the
    lowest a large gear comes (the trailer retracted); the quills reach down through it to their
    lugs, which play between the stops under it.
    """
    from geargen.core.stiffness import stiffness_summary

    design = layout.design
    summary = stiffness if stiffness is not None else stiffness_summary(design)
    beam = summary.beam
    eng = layout.engagement if layout.engagement is not None else summary.engagement
    if beam is None or eng is None:
        raise DesignError("beam_pinion", "the C-axis needs [beam_pinion] (the long pinion) and [engagement]",
                          "both sections")
    out = _Parts()
    g = {p.name: p for p in layout.gears}
    inp, bull = g["input"], g["output"]
    gap = s["bearing_clearance"]
    x_in = inp.centre[0]

    # --- spindle stub through the bull gear
    z_b0, z_b1 = bull.height
    d_sp = _bore(bull.spec)
    sp_len = s["spindle_length"]
    spindle = out.add("spindle", out.shared(P.shaft, d_sp, sp_len), _at(0, 0, (z_b0 + z_b1 - sp_len) / 2), "spindle",
                      "reference", "reference", f"lathe spindle (reference), d {d_sp:.4g} mm")
    out.touch(spindle, "output", "bull gear on the spindle")
    out.ground.append(spindle)  # turns in the machine's own spindle bearings, outside the model
    out.rotating.append(spindle)

    # --- the long pinion: bearings at the beam span, symmetric about the engaged mesh
    from geargen.model.shafts import beam_pinion_shafts, housing_heights
    span = beam.span
    d_ish = s["input_shaft_diameter"]
    if not math.isclose(d_ish, _bore(inp.spec)):
        raise DesignError("parts.input_shaft_diameter_mm", "must equal the long pinion's bore", f"{_bore(inp.spec):.6g} mm")
    ibw, ibod = s["input_bearing_width"], s["input_bearing_outer_diameter"]
    placed_shafts = beam_pinion_shafts(layout, s)
    placed_input = placed_shafts["input"]
    z_mesh = placed_input.loads["input"]
    cl = s["coupling_length"]
    ish_lo, ish_hi = placed_input.z_lo, placed_input.z_hi
    ishaft = out.add("input_shaft", out.shared(P.shaft, d_ish, ish_hi - ish_lo), _at(x_in, 0, ish_lo), "drive", "shaft",
                     description=f"long pinion's shaft d {d_ish:.4g} mm, bearing span {span:.4g} mm (beam spring)")
    out.touch(ishaft, "input", "pinion teeth on their shaft")
    input_bearings = []
    for bearing in placed_input.supports():
        b = out.add(bearing.name, out.shared(P.bearing, d_ish, ibod, ibw), _at(x_in, 0, bearing.z), "drive", "bearing",
                    description=f"{d_ish:.4g} x {ibod:.4g} x {ibw:.4g} mm, simple support of the beam at "
                                f"z = {bearing.centre_z:.5g} mm")
        out.touch(b, ishaft, "bearing on its shaft")
        input_bearings.append((b, bearing.z))
    z_lo_bearing = placed_input.supports()[0].z
    # coupling (half on the shaft), gearhead (the exact upstream ratio), motor with the encoder
    zc = ish_hi - cl / 2
    coupling = out.add("coupling", P.cylinder(s["coupling_diameter"], cl, d_ish), _at(x_in, 0, zc), "drive", "shaft",
                       description="shaft coupling (bored for the pinion shaft, which fills half its length)")
    out.touch(coupling, ishaft, "coupling on the pinion shaft")
    zg = zc + cl
    stages = " x ".join(f"{b}:{a}" for a, b in layout.settings.get("upstream_stages", ()))
    gearhead = out.add("gearhead", P.cylinder(s["gearhead_diameter"], s["gearhead_length"]), _at(x_in, 0, zg), "drive",
                       "motor", description=f"planetary gearhead {stages}")
    out.touch(gearhead, coupling, "gearhead output in the coupling")
    # gearhead and motor both bolt to the motor plate, from below and above; the motor's shaft reaches
    # through the plate into the gearhead's input. Each is a joint between the plate (its housing) and
    # what it turns: the gearhead the coupling, the motor the gearhead's input
    z_plate = zg + s["gearhead_length"]
    t_plate = s["motor_plate_thickness"]
    d_stub = d_ish * 0.5
    motor = out.add("servo_motor", P.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], d_stub, t_plate),
                    _at(x_in, 0, z_plate + t_plate), "drive", "motor", description="servo motor with the C-axis encoder")
    out.touch(motor, gearhead, "motor shaft in the gearhead's input")

    # --- the housing block's heights: its top a clearance below the lowest a large gear comes (the
    # trailer retracted), its thickness the length of the bores the quills slide in
    clusters = {side: (g[f"cluster_small_{side}"], g[f"cluster_large_{side}"],
                       layout.axial_shift.get(f"cluster_{side}", 0.0)) for side in ("a", "b")}
    z_block, z_block_top = housing_heights(layout, s, eng)
    strokes = {"a": -eng.leader_retracted_stop, "b": -eng.trailer_retracted_stop}

    # --- each dual pinion: shaft, bearings, quill, stops
    d_cs = s["cluster_shaft_diameter"]
    d_quill = s["quill_outer_diameter"]
    lug, lug_w, lug_t, block = s["stop_lug_length"], s["stop_lug_width"], s["stop_lug_thickness"], s["stop_block_size"]
    hole = max(ibod, 2 * inp.gears[0].tip_radius) + 2 * gap  # the long pinion (and its bearing) pass the block
    for small, _, _ in clusters.values():
        wall = math.hypot(small.centre[0] - x_in, small.centre[1]) - (d_quill + hole) / 2
        if not wall > 0:
            raise DesignError("parts.quill_outer_diameter_mm", f"{d_quill:.6g} mm: the quill's bore in the housing "
                              f"block runs {-wall:.4g} mm into the hole the long pinion passes",
                              f"< {d_quill + 2 * wall:.6g} mm")
    quills = []
    for side, (small, large, shift) in clusters.items():
        for part in (small, large):
            if not math.isclose(_bore(part.spec), d_cs):
                raise DesignError("parts.cluster_shaft_diameter_mm", f"must equal the bore of {part.name}",
                                  f"{_bore(part.spec):.6g} mm")
        x, y = small.centre
        zl1 = large.height[1]
        ring_w = s["friction_ring_width"]
        ring = out.add(f"friction_ring_{side}", P.cylinder(s["friction_ring_outer_diameter"], ring_w, d_cs),
                       _at(x, y, zl1), f"cluster_{side}", "friction",
                       description="frictional preload interface: locking ring clamping the large gear to the "
                                   "pinion shaft (released, turned to wind the loop, clamped)")
        out.touch(ring, large.name, "frictional interface on the large gear")
        # shaft and quill bearings where the model places them (the stiffness reads the same)
        sh = placed_shafts[f"cluster_{side}"]
        shaft = out.add(sh.name, out.shared(P.shaft, sh.diameter, sh.length), _at(x, y, sh.z_lo), f"cluster_{side}",
                        "shaft", description=f"dual pinion shaft d {sh.diameter:.4g} mm (slides with the pinion)")
        for part in (small.name, large.name, ring):
            out.touch(shaft, part, "on the pinion shaft")
        for b in sh.bearings:
            ring_b = out.add(b.name, out.shared(P.bearing, b.bore, b.outer_diameter, b.width), _at(x, y, b.z),
                             f"cluster_{side}", "bearing",
                             description=f"{b.bore:.4g} x {b.outer_diameter:.4g} x {b.width:.4g} mm in the sliding quill")
            out.touch(ring_b, shaft, "bearing on its shaft")
        lower, upper = sh.supports()
        nut = out.add(f"locknut_{side}", out.shared(P.cylinder, s["locknut_outer_diameter"], s["locknut_width"], d_cs),
                      _at(x, y, sh.z_lo), f"cluster_{side}", "shaft",
                      description="locknut clamping the bearings' inner rings to the shaft")
        out.touch(nut, shaft, "locknut on the shaft")
        out.touch(nut, lower.name, "locknut against the lower bearing's inner ring")
        # The quill holds both outer rings (a shoulder between them, the shaft and inner rings clear
        # by the ring relief) and slides in the housing block without turning. The travel stops act
        # on a lug of the quill: stop and lug are both stationary in rotation, so the stops need no
        # thrust bearing (a lug on the turning shaft would rub on them at speed, or need a collar and
        # a thrust bearing to hold the quill); the angular-contact pair already carries the axial
        # force between shaft and quill.
        z_top = upper.z + upper.width
        z_lug_engaged = z_block - block - lug_t  # the lug's lower face, engaged: its top on the engaged stop
        z_bottom = z_lug_engaged + shift
        relief = P.ring_relief(lower.outer_diameter, d_cs)
        steps = [(0.0, lower.z + lower.width - z_bottom, lower.outer_diameter),
                 (lower.z + lower.width - z_bottom, upper.z - z_bottom, relief),
                 (upper.z - z_bottom, z_top - z_bottom, upper.outer_diameter)]
        # the lug points away from the long pinion: its stops stay clear of the drive line
        direction = math.atan2(y, x - x_in)
        quill = out.add(f"quill_{side}", P.quill(d_quill, z_top - z_bottom, [st for st in steps if st[1] > st[0]], lug,
                                                 lug_w, lug_t),
                        transform((x, y, z_bottom), (0, 0, 1), direction), f"cluster_{side}", "quill",
                        description=f"quill {d_quill:.4g} mm, {z_top - z_bottom:.4g} mm long: holds both bearings' "
                                    "outer rings, slides in the housing block, its lug between the travel stops")
        for b in (lower, upper):
            out.touch(quill, b.name, "outer ring seated in the quill")
        out.touch(quill, "housing", "quill in the housing block's bore (a sliding fit; the quill does not turn)")
        out.stationary.append(quill)
        quills.append((x, y))
        out.dims.setdefault("quills", {})[side] = dict(z=(z_bottom, z_top), steps=steps, direction=direction)
        # the stops, in the quill's frame at the engaged position: the engaged stop a block under the
        # housing over the lug's end; the retracted stop a foot under the lug on a column just beyond
        # the lug's end, up to the housing
        place = transform((x, y, 0.0), (0, 0, 1), direction)
        x_end = d_quill / 2 + lug
        engaged_stop = out.add(f"travel_stop_engaged_{side}",
                     P.box_between((x_end - block, -block / 2, z_block - block), (x_end, block / 2, z_block)),
                     place, "housing", "stop", description="engaged travel stop under the housing block: the "
                                                           "pinion fully in mesh")
        z_foot = z_lug_engaged - strokes[side]
        foot_and_column = P.fuse([P.box_between((x_end - block, -block / 2, z_foot - block),
                                                (x_end + gap + block, block / 2, z_foot)),
                                  P.box_between((x_end + gap, -block / 2, z_foot), (x_end + gap + block, block / 2, z_block))],
                                 "retracted stop")
        retracted_stop = out.add(f"travel_stop_retracted_{side}", foot_and_column, place, "housing", "stop",
                     description=f"retracted travel stop, stroke {strokes[side]:.4g} mm"
                                 + (f" (the trailing pinion: {eng.lead:.4g} mm lead further)" if side == "b" else ""))
        out.touch(quill, engaged_stop if shift == 0 else retracted_stop, "the quill's lug against its travel stop")
        out.touch(engaged_stop, "housing", "stop bolted under the housing block")
        out.touch(retracted_stop, "housing", "stop's column bolted under the housing block")
        out.stationary += [engaged_stop, retracted_stop]

    # --- the drive column beside the long pinion, a clearance beyond the drive line and the large gears
    width, thick = s["drive_column_width"], s["drive_column_thickness"]
    margin = s["housing_margin"]
    reach = max(s["coupling_diameter"], s["gearhead_diameter"], ibod, 2 * inp.gears[0].tip_radius) / 2 + gap
    large_reach = max(large.centre[0] + large.gears[0].tip_radius for _, large, _ in clusters.values()) + gap
    x_col = max(x_in + width / 2, x_in + hole / 2 + margin, x_in + reach, large_reach)
    column = out.add("drive_column", P.box_between((x_col, -width / 2, z_lo_bearing), (x_col + thick, width / 2, z_plate)),
                     np.eye(4), "housing", "housing",
                     description="column bolted to the housing block: carries the long pinion's bearing plates and "
                                 "the motor plate")
    out.touch(column, "housing", "column bolted to the housing block's end")
    # the long pinion's bearings seated in plates on the column (each as thick as its bearing)
    for b, z in input_bearings:
        plate = out.add(f"{b}_plate", P.plate_with_holes(x_col - (x_in - width / 2), width, ibw, [(x_in, 0.0, ibod)],
                                                         corner=(x_in - width / 2, -width / 2, z)),
                        np.eye(4), "housing", "housing", description="bearing plate on the drive column")
        out.touch(plate, b, "outer ring seated in the plate")
        out.touch(plate, column, "plate bolted to the column")
        out.stationary.append(plate)
    flange = max(width, s["motor_flange"], s["gearhead_diameter"])
    x_plate1 = max(x_col + thick, x_in + flange / 2)
    mplate = out.add("motor_plate", P.plate_with_holes(x_plate1 - (x_in - flange / 2), flange, t_plate,
                                                       [(x_in, 0.0, d_stub + 2 * gap)],
                                                       corner=(x_in - flange / 2, -flange / 2, z_plate)),
                     np.eye(4), "housing", "housing", description="motor plate on the drive column: the gearhead hangs "
                                                                  "under it, the motor stands on it")
    out.touch(mplate, column, "plate on the column's top")
    out.touch(gearhead, mplate, "gearhead housing bolted under the motor plate")
    out.touch(motor, mplate, "motor flange bolted on the motor plate")
    out.stationary += [column, mplate]

    # --- the housing block: the quills' bores, the long pinion's hole, over the stops; it ends at the column
    holes = [(x, y, d_quill) for x, y in quills] + [(x_in, 0.0, hole)]
    boxes = [((hx - hd / 2, hy - hd / 2), (hx + hd / 2, hy + hd / 2)) for hx, hy, hd in holes]
    boxes += [P.bounding_box(p.world()) for p in out.parts if p.kind == "stop"]
    lo = (float(min(b[0][0] for b in boxes)) - margin, float(min(b[0][1] for b in boxes)) - margin, z_block)
    hi = (x_col, float(max(b[1][1] for b in boxes)) + margin, z_block_top)
    housing = P.plate_with_holes(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], holes, corner=lo)
    out.ground.append("housing")
    out.add("housing", housing, np.eye(4), "housing", "housing",
            description="C-axis housing block, bolted to the headstock: the quills slide in its bores, the stops hang under it")
    out.dims.update(beam=beam, engagement=eng, z_mesh=z_mesh, housing=dict(lo=lo, hi=hi),
                    drive_column=dict(x=x_col, width=width, thickness=thick, z=(z_lo_bearing, z_plate)))
    out.notes.append(f"long pinion: bearing span {span:.4g} mm symmetric about the engaged mesh at z = {z_mesh:.4g} mm "
                     f"(zero slope there), beam stiffness {beam.stiffness:.4g} N/mm; static deflection at the preload "
                     f"{beam.deflection * 1e3:.3g} um (the model shows the straight beam)")
    out.notes.append(f"axial engagement: lead {eng.lead:.4g} mm between the pinions, strokes "
                     f"{-eng.leader_retracted_stop:.4g} / {-eng.trailer_retracted_stop:.4g} mm, relative rotation "
                     f"{eng.relative_rotation * 1e3:.3g} mrad")
    return out.done()


# ---------------------------------------------------------------- split pinion (Fig. 8)


def split_pinion_parts(layout, s: Mapping[str, Any], stiffness=None) -> PartSet:
    """The concentric Type 1 drive of Fig. 8: the stiff pinion on a hollow shaft (outer path), the
    compliant pinion on the inner shaft that runs through it from the clamp collar (the frictional
    interface where preload is set) to an outboard bearing, a preloaded bearing pair on the
    hollow shaft, the output shaft and bearings, and the housing's two plates that hold every
    bearing.

    Shafts and bearings stand where :func:`geargen.model.shafts.split_pinion_shafts` places them:
    the stiffness model reads the same shafts (the inner shaft's torsion, each pinion's support).
    """
    from geargen.model.shafts import split_pinion_shafts

    out = _Parts()
    g = {p.name: p for p in layout.gears}
    st = layout.settings
    stiff, compl, outg = g[st["pinion_stiff"]], g[st["pinion_compliant"]], g[st["output"]]
    gap = s["bearing_clearance"]
    if not _bore(stiff.spec) == s["hollow_shaft_outer_diameter"]:
        raise DesignError("parts.hollow_shaft_outer_diameter", "must equal the stiff pinion's bore",
                          f"{_bore(stiff.spec):.6g} mm")
    placed = split_pinion_shafts(layout, s)
    hollow, inner = placed["hollow"], placed["inner"]
    x_p = hollow.centre[0]
    hollow_part = out.add("hollow_shaft", out.shared(P.shaft, hollow.diameter, hollow.length, hollow.bore),
                          _at(x_p, 0, hollow.z_lo), "split_pinion", "shaft",
                          description=f"outer (stiff) path: hollow shaft {hollow.diameter:.4g}/{hollow.bore:.4g} mm")
    out.touch(hollow_part, stiff.name, "stiff pinion on the hollow shaft")
    for b in hollow.bearings:
        name = out.add(b.name, out.shared(P.bearing, b.bore, b.outer_diameter, b.width), _at(x_p, 0, b.z),
                       "split_pinion", "bearing", description=f"angular-contact pair (preloaded), {b.bore:.4g} x "
                                                              f"{b.outer_diameter:.4g} x {b.width:.4g} mm")
        out.touch(name, hollow_part, "bearing on the hollow shaft")
    collar, outboard = inner.supports()
    collar_part = out.add(collar.name, P.split_collar(collar.bore, collar.outer_diameter, collar.width, s["collar_slot"]),
                          _at(x_p, 0, collar.z), "split_pinion", "friction",
                          description="frictional interface: clamp collar joining the inner shaft to the hollow shaft; "
                                      "set screws wind the inner shaft before clamping")
    out.touch(collar_part, hollow_part, "collar against the hollow shaft's end")
    inner_part = out.add("inner_shaft", out.shared(P.shaft, inner.diameter, inner.length), _at(x_p, 0, inner.z_lo),
                         "split_pinion", "shaft",
                         description=f"inner (compliant) path: d {inner.diameter:.4g} mm, twisting over "
                                     f"{inner.twist_length:.4g} mm, collar to compliant pinion")
    out.touch(inner_part, collar_part, "clamped in the collar")
    out.touch(inner_part, compl.name, "compliant pinion on the inner shaft")
    top = out.add(outboard.name, out.shared(P.bearing, outboard.bore, outboard.outer_diameter, outboard.width),
                  _at(x_p, 0, outboard.z), "split_pinion", "bearing",
                  description=f"outboard bearing of the compliant pinion, {outboard.bore:.4g} x "
                              f"{outboard.outer_diameter:.4g} x {outboard.width:.4g} mm")
    out.touch(top, inner_part, "bearing on the inner shaft")
    out.dims["inner_shaft"] = dict(diameter=inner.diameter, twist_length=inner.twist_length)
    # output shaft and bearings: the lower one level with the pinion pair's upper bearing, the upper
    # one level with the outboard bearing, so that one plate holds each level
    d_os = _bore(outg.spec)
    obw, obod = s["output_bearing_width"], s["output_bearing_outer_diameter"]
    zo0, zo1 = outg.height
    z_low, z_high = zo0 - gap - obw, max(zo1 + gap, outboard.z)
    oshaft = out.add("output_shaft", out.shared(P.shaft, d_os, z_high + obw - z_low), _at(0, 0, z_low),
                     "output", "shaft", description=f"d {d_os:.4g} mm")
    out.touch(oshaft, outg.name, "output gear on its shaft")
    output_bearings = {}
    for where, z in (("lower", z_low), ("upper", z_high)):
        output_bearings[where] = out.add(f"output_bearing_{where}", out.shared(P.bearing, d_os, obod, obw),
                                         _at(0, 0, z), "output", "bearing",
                                         description=f"{d_os:.4g} x {obod:.4g} x {obw:.4g} mm")
        out.touch(output_bearings[where], oshaft, "bearing on its shaft")
    # the housing: a bottom plate holding the pinion pair and the lower output bearing, a top plate
    # holding the outboard and the upper output bearing (both fixed to the machine: the ground)
    margin = s["housing_margin"]
    lo_pair = min(b.z for b in hollow.bearings)
    hi_pair = max(b.z + b.width for b in hollow.bearings)
    pair_od = max(b.outer_diameter for b in hollow.bearings)
    plates = (("bottom_plate", lo_pair, hi_pair - lo_pair, pair_od, [*hollow.bearings], output_bearings["lower"]),
              ("top_plate", outboard.z, outboard.width, outboard.outer_diameter, [outboard], output_bearings["upper"]))
    for name, z, thickness, od_pinion, held, held_output in plates:
        half_y = max(od_pinion, obod) / 2 + margin
        x0, x1 = -obod / 2 - margin, x_p + od_pinion / 2 + margin
        plate = out.add(name, P.plate_with_holes(x1 - x0, 2 * half_y, thickness, [(0.0, 0.0, obod), (x_p, 0.0, od_pinion)],
                                                 corner=(x0, -half_y, 0.0)), _at(0, 0, z), "housing", "housing",
                        description=f"housing plate, {thickness:.4g} mm, holds the bearings at this level")
        for b in held:
            out.touch(plate, b.name, "bearing seated in the plate")
        out.touch(plate, held_output, "bearing seated in the plate")
        out.ground.append(plate)
    return out.done()


# ---------------------------------------------------------------- the whole assembly


def all_parts(gears: Mapping[str, PlacedPart], others: PartSet) -> list[PlacedPart]:
    return list(gears.values()) + list(others.parts)


def assembly_document(name: str, parts: Iterable[PlacedPart]):
    """The assembly as an XCAF document: root ``name``, one sub-assembly ``<group>_assembly`` per
    group, each part an occurrence named as the part, placed by its matrix, coloured (surface
    colour, alpha kept). Parts sharing one shape and colour share one product (named after the
    first). Names must be unique in the whole tree. The tree is the one CadQuery's ``Assembly``
    writes, built here with the kernel directly."""
    from OCP.Quantity import Quantity_Color, Quantity_ColorRGBA, Quantity_TOC_sRGB
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_ColorType, XCAFDoc_DocumentTool

    parts = list(parts)
    names = [p.name for p in parts]
    if len(set(names)) != len(names):
        raise BuildError(f"assembly {name}: part names are not unique")
    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    tool.SetAutoNaming_s(False)
    colours = XCAFDoc_DocumentTool.ColorTool_s(doc.Main())

    def named(label, text):
        TDataStd_Name.Set_s(label, TCollection_ExtendedString(text))
        return label

    root = named(tool.NewShape(), name)
    groups: dict[str, Any] = {}
    products: list[tuple[TopoDS_Shape, tuple, Any]] = []  # (shape, colour, label)
    for p in parts:
        if p.group not in groups:
            groups[p.group] = named(tool.NewShape(), f"{p.group}_assembly")
        label = next((lab for shape, colour, lab in products if colour == p.colour and shape.IsSame(p.shape)), None)
        if label is None:
            label = named(tool.NewShape(), p.name)
            tool.SetShape(label, p.shape)
            r, g, b, a = p.colour
            colours.SetColor(label, Quantity_ColorRGBA(Quantity_Color(r, g, b, Quantity_TOC_sRGB), a),
                             XCAFDoc_ColorType.XCAFDoc_ColorSurf)
            products.append((p.shape, p.colour, label))
        named(tool.AddComponent(groups[p.group], label, location(p.matrix)), p.name)
    for grp in groups.values():
        tool.AddComponent(root, grp, TopLoc_Location())
    tool.UpdateAssemblies()
    return doc


def write_assembly_step(name: str, parts: Iterable[PlacedPart], path: Path, length_unit: str = "mm") -> Path:
    """The assembly STEP: tree root/group/part, names and colours, declared in ``length_unit``
    (geometry in mm, converted by the writer); edges as 3-D curves only, as the part files."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller
    from OCP.XSControl import XSControl_WorkSession
    from geargen.cad.export import STEP_UNITS, _quiet_kernel, atomic_path

    doc = assembly_document(name, parts)
    STEPControl_Controller.Init_s()
    _quiet_kernel()
    writer = STEPCAFControl_Writer(XSControl_WorkSession(), False)
    writer.SetColorMode(True)
    writer.SetLayerMode(True)
    writer.SetNameMode(True)
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 0)
    Interface_Static.SetIVal_s("write.precision.mode", 0)
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    Interface_Static.SetCVal_s("write.step.unit", STEP_UNITS[length_unit])
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise BuildError(f"assembly STEP transfer failed: {path}")
    with atomic_path(Path(path)) as tmp:
        if writer.Write(str(tmp)) != IFSelect_RetDone:
            raise BuildError(f"assembly STEP export failed: {path}")
    return Path(path)


def export_parts(layout, parts_set: PartSet | list, folder: Path, settings: Mapping[str, Any]) -> dict[str, Any]:
    """Write assembly.step and, per part, ``<name>.step`` and ``<name>.stl`` (assembly frame).

    Returns ``{"records": {file: manifest entry}, "parts": {name: placement and files},
    "tolerances": {...}}``.
    """
    from geargen.cad.export import export_step, export_stl

    parts = parts_set if isinstance(parts_set, list) else parts_set.parts
    unit = layout.design.length_unit
    folder.mkdir(parents=True, exist_ok=True)
    records: dict[str, Any] = {}
    info: dict[str, Any] = {}
    volumes: list[tuple[Any, float]] = []  # (shape, mm^3) already integrated
    asm = write_assembly_step(layout.design.name, parts, folder / "assembly.step", unit)
    records[asm.name] = {"format": "step", "length_unit": unit, "bytes": asm.stat().st_size,
                         "role": "assembly", "parts": [p.name for p in parts]}
    chord = settings["stl_chordal_tolerance"]
    chord_parts = settings.get("stl_chordal_tolerance_parts") or chord
    ang = settings["stl_angular_tolerance"]
    for p in parts:
        rs = export_step((p.name, p.world()), folder / f"{p.name}.step", unit)
        # every part meshed in its own frame and moved by its placement: gears by the exact mesher on
        # the GearSolid (20x faster than the kernel), the others by the kernel, whose mesh stays on
        # the shape, so parts sharing a shape (two bearings alike) are meshed once
        rl = export_stl(p.solid if p.solid is not None else p.shape, folder / f"{p.name}.stl",
                        chordal_tolerance=chord if p.role == "gear" else chord_parts, angular_tolerance=ang,
                        transform=p.matrix)
        records[rs.path.name] = rs.manifest_entry()
        records[rl.path.name] = rl.manifest_entry()
        vol = next((v for shape, v in volumes if shape.IsSame(p.shape)), None)
        if vol is None:  # parts sharing a shape (the two clusters, bearings alike) share its volume
            vol = solid_volume(p.shape, 1e-6)
            volumes.append((p.shape, vol))
        info[p.name] = {"group": p.group, "kind": p.kind, "role": p.role, "description": p.description,
                        "colour_rgba": list(p.colour), "placement_matrix_mm": p.matrix.round(12).tolist(),
                        "files": [rs.path.name, rl.path.name], "volume_mm3": vol}
    return {"records": records, "parts": info,
            "tolerances": {"stl_chordal_mm_gears": chord, "stl_chordal_mm_other_parts": chord_parts,
                           "stl_angular_rad": ang,
                           "step_frame": "assembly frame (placement_matrix_mm maps the part's own frame into it)"}}


# ---------------------------------------------------------------- faces near a mesh


def faces_near(shape, points, radius: float) -> TopoDS_Shape:
    """The faces of ``shape`` that come within ``radius`` (mm) of any of ``points`` ``(k, 2)``
    (x, y in the shape's own frame, mm), as one compound, for sectioning only where two gears
    can meet.

    A face is kept when its bounding box, projected on z = 0, is within ``radius`` of a point.
    The boxes come from the faces' geometry (B-spline poles, analytic bounds), so they hold the
    whole face: every point of a dropped face is farther than ``radius`` from every point.
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    kept = []
    for face, box in _faces_with_boxes(shape):
        x0, y0, _, x1, y1, _ = box.Get()
        dx = np.maximum(np.maximum(x0 - pts[:, 0], pts[:, 0] - x1), 0.0)
        dy = np.maximum(np.maximum(y0 - pts[:, 1], pts[:, 1] - y1), 0.0)
        if float(np.min(np.hypot(dx, dy))) <= radius:
            kept.append(face)
    return P.compound(kept)


# ---------------------------------------------------------------- overlap check


@dataclass(frozen=True)
class Overlap:
    """Two parts sharing ``volume`` mm^3 (``intended``: listed as meant to touch, with ``why``)."""

    part1: str
    part2: str
    volume: float
    intended: bool
    why: str = ""


@dataclass
class OverlapReport:
    """Pairwise intersections: ``pairs_checked`` (bounding boxes touching), the overlaps found,
    the tolerance (mm^3) below which a shared volume counts as touching, not overlapping."""

    parts: int
    pairs_checked: int
    overlaps: list[Overlap]
    tolerance: float
    intended: list[tuple[str, str, str]]
    delegated: list[tuple[str, str, str]] = field(default_factory=list)
    # intended contacts whose solids do not touch: (part, part, gap mm, why)
    missing_contacts: list[tuple[str, str, float, str]] = field(default_factory=list)
    contact_tolerance: float = 1e-3

    @property
    def unintended(self) -> list[Overlap]:
        return [o for o in self.overlaps if not o.intended and o.volume > self.tolerance]

    @property
    def interpenetrating(self) -> list[Overlap]:
        """Intended contacts whose solids share volume: parts meant to touch that run into each other."""
        return [o for o in self.overlaps if o.intended and o.volume > self.tolerance]

    @property
    def ok(self) -> bool:
        return not (self.unintended or self.interpenetrating or self.missing_contacts)


def _bbox(shape) -> Bnd_Box:
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box, True)
    return box


def _faces_with_boxes(shape):
    """Each face of ``shape`` with its bounding box, taken from the face's geometry (B-spline
    poles, analytic bounds), not from a possibly coarse mesh: the box holds the whole face."""
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = exp.Current()
        exp.Next()
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box, False)
        yield face, box


def _faces_within(shape, box: Bnd_Box) -> list:
    """The faces of ``shape`` whose geometric bounding box meets ``box``."""
    return [face for face, fb in _faces_with_boxes(shape) if not fb.IsOut(box)]


def contact_gap(a, b, tolerance: float) -> float:
    """The smallest distance (mm) between the solids ``a`` and ``b``. Where they come within
    ``tolerance`` of each other only the faces of each that can are measured (a gear's teeth
    never come near its shaft), so a shaft in a 112-tooth gear's bore costs milliseconds."""
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    box_a, box_b = _bbox(a), _bbox(b)
    box_a.Enlarge(tolerance)
    box_b.Enlarge(tolerance)
    fa, fb = ([], []) if box_a.IsOut(box_b) else (_faces_within(a, box_b), _faces_within(b, box_a))
    # apart: measured on the whole solids (only a missing contact, the failure, pays for that)
    dist = BRepExtrema_DistShapeShape(P.compound(fa), P.compound(fb)) if fa and fb else BRepExtrema_DistShapeShape(a, b)
    return float(dist.Value()) if dist.IsDone() else math.inf

def _volume(shape) -> float:
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return abs(props.Mass())


def intersection_volume(a, b) -> float:
    """Volume (mm^3) of the boolean common of two shapes (0 if they only touch)."""
    op = BRepAlgoAPI_Common(a, b)
    op.SetRunParallel(False)
    op.Build()
    if not op.IsDone():
        raise BuildError("boolean common failed")
    return _volume(op.Shape())


def gear_core(part: PlacedPart) -> TopoDS_Shape | None:
    """The material of a gear part between its bore and its root circle (and its hubs), in the
    assembly frame: a cheap solid wholly inside the gear, so what runs into it runs into the gear
    (a shaft too big for the bore). None for a part that is not a gear, or one with a keyway
    (the core would not be all material)."""
    solid = part.solid
    if solid is None:
        return None
    spec = solid.spec
    gears = (spec.large, spec.small) if isinstance(spec, ClusterSpec) else (spec,)
    if not all(hasattr(g, "hub") for g in gears):  # a rack: no bore, nothing runs into a core
        return None
    if any(g.hub.keyway_width > 0 for g in gears):
        return None
    pieces = []
    for g, z0 in zip(gears, (0.0, spec.small_gear_z) if isinstance(spec, ClusterSpec) else (0.0,)):
        bore = g.hub.bore_diameter
        # 2 % inside the root circle (the margin the design rules keep a bore from it): all material
        pieces.append(P.translate(P.cylinder(2 * 0.98 * g.root_radius_standard, g.face_width, bore), (0, 0, z0)))
        if g.hub.hub_length > 0:
            pieces.append(P.translate(P.cylinder(g.hub.hub_diameter, g.hub.hub_length, bore),
                                      (0, 0, z0 - g.hub.hub_length)))
    return P.compound(pieces).Moved(location(part.matrix))


def part_envelope(part: PlacedPart) -> TopoDS_Shape | None:
    """A cheap solid that contains the part, in the assembly frame: a gear's tip cylinders (with
    hubs and spacer), another part's ``envelope``; None if the part has none."""
    solid = part.solid
    if solid is None:
        return None if part.envelope is None else part.envelope.Moved(location(part.matrix))
    spec = solid.spec
    if not isinstance(spec, ClusterSpec) and not hasattr(spec, "hub"):  # a rack: its own (prismatic) solid
        return part.shape.Moved(location(part.matrix))
    pieces = []

    def gear_body(g, z0):
        pieces.append(P.translate(P.cylinder(2 * g.tip_radius, g.face_width), (0, 0, z0)))
        if g.hub.hub_length > 0:
            pieces.append(P.translate(P.cylinder(g.hub.hub_diameter, g.hub.hub_length), (0, 0, z0 - g.hub.hub_length)))

    if isinstance(spec, ClusterSpec):
        gear_body(spec.large, 0.0)
        gear_body(spec.small, spec.small_gear_z)
        if spec.axial_gap > 0:
            pieces.append(P.translate(P.cylinder(spec.spacer_diameter_resolved, spec.axial_gap),
                                      (0, 0, spec.large.face_width)))
    else:
        gear_body(spec, 0.0)
    return P.compound(pieces).Moved(location(part.matrix))


def pairwise_overlaps(parts: Iterable[PlacedPart], intended: Iterable[tuple[str, str, str]] = (),
                      tolerance: float = 1e-3, skip_intended: bool = True,
                      delegated: Iterable[tuple[str, str, str]] = (), contact_tolerance: float = 1e-3) -> OverlapReport:
    """Check every pair of parts for shared volume (boolean common, after a bounding-box test).

    Pairs listed in ``intended`` (part, part, why) are meant to touch: with ``skip_intended``
    they are not intersected (their contact is by construction, a shaft in its bore). Pairs in
    ``delegated`` (meshing gears) are checked elsewhere, by the geometric mesh checker, and
    skipped here. A gear is first tested through its tip-cylinder envelope (a helical spring
    through its tube: :func:`part_envelope`); only when that shares volume with the other part
    are the exact solids intersected. Any other pair sharing
    more than ``tolerance`` mm^3 is an overlap.

    Every intended contact is verified: its two solids must come within ``contact_tolerance``
    (mm) of each other (:func:`contact_gap`), else it is a missing contact, and must not share
    more than ``tolerance`` mm^3 (interpenetrating).
    """
    parts, intended = list(parts), list(intended)
    wanted = {frozenset((a, b)): why for a, b, why in intended}
    skip = {frozenset((a, b)) for a, b, _ in delegated}
    boxes = [_bbox(p.world()) for p in parts]
    envelopes = [part_envelope(p) for p in parts]
    overlaps: list[Overlap] = []
    checked = 0
    for i in range(len(parts)):
        for j in range(i + 1, len(parts)):
            if boxes[i].IsOut(boxes[j]):
                continue
            key = frozenset((parts[i].name, parts[j].name))
            if key in skip or (key in wanted and skip_intended):
                continue
            checked += 1
            a = envelopes[i] if envelopes[i] is not None else parts[i].world()
            b = envelopes[j] if envelopes[j] is not None else parts[j].world()
            if envelopes[i] is not None or envelopes[j] is not None:
                if intersection_volume(a, b) <= tolerance:
                    continue
            v = intersection_volume(parts[i].world(), parts[j].world())
            if v > tolerance or key in wanted:
                overlaps.append(Overlap(parts[i].name, parts[j].name, v, key in wanted, wanted.get(key, "")))
    # every intended contact must be one: the two solids touch (a check that can fail), and
    # (when not intersected above) do not run into each other
    by_name = {p.name: p for p in parts}
    missing = []
    for a, b, why in intended:
        if a not in by_name or b not in by_name:
            missing.append((a, b, math.inf, why + " (no such part)"))
            continue
        gap = contact_gap(by_name[a].world(), by_name[b].world(), contact_tolerance)
        if gap > contact_tolerance:
            missing.append((a, b, gap, why))
        elif skip_intended:
            # a spring seated on a wall: its tube only touches the wall, so the helix cannot
            # run into it (the exact helix is intersected only when the tube shares volume)
            tubes = [part_envelope(by_name[n]) if by_name[n].envelope is not None else None for n in (a, b)]
            if any(t is not None for t in tubes) and intersection_volume(
                    *(t if t is not None else by_name[n].world() for t, n in zip(tubes, (a, b)))) <= tolerance:
                continue
            # a gear is represented by its core (bore to root circle): exact for what comes in
            # through the bore, and milliseconds instead of a boolean with every tooth
            core_a, core_b = gear_core(by_name[a]), gear_core(by_name[b])
            v = intersection_volume(core_a if core_a is not None else by_name[a].world(),
                                    core_b if core_b is not None else by_name[b].world())
            if v > tolerance:
                overlaps.append(Overlap(a, b, v, True, why))
    report = OverlapReport(len(parts), checked, overlaps, tolerance, list(intended), missing_contacts=missing,
                           contact_tolerance=contact_tolerance)
    report.delegated = list(delegated)
    return report


__all__ = ["COLOURS", "transform", "location", "PlacedPart", "PartSet", "gear_parts", "parts_settings",
           "non_gear_parts", "carriage_parts", "beam_pinion_parts", "split_pinion_parts", "all_parts", "assembly_document",
           "write_assembly_step", "export_parts", "faces_near", "Overlap", "OverlapReport", "intersection_volume",
           "pairwise_overlaps"]
