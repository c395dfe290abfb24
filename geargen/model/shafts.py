"""Shafts and their bearings, placed: the one home of every length the solids and the stiffness
model share (bearing positions, spans, where each gear loads its shaft, shaft diameters).

The CAD layer builds the shafts and bearing rings at exactly these positions, and
:mod:`geargen.model.analysis` sizes the shaft components of the stiffness model from them, so
moving a bearing in the design moves the solid and changes the stiffness together.

Frame as :mod:`geargen.model.layout` (mm, z along the gear axes). A bearing is a ring of
``width`` whose lower face is at ``z``; it supports the shaft at its mid-width.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from geargen.design.cluster import ClusterSpec
from geargen.errors import DesignError
from geargen.model.layout import Layout


@dataclass(frozen=True)
class Bearing:
    """A support of a shaft (mm): lower face at ``z``, ``width``, ``bore`` x ``outer_diameter``.

    A rolling bearing to the structure, or (``via`` = another placed shaft's name) a part that
    holds this shaft on that shaft (the split pinion's clamp collar on the hollow shaft): its
    radial support is then that shaft's lateral compliance at this height."""

    name: str
    z: float
    width: float
    bore: float
    outer_diameter: float
    via: str | None = None

    @property
    def centre_z(self) -> float:
        """Where it supports the shaft: the middle of its width."""
        return self.z + self.width / 2


@dataclass(frozen=True)
class Shaft:
    """A rotating shaft (mm): on the axis through ``centre``, from ``z_lo`` to ``z_hi``, of
    ``diameter``, carried by ``bearings``; ``loads`` maps each gear (by role) on it to the height
    of its face's middle, where its mesh force acts."""

    name: str  # the solid's part name
    centre: tuple[float, float]
    z_lo: float
    z_hi: float
    diameter: float
    bearings: tuple[Bearing, ...]
    loads: dict[str, float]
    bore: float = 0.0  # a hollow shaft's bore
    # heights between which the shaft twists, where they are not the first two loads' mid-faces
    # (the split pinion's inner shaft: from its clamp collar's face to the compliant pinion's face)
    twist: tuple[float, float] | None = None

    @property
    def length(self) -> float:
        return self.z_hi - self.z_lo

    @property
    def twist_length(self) -> float:
        """Length of shaft twisting between the torque's way in and out."""
        if self.twist is not None:
            return abs(self.twist[1] - self.twist[0])
        first, second = list(self.loads)[:2]
        return self.distance(first, second)

    @property
    def lower_support(self) -> float:
        return min(b.centre_z for b in self.bearings)

    def supports(self) -> tuple[Bearing, ...]:
        """The bearings from the lowest up."""
        return tuple(sorted(self.bearings, key=lambda b: b.centre_z))

    @property
    def span(self) -> float:
        """Distance between the outermost bearings' support points."""
        zs = [b.centre_z for b in self.bearings]
        return max(zs) - min(zs)

    def load_position(self, gear: str) -> float:
        """Distance of ``gear``'s mid-face from the lower support (inside the span when between them)."""
        return self.loads[gear] - self.lower_support

    def distance(self, gear_a: str, gear_b: str) -> float:
        """Length of shaft twisting between two gears' mid-faces."""
        return abs(self.loads[gear_a] - self.loads[gear_b])


def bore_of(spec) -> float:
    s = spec.large if isinstance(spec, ClusterSpec) else spec
    return s.hub.bore_diameter


def _mid(placed, gear) -> float:
    z0, z1 = placed.face_z(gear)
    return (z0 + z1) / 2


def loop_shafts(gears, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The robot joint's loop shafts (Fig. 10) from its placed loop ``gears``
    (:class:`~geargen.model.layout.GearPlacement`): each cluster's, the output's and the
    input's, with two bearings each a ``bearing_clearance`` beyond the faces of the gears they
    carry. ``parts``: the ``[parts]`` settings (:func:`geargen.design.parts.parts_settings`)."""
    gap = parts["bearing_clearance"]
    gears = list(gears)
    by = {p.name: p for p in gears}
    out: dict[str, Shaft] = {}

    def on_shaft(name, bearing_names, members, width, outer):
        z0 = min(p.height[0] for p in members)
        z1 = max(p.height[1] for p in members)
        diameter = bore_of(members[0].spec)  # the shaft fills the gears' bore
        lower = Bearing(bearing_names[0], z0 - gap - width, width, diameter, outer)
        upper = Bearing(bearing_names[1], z1 + gap, width, diameter, outer)
        loads = {g.name: _mid(p, g) for p in members for g in p.gears}
        return Shaft(name, tuple(members[0].centre), lower.z, upper.z + width, diameter, (lower, upper), loads)

    for side in ("a", "b"):
        members = [p for p in gears if p.group == f"cluster_{side}"]
        out[f"cluster_{side}"] = on_shaft(f"cluster_shaft_{side}", (f"cluster_bearing_lower_{side}",
                                                                    f"cluster_bearing_upper_{side}"), members,
                                          parts["cluster_bearing_width"], parts["cluster_bearing_outer_diameter"])
    out["output"] = on_shaft("output_shaft", ("output_bearing_lower", "output_bearing_upper"), [by["output"]],
                             parts["output_bearing_width"], parts["output_bearing_outer_diameter"])
    out["input"] = on_shaft("input_shaft", ("input_bearing_lower", "input_bearing_upper"), [by["input"]],
                            parts["input_bearing_width"], parts["input_bearing_outer_diameter"])
    return out


def carriage_arm_top(input_shaft: Shaft, parts: dict[str, Any]) -> float:
    """Top of the preload carriage's arm, which holds the input's upper bearing from above: where
    the stage shafts' lower bearings stand."""
    return max(b.z + b.width for b in input_shaft.bearings) + parts["carriage_plate_thickness"]


def carriage_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The robot joint's shafts (Fig. 10): the loop's (:func:`loop_shafts`), the input's running
    on to the gear that drives it (the bevel gear, or the last of the [stages]), and the stage
    shafts (:func:`stage_shafts`)."""
    out = loop_shafts(layout.gears, parts)
    shaft = out["input"]
    from geargen.design.stages import stages
    stage_list = stages(layout.design)
    if not stage_list:
        # the input shaft runs on to the bevel gear, whose heel is input_shaft_to_bevel above the input's mid-face
        bevel_heel = shaft.loads["input"] + parts["input_shaft_to_bevel"]
        out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, shaft.z_hi, shaft.diameter, shaft.bearings,
                             {**shaft.loads, "bevel_gear": bevel_heel})
        return out
    if stage_list[-1].kind == "planetary":
        # the input shaft runs up through the carriage arm into the planet carrier's lower plate
        from geargen.model.planetary_stage import carrier
        c = carrier(layout, parts, stage_list[-1])
        out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, c.lower_top, shaft.diameter, shaft.bearings,
                             {**shaft.loads, c.name: c.z_lower + c.thickness / 2})
        return out
    # the input shaft runs up through the carriage arm to the last stage's driven gear
    last = layout.gear(stage_list[-1].driven)
    if not math.isclose(bore_of(last.spec), shaft.diameter, rel_tol=1e-9):
        raise DesignError(f"gears.{last.name}.bore_diameter", f"{bore_of(last.spec):.6g} mm: the gear sits on the input "
                          "gear's shaft", f"the input's bore, {shaft.diameter:.6g} mm")
    out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, last.height[1], shaft.diameter, shaft.bearings,
                         {**shaft.loads, last.name: _mid(last, last.spec)})
    out.update(stage_shafts(layout, parts, stage_list))
    return out


def stage_shafts(layout: Layout, parts: dict[str, Any], stage_list) -> dict[str, Shaft]:
    """The shafts between the upstream stages (:mod:`geargen.design.stages`): each carries one
    stage's driven gear and the next stage's driver, from its lower bearing standing on the
    carriage arm to its upper bearing under the bridge over the highest stage."""
    gap, width, outer = parts["bearing_clearance"], parts["stage_bearing_width"], parts["stage_bearing_outer_diameter"]
    by = {p.name: p for p in layout.gears}
    loop = [p for p in layout.gears if not p.group.startswith("stage_")]
    z_lower = carriage_arm_top(loop_shafts(loop, parts)["input"], parts)
    top = max(by[g].height[1] for st in stage_list for g in (st.driver, st.driven))
    z_upper = top + gap
    out: dict[str, Shaft] = {}
    for i, (st, nxt) in enumerate(zip(stage_list, stage_list[1:]), start=1):
        members = [by[st.driven], by[nxt.driver]]
        bores = {bore_of(m.spec) for m in members}
        if len(bores) != 1:
            raise DesignError(f"gears.{nxt.driver}.bore_diameter", f"{bore_of(members[1].spec):.6g} mm: it shares a shaft "
                              f"with {st.driven}", f"{bore_of(members[0].spec):.6g} mm, the same bore")
        diameter = bores.pop()
        if not diameter > 0:
            raise DesignError(f"gears.{st.driven}.bore_diameter", "missing: the gear sits on a stage shaft", "> 0")
        if not outer > diameter:
            raise DesignError("parts.stage_bearing_outer_diameter", f"not larger than the stage shaft ({diameter:.6g} mm)",
                              f"> {diameter:.6g} mm")
        bearings = (Bearing(f"stage_bearing_lower_{i}", z_lower, width, diameter, outer),
                    Bearing(f"stage_bearing_upper_{i}", z_upper, width, diameter, outer))
        loads = {m.name: _mid(m, m.spec) for m in members}
        out[f"stage_{i}"] = Shaft(f"stage_shaft_{i}", tuple(members[0].centre), z_lower, z_upper + width, diameter,
                                  bearings, loads)
    return out


def beam_pinion_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The C-axis dual pinions' shafts (Fig. 12): each slides in a quill whose two bearings,
    ``cluster_bearing_spacing`` apart, sit a ``bearing_clearance`` below the large gear; the
    large gear and, beyond it, the pinion meshing the bull gear are overhung above them. The
    shaft runs from its locknut (against the lower bearing's inner ring) to the pinion's top."""
    gap = parts["bearing_clearance"]
    width, outer = parts["cluster_bearing_width"], parts["cluster_bearing_outer_diameter"]
    out: dict[str, Shaft] = {}
    for side in ("a", "b"):
        large, small = layout.gear(f"cluster_large_{side}"), layout.gear(f"cluster_small_{side}")
        diameter = parts["cluster_shaft_diameter"]
        upper = Bearing(f"cluster_bearing_upper_{side}", large.height[0] - gap - width, width, diameter, outer)
        lower = Bearing(f"cluster_bearing_lower_{side}", upper.z - parts["cluster_bearing_spacing"], width, diameter, outer)
        z_nut = lower.z - parts["locknut_width"]
        loads = {g.name: _mid(p, g) for p in (large, small) for g in p.gears}
        out[f"cluster_{side}"] = Shaft(f"cluster_shaft_{side}", tuple(small.centre), z_nut, small.height[1], diameter,
                                       (lower, upper), loads)
    out["input"] = beam_pinion_input_shaft(layout, parts)
    return out


def beam_pinion_input_shaft(layout: Layout, parts: dict[str, Any]) -> Shaft:
    """The long pinion's shaft: on its two bearings (:func:`beam_pinion_bearings`, at the span the
    beam-spring helper sizes), up through the upper one and a ``bearing_clearance`` into the
    coupling, which it fills for half the coupling's length. The motor's torque enters along that
    half and leaves at the meshes with the large gears: it twists from the middle of the one to the
    large gears' mid-face (engaged)."""
    from geargen.core.stiffness import sized_beam_pinion
    from geargen.design.stiffness import stiffness_design
    spec = stiffness_design(layout.design).beam_pinion
    if spec is None:
        raise DesignError("beam_pinion", "missing: the long pinion's span comes from it", "a [beam_pinion] section")
    span = sized_beam_pinion(layout.design, spec).span
    width, outer, diameter = parts["input_bearing_width"], parts["input_bearing_outer_diameter"], \
        parts["input_shaft_diameter"]
    z_lo, z_hi = beam_pinion_bearings(layout, parts, span)
    lower = Bearing("input_bearing_lower", z_lo, width, diameter, outer)
    upper = Bearing("input_bearing_upper", z_hi, width, diameter, outer)
    in_coupling = parts["coupling_length"] / 2
    top = z_hi + width + parts["bearing_clearance"] + in_coupling
    z_mesh = z_lo + width / 2 + span / 2
    return Shaft("input_shaft", tuple(layout.gear("input").centre), z_lo, top, diameter, (lower, upper),
                 {"input": z_mesh}, twist=(z_mesh, top - in_coupling / 2))


def beam_pinion_bearings(layout: Layout, parts: dict[str, Any], span: float) -> tuple[float, float]:
    """Lower faces (z) of the long pinion's two bearings: ``span`` apart (the beam-spring helper's),
    symmetric about the large gears' engaged mid-face, so the slope at the mesh is zero."""
    large = layout.gear("cluster_large_a")
    z_mesh = sum(large.height) / 2 - layout.axial_shift.get("cluster_a", 0.0)
    width = parts["input_bearing_width"]
    return z_mesh - span / 2 - width / 2, z_mesh + span / 2 - width / 2


def housing_heights(layout: Layout, parts: dict[str, Any], engagement) -> tuple[float, float]:
    """(bottom, top) of the C-axis housing block the quills slide in: its top a clearance below the
    lowest a large gear comes (the trailer retracted, ``engagement``'s strokes), its thickness
    ``housing_thickness``."""
    strokes = {"a": -engagement.leader_retracted_stop, "b": -engagement.trailer_retracted_stop}
    top = min(layout.gear(f"cluster_large_{side}").height[0] - layout.axial_shift.get(f"cluster_{side}", 0.0)
              - strokes[side] for side in ("a", "b")) - parts["bearing_clearance"]
    return top - parts["housing_thickness"], top


@dataclass(frozen=True)
class DriveColumn:
    """The C-axis drive column: a bar ``width`` x ``thickness`` (the thickness along the preload
    motion, x) bolted to the housing block's end face over ``clamp`` (z range), carrying the long
    pinion's bearing plates at ``supports`` (their mid-widths, lower and upper)."""

    width: float
    thickness: float
    clamp: tuple[float, float]
    supports: tuple[float, float]

    def support_stiffness(self, elastic_modulus: float) -> tuple[float, float]:
        """Radial stiffness (N/mm, along x) the column gives each bearing: a cantilever from the
        clamp's nearer edge, ``3 E I / h^3`` with ``I = width thickness^3 / 12``; the bearing plates
        (loaded in their plane) and the bolted joint taken as rigid. Infinite inside the clamp."""
        second_moment = self.width * self.thickness ** 3 / 12
        out = []
        for z in self.supports:
            h = max(self.clamp[0] - z, z - self.clamp[1], 0.0)
            out.append(math.inf if h == 0.0 else 3 * elastic_modulus * second_moment / h ** 3)
        return out[0], out[1]


def drive_column(layout: Layout, parts: dict[str, Any], span: float, engagement) -> DriveColumn:
    """The column as the solids are built (:func:`beam_pinion_bearings`, :func:`housing_heights`)."""
    width = parts["input_bearing_width"]
    return DriveColumn(parts["drive_column_width"], parts["drive_column_thickness"],
                       housing_heights(layout, parts, engagement),
                       tuple(z + width / 2 for z in beam_pinion_bearings(layout, parts, span)))


def split_pinion_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The split pinion's two concentric shafts (Fig. 8).

    ``hollow``: the stiff pinion's shaft (its bore, so the inner shaft clears it by a
    ``bearing_clearance`` all round), ``hollow_shaft_length`` from the stiff pinion's far face
    down, on its bearing pair (``bearing_spacing`` apart) just below the stiff pinion, which it
    overhangs. The drive turns it at its lower end; it twists from there to the stiff pinion's
    mid-face.
    ``inner``: the compliant pinion's shaft (the pinion's bore), from the clamp collar below the
    hollow shaft's end, up through it and the compliant pinion to an outboard bearing a
    ``bearing_clearance`` above the compliant pinion and the output gear (the plate that holds
    it clears both). It is carried by the collar (on the hollow shaft) and the outboard bearing,
    so the compliant pinion sits between two supports; it twists from the collar's face to the
    compliant pinion's face."""
    gap = parts["bearing_clearance"]
    stiff, compl = layout.gear(layout.settings["pinion_stiff"]), layout.gear(layout.settings["pinion_compliant"])
    output = layout.gear(layout.settings["output"])
    d_hollow, d_inner = parts["hollow_shaft_outer_diameter"], bore_of(compl.spec)
    if not d_inner > 0:
        raise DesignError(f"gears.{compl.name}.bore_diameter", "missing: the inner shaft fills the compliant "
                          "pinion's bore", "bore_diameter_* > 0")
    bore_hollow = d_inner + 2 * gap
    if not bore_hollow < d_hollow:
        raise DesignError("parts.hollow_shaft_outer_diameter", f"{d_hollow:.6g} mm leaves no wall around the inner "
                          f"shaft ({d_inner:.6g} mm + {gap:.6g} mm clearance all round)", f"> {bore_hollow:.6g} mm")
    zs0, zs1 = stiff.height
    zc0, zc1 = compl.height
    bw, bod = parts["bearing_width"], parts["bearing_outer_diameter"]
    z_hollow0 = zs1 - parts["hollow_shaft_length"]
    spacing = parts.get("bearing_spacing") or (bw + gap)
    if not spacing >= bw + gap:
        raise DesignError("parts.bearing_spacing", f"{spacing:.6g} mm puts the two bearings into each other",
                          f">= {bw + gap:.6g} mm (a bearing width and a bearing_clearance)")
    upper = Bearing("pinion_bearing_1", zs0 - gap - bw, bw, d_hollow, bod)
    pair = (Bearing("pinion_bearing_2", upper.z - spacing, bw, d_hollow, bod), upper)
    if not z_hollow0 < pair[0].z:
        raise DesignError("parts.hollow_shaft_length", f"{parts['hollow_shaft_length']:.6g} mm does not reach "
                          "through the bearing pair", f"> {zs1 - pair[0].z:.6g} mm")
    # the drive turns the hollow shaft at its lower end, where the collar joins the inner shaft to it:
    # the stiff path twists from there to the stiff pinion's mid-face, the compliant one from the
    # collar's face to the compliant pinion
    loads = {g.name: _mid(stiff, g) for g in stiff.gears}
    hollow = Shaft("hollow_shaft", tuple(stiff.centre), z_hollow0, zs1, d_hollow, pair, loads, bore=bore_hollow,
                   twist=(z_hollow0, next(iter(loads.values()))))
    cw = parts["collar_width"]
    collar = Bearing("friction_collar", z_hollow0 - cw, cw, d_inner, parts["collar_outer_diameter"], via=hollow.name)
    z_top = max(zc1, output.height[1]) + gap
    outboard = Bearing("compliant_bearing", z_top, parts["compliant_bearing_width"], d_inner,
                       parts["compliant_bearing_outer_diameter"])
    inner = Shaft("inner_shaft", tuple(compl.centre), collar.z, outboard.z + outboard.width, d_inner,
                  (collar, outboard), {g.name: _mid(compl, g) for g in compl.gears}, twist=(z_hollow0, zc0))
    return {"hollow": hollow, "inner": inner}


#: the shafts of each kind of hardware that the model places
SHAFT_BUILDERS = {"carriage": carriage_shafts, "beam_pinion": beam_pinion_shafts, "split_pinion": split_pinion_shafts}


def shafts(layout: Layout) -> dict[str, Shaft]:
    """The placed shafts of the resolved drive (empty without a [parts] table)."""
    from geargen.design.parts import parts_settings
    if not layout.design.section("parts"):
        return {}
    parts = parts_settings(layout.design)
    builder = SHAFT_BUILDERS.get(parts["hardware"])
    return builder(layout, parts) if builder is not None else {}


__all__ = ["Bearing", "Shaft", "DriveColumn", "carriage_shafts", "beam_pinion_shafts", "beam_pinion_bearings",
           "beam_pinion_input_shaft",
           "drive_column", "housing_heights", "split_pinion_shafts", "shafts", "SHAFT_BUILDERS", "bore_of"]
