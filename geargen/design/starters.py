"""Starter designs for ``geargen new KIND FILE.toml``: complete, commented design files that build.

Each starter is data (:class:`Starter`: tables of keys, values and the reason for each value
that needs one); :func:`starter_text` writes it as TOML, every key followed by its meaning and
unit from the schema (:func:`geargen.design.reference.key_comment`), so the comments cannot
disagree with what ``load_design`` reads.

``dual_pinion``: a Type 2 dual-pinion drive with radial preload on blade flexures and springs,
laid out like ``assemblies/robot_joint.toml`` but metric (module 1 mm) with its own tooth train
(18/54 and 20/100, 15:1). ``split_pinion``: a Type 1 concentric split pinion like
``assemblies/split_pinion.toml`` at another size (module 1 mm, 24/96, 4:1), its inner shaft
sized for the preload band. Both pass ``geargen check`` and build (tests/test_new.py).
"""

from __future__ import annotations

import json
import textwrap
from dataclasses import dataclass
from typing import Any

from geargen.design.schema import key_comment
from geargen.design.validate import key_schema
from geargen.errors import DesignError

#: where the value's comment starts (wider keys push it right)
COMMENT_COLUMN = 40
LINE_WIDTH = 100


@dataclass(frozen=True)
class Key:
    """One key of a starter: its value, and why this value (empty when the meaning says it all)."""

    key: str
    value: Any
    why: str = ""


@dataclass(frozen=True)
class Table:
    """``[header]`` (``""``: the top-level keys) with a note above it and its keys."""

    header: str
    keys: tuple[Key, ...]
    note: str = ""


@dataclass(frozen=True)
class Starter:
    kind: str
    summary: str
    intro: str
    tables: tuple[Table, ...]


# ---------------------------------------------------------------- dual pinion

_DUAL_PINION = Starter(
    "dual_pinion",
    "a Type 2 dual-pinion drive with radial preload (Hale & Slocum 1994, Fig. 10), metric",
    "The structure of assemblies/robot_joint.toml (a robot revolute joint: the input pinion rides on blade "
    "flexures and is pushed between two cluster gears by two springs), metric and with its own tooth train: "
    "module 1 mm, 18/54 then 20/100, 15:1, and 30:1 from the motor through a 2:1 bevel pair. Every value is a "
    "consistent starting point, not a finished design: change the gears first, then run geargen synth, "
    "check and stiffness again.",
    (
        Table("", (
            Key("description", "Metric dual-pinion Type 2 drive with radial-motion preload (geargen starter)"),
            Key("length_unit", "mm"),
        )),
        Table("drive", (
            Key("type", "type2", "both paths carry the load alike; the preload must be at least half the maximum load"),
            Key("preload", "radial", "the input pinion moves on its carriage between the two cluster gears"),
        )),
        Table("gear_defaults", (
            Key("module_mm", 1.0, "about the robot joint's 32 DP (0.79 mm) scaled up, so the 20-tooth cluster "
                "pinion keeps a root around an 8 mm shaft"),
            Key("pressure_angle_deg", 20),
        )),
        Table("gears.input", (
            Key("teeth", 18, "18 teeth at 20 deg are not undercut (the limit is 17)"),
            Key("face_width_mm", 8, "wider than the cluster's large gear so the carriage's axial play keeps "
                "the full contact"),
            Key("bore_diameter_mm", 5, "on the 5 mm input shaft from the bevel gear"),
        ), "gear 1: the input pinion, on the symmetry line, on the flexure carriage"),
        Table("gears.cluster_large", (
            Key("teeth", 54, "mesh 1 is 54 / 18 = 3:1"),
            Key("face_width_mm", 6),
            Key("bore_diameter_mm", 8, "pressed and bonded on the 8 mm cluster shaft"),
        ), "gear 2: the large gear of each cluster (mesh 1 with the input)"),
        Table("gears.cluster_small", (
            Key("teeth", 20, "mesh 2 is 100 / 20 = 5:1: the train is 3 x 5 = 15:1"),
            Key("face_width_mm", 10, "the widest face: mesh 2 carries the output torque"),
            Key("bore_diameter_mm", 8),
        ), "gear 3: the small gear of each cluster (mesh 2 with the output)"),
        Table("gears.output", (
            Key("teeth", 100),
            Key("face_width_mm", 8, "at 7 N·m plus the preload the loaded path's mesh 2 sees about 150 N: "
                "about 60 MPa Lewis root stress on 8 mm of face"),
            Key("bore_diameter_mm", 25, "on the 25 mm joint shaft"),
        ), "gear 4: the output gear of the joint"),
        Table("synthesis", (
            Key("centre_distance_mesh1_mm", 36.1, "standard (18 + 54) x 1 / 2 = 36 mm, plus 0.1 mm so that "
                "mesh 1 keeps backlash as the carriage moves"),
            Key("centre_distance_mesh2_mm", 60.0, "standard (20 + 100) x 1 / 2"),
            Key("circumferential_backlash_max_mesh1_mm", 0.13, "mesh 1 is where the preload closes the loop: "
                "it keeps backlash over the whole error budget (geargen check: 0.05 mm worst case)"),
            Key("circumferential_backlash_min_mesh1_mm", 0.10),
            Key("circumferential_backlash_max_mesh2_mm", 0.10),
            Key("circumferential_backlash_min_mesh2_mm", 0.02),
            Key("start_angle_A1_deg", -70.0, "as the robot joint: the input's lines of action near the "
                "carriage's motion"),
            Key("rounding", "whole_down"),
        ), "Where the two clusters sit so that both paths mesh (the paper's Eqs. 7-8 and Appendix). Backlash "
           "is circumferential, at the reference circles."),
        Table("errors.input", (
            Key("bearing_eccentricity_tir_um", 5, "P5 (ABEC 5) ball bearings"),
            Key("pitch_line_eccentricity_tir_um", 15, "precision-ground gears, about ISO 1328 grade 6"),
            Key("tooth_to_tooth_tir_um", 10),
        ), "The error budget (total indicator readings, here in micrometres) the carriage travel must absorb."),
        Table("errors.cluster_large", (
            Key("bearing_eccentricity_tir_um", 5),
            Key("pitch_line_eccentricity_tir_um", 20),
            Key("tooth_to_tooth_tir_um", 10),
        )),
        Table("errors.cluster_small", (
            Key("bearing_eccentricity_tir_um", 5),
            Key("pitch_line_eccentricity_tir_um", 15),
            Key("tooth_to_tooth_tir_um", 10),
        )),
        Table("errors.output", (
            Key("bearing_eccentricity_tir_um", 8, "a thin-section bearing"),
            Key("pitch_line_eccentricity_tir_um", 25),
            Key("tooth_to_tooth_tir_um", 10),
        )),
        Table("checks", (
            Key("carriage_travel_limit_mm", 0.5, "= [flexures] travel: the error budget must fit in it "
                "(geargen check: 0.12 mm worst case)"),
        )),
        Table("stiffness", (
            Key("elastic_modulus_GPa", 207, "steel gears and shafts"),
            Key("shear_modulus_GPa", 79.3),
            Key("reduce_to", "output"),
        ), "Stiffness and preload (geargen stiffness). The meshes of each path come from the gears (Eq. 1); "
           "the components below are the rest of each path."),
        Table("stiffness.components.cluster_shaft", (
            Key("kind", "shaft_torsion"),
            Key("shaft", "cluster"),
            Key("diameter_mm", 8, "the softest part of a path: 8 mm rather than 6 mm triples its stiffness"),
            Key("length_mm", 9.5, "between the two gears' mid-planes: 6 / 2 + 1.5 gap + 10 / 2"),
        ), "Each cluster's shaft twisting between its large and its small gear"),
        Table("stiffness.components.cluster_shaft_bending", (
            Key("kind", "shaft_bending"),
            Key("gear", "cluster_small"),
            Key("diameter_mm", 8),
            Key("span_mm", 20, "between the cluster shaft's two bearings"),
            Key("load_position_mm", 7, "the small gear near one bearing"),
            Key("support", "simple"),
        ), "... and bending between its bearings under the mesh-2 force"),
        Table("stiffness.components.cluster_bearings", (
            Key("kind", "linear"),
            Key("gear", "cluster_small"),
            Key("stiffness_N_per_um", 10, "a small deep-groove ball bearing with light axial preload"),
            Key("count", 2),
        ), "The cluster shaft's two bearings, along the mesh-2 line of action"),
        Table("stiffness.components.input_shaft", (
            Key("kind", "shaft_torsion"),
            Key("shaft", "input"),
            Key("diameter_mm", 5),
            Key("length_mm", 13.5, "= [parts] input_shaft_to_bevel"),
            Key("scope", "common"),
        ), "In series with both paths: the input shaft from the bevel gear ..."),
        Table("stiffness.components.output_hub", (
            Key("kind", "shaft_torsion"),
            Key("shaft", "output"),
            Key("diameter_mm", 32),
            Key("bore_diameter_mm", 25),
            Key("length_mm", 10),
            Key("scope", "common"),
        ), "... and the output gear's hub on the joint shaft"),
        Table("preload", (
            Key("max_output_torque_Nm", 7, "peak joint torque, either direction"),
            Key("line_of_action_angle_deg", 0.0, "the optimal configuration of Fig. 9"),
            Key("loop_error_budget", "mean"),
            Key("path_backlash_urad", 1141, "mesh 1's 0.10 mm at the 27 mm cluster radius, / 5, plus mesh 2's "
                "0.02 mm at the 50 mm output radius"),
        ), "The preload is set by the springs' installed length ([springs]): geargen stiffness shows about "
           "4 N·m against the 3.5 N·m (half the maximum load) the paper asks of a Type 2 drive."),
        Table("flexures", (
            Key("count", 3),
            Key("thickness_mm", 0.25, "hardened spring-steel shim"),
            Key("length_mm", 25),
            Key("width_mm", 12),
            Key("elastic_modulus_GPa", 207),
            Key("poisson_ratio", 0.29),
            Key("allowable_stress_MPa", 500, "well below the shim's yield, for long life"),
            Key("travel_mm", 0.5, "+-0.5 mm: the loop errors (0.12 mm) plus assembly adjustment; 124 MPa at the "
                "clamps"),
            Key("neutral_offset_mm", 0.0, "blades unstressed at the operating position"),
            Key("target_stiffness_N_per_mm", 7.5, "asks the design helper for blades of the same stiffness "
                "(3 x 12 E I / L^3 = 7.45 N/mm here)"),
        ), "Three parallel blades carry the motor, bevel pair and input gear (the preload carriage)."),
        Table("springs", (
            Key("count", 2),
            Key("wire_diameter_mm", 1.2, "music wire"),
            Key("mean_coil_diameter_mm", 12, "spring index 10"),
            Key("active_coils", 4, "rate G d^4 / (8 D^3 Na) = 2.97 N/mm each"),
            Key("end_type", "squared_ground"),
            Key("free_length_mm", 21.5),
            Key("installed_length_mm", 11, "10.5 mm compressed: 2 x 31 N = 62 N on the carriage, 632 MPa in "
                "the wire"),
            Key("shear_modulus_GPa", 79.3),
            Key("allowable_shear_stress_MPa", 900, "about 0.4 of the tensile strength of 1.2 mm music wire; "
                "861 MPa when compressed solid"),
        ), "Two helical compression springs push the carriage towards the output."),
        Table("layout", (
            Key("kind", "dual_pinion"),
            Key("model_tooth_thickness", "mid_tolerance", "each gear of the model made at the middle of its "
                "tooth-thickness allowance (taken from its mesh's backlash range where the mesh runs)"),
            Key("loaded_flank_gap_mm", 0.0005, "0.5 um, so that the solids do not touch"),
            Key("cluster", "separate", "large gear bonded on the small gear's shaft: two parts"),
            Key("cluster_axial_gap_mm", 1.5),
            Key("carriage_travel_mm", 0.5, "= [flexures] travel"),
            Key("upstream_stages", [[15, 30]], "the bevel pair: 15 teeth on the motor, 30 on the input shaft"),
            Key("required_ratios", [30], "motor to output 2 x 15 = 30:1"),
        ), "The assembly model (geargen build): placement, the other parts, exports."),
        Table("parts", (
            Key("bearing_clearance_mm", 0.5),
            Key("bevel_pinion_teeth", 15),
            Key("bevel_gear_teeth", 30),
            Key("bevel_module_mm", 0.8),
            Key("bevel_face_width_mm", 4, "under a third of the 13.4 mm cone distance"),
            Key("input_shaft_to_bevel_mm", 13.5, "the bevel gear's heel root circle 0.6 mm above the carriage arm"),
            Key("bevel_backlash_mm", 0.04, "circumferential at the heel pitch circles, cut as equal thinnings (about "
                "the robot joint's 0.0015 in)"),
            Key("motor_body_diameter_mm", 28, "a small servo motor with encoder"),
            Key("motor_body_length_mm", 40),
            Key("motor_flange_mm", 28),
            Key("motor_flange_thickness_mm", 3),
            Key("motor_shaft_diameter_mm", 5),
            Key("motor_shaft_length_mm", 3),
            Key("cluster_bearing_outer_diameter_mm", 22, "608 bearing, 8 x 22 x 7 mm"),
            Key("cluster_bearing_width_mm", 7),
            Key("input_bearing_outer_diameter_mm", 13, "695 bearing, 5 x 13 x 4 mm"),
            Key("input_bearing_width_mm", 4),
            Key("output_bearing_outer_diameter_mm", 37, "6805 thin-section bearing, 25 x 37 x 7 mm"),
            Key("output_bearing_width_mm", 7),
            Key("carriage_plate_thickness_mm", 3, "aluminium"),
            Key("carriage_width_mm", 24),
            Key("link_radius_mm", 68, "the cluster gears reach 61.4 mm from the symmetry line; 3.6 mm inside "
                "the walls"),
            Key("link_wall_mm", 3),
            Key("link_floor_mm", 4),
            Key("link_top_clearance_mm", 2.5),
            Key("spring_y_offset_mm", 14),
            Key("spring_model", "helix"),
        )),
        Table("export", (
            Key("stl_chordal_tolerance_mm", 0.005, "gear STL within 5 um of the exact flanks"),
            Key("stl_chordal_tolerance_parts_mm", 0.05),
            Key("stl_angular_tolerance_deg", 30),
            Key("render_view", [-60, 30]),
        )),
    ))


# ---------------------------------------------------------------- split pinion

_SPLIT_PINION = Starter(
    "split_pinion",
    "a Type 1 concentric split pinion (Hale & Slocum 1994, Fig. 8), metric",
    "The structure of assemblies/split_pinion.toml at another size: module 1 mm, two 24-tooth pinions side by "
    "side on one 96-tooth output (4:1). The stiff path is a wide pinion on a hollow shaft; the compliant path a "
    "narrow pinion on an inner shaft that runs through the hollow one to a clamp collar, the frictional "
    "interface where the preload is set (wind the inner shaft, then clamp). The inner shaft's torsion is the "
    "loop's compliance, sized below for the loop errors.",
    (
        Table("", (
            Key("description", "Metric Type 1 split pinion with a frictional-interface preload (geargen starter)"),
            Key("length_unit", "mm"),
        )),
        Table("drive", (
            Key("type", "type1", "the compliant path carries the preload only, the stiff one the load"),
            Key("preload", "frictional_interface"),
        )),
        Table("gear_defaults", (
            Key("module_mm", 1.0),
            Key("pressure_angle_deg", 20),
        )),
        Table("gears.pinion_stiff", (
            Key("teeth", 24),
            Key("face_width_mm", 10, "carries the drive load"),
            Key("bore_diameter_mm", 12, "on the hollow shaft (= [parts] hollow_shaft_outer_diameter)"),
        ), "outer (stiff) path"),
        Table("gears.pinion_compliant", (
            Key("teeth", 24),
            Key("face_width_mm", 6, "carries the preload only: a narrower face"),
            Key("bore_diameter_mm", 6.5, "the inner shaft fills it (its one home)"),
        ), "inner (compliant) path"),
        Table("gears.output", (
            Key("teeth", 96, "4:1 with either pinion"),
            Key("face_width_mm", 18, "spans both pinions: 10 + 2 gap + 6"),
            Key("bore_diameter_mm", 20),
        )),
        Table("stiffness", (
            Key("elastic_modulus_GPa", 207),
            Key("shear_modulus_GPa", 79.3),
            Key("reduce_to", "output", "the split pinion of [layout]: each component sits on the shaft or the gear "
                "it names, whose speed comes from the teeth (\"input\", the pinions' shaft, turns 96 / 24 = 4 times "
                "the output)"),
        ), "Inner shaft sizing. Loop error (runout of the two pinion halves against each other plus "
           "tooth-to-tooth, about 20 um at the output's 48 mm pitch radius): 400 urad at the output. Preload "
           "9 N·m (a little above the 8 N·m maximum load: the paper's rule for Type 1); preload band 20 % peak "
           "to peak: k_L = 0.2 x 9 / 400e-6 = 4500 N·m/rad at the output, 281 N·m/rad on the pinion shaft "
           "(ratio 4 squared). The compliant path is almost all shaft, so G J / L = 281 N·m/rad with L = 60 mm "
           "gives d = (32 x 281e3 x 60 / (pi x 79.3e3))^(1/4) = 6.8 mm: 6.5 mm, a little softer. "
           "With each pinion's support (below) geargen stiffness shows the band: 8.5 to 9.5 N·m (12 %)."),
        Table("stiffness.components.mesh_stiff", (
            Key("kind", "mesh"),
            Key("gears", ["pinion_stiff", "output"]),
            Key("scope", "path1"),
        )),
        Table("stiffness.components.mesh_compliant", (
            Key("kind", "mesh"),
            Key("gears", ["pinion_compliant", "output"]),
            Key("scope", "path2"),
        )),
        Table("stiffness.components.hollow_shaft", (
            Key("kind", "shaft_torsion"),
            Key("gear", "pinion_stiff"),
            Key("from_geometry", True, "the placed hollow shaft: its lower end, where the drive turns it, to the "
                "wide pinion's mid-face"),
            Key("scope", "path1"),
        ), "the stiff path's shaft between the input and the wide pinion"),
        Table("stiffness.components.inner_shaft", (
            Key("kind", "shaft_torsion"),
            Key("gear", "pinion_compliant"),
            Key("from_geometry", True, "d = the narrow pinion's bore, L = 60 mm from [parts]"),
            Key("scope", "path2"),
        ), "the compliant path: the placed inner shaft, collar face to narrow pinion"),
        Table("stiffness.components.stiff_support", (
            Key("kind", "shaft_support"),
            Key("gear", "pinion_stiff"),
            Key("from_geometry", True, "overhangs its bearing pair (20 mm apart) by 8.5 mm"),
            Key("stiffness_N_per_um", 40, "per bearing, radial"),
            Key("scope", "path1"),
        ), "each pinion on its placed shaft and supports"),
        Table("stiffness.components.compliant_support", (
            Key("kind", "shaft_support"),
            Key("gear", "pinion_compliant"),
            Key("from_geometry", True, "between the clamp collar and the outboard bearing"),
            Key("stiffness_N_per_um", 40),
            Key("scope", "path2"),
        )),
        Table("preload", (
            Key("max_output_torque_Nm", 8),
            Key("preload_Nm", 9, "a little above the maximum load (Type 1)"),
            Key("loop_error_rotation_urad", 400, "anticipated loop error at the output, peak to peak"),
        )),
        Table("layout", (
            Key("kind", "split_pinion"),
            Key("model_tooth_thickness", "mid_tolerance"),
            Key("loaded_flank_gap_mm", 0.0005, "0.5 um, so that the solids do not touch"),
            Key("centre_distance_mm", 60.0, "standard (24 + 96) x 1 / 2"),
            Key("pinion_axial_gap_mm", 2),
            Key("circumferential_backlash_min_mm", 0.04, "each pinion's own mesh with the output"),
            Key("circumferential_backlash_max_mm", 0.08),
        ), "The assembly model (geargen build): placement, the other parts, exports."),
        Table("parts", (
            Key("bearing_clearance_mm", 0.5),
            Key("hollow_shaft_outer_diameter_mm", 12),
            Key("hollow_shaft_length_mm", 58, "the inner shaft then twists over 60 mm, collar to narrow pinion"),
            Key("bearing_outer_diameter_mm", 24, "61901-size pair, 12 x 24 x 6 mm, preloaded"),
            Key("bearing_width_mm", 6),
            Key("bearing_spacing_mm", 20, "a spacer between the pair, so the wide pinion overhangs a 20 mm base"),
            Key("collar_outer_diameter_mm", 22, "clamp collar: the frictional interface"),
            Key("collar_width_mm", 8),
            Key("collar_slot_mm", 1.2),
            Key("compliant_bearing_outer_diameter_mm", 19, "outboard bearing above the narrow pinion, 6.5 x 19 x 6"),
            Key("compliant_bearing_width_mm", 6),
            Key("output_shaft_diameter_mm", 20, "= the output gear's bore"),
            Key("output_bearing_outer_diameter_mm", 32, "61804-size, 20 x 32 x 7 mm"),
            Key("output_bearing_width_mm", 7),
        )),
        Table("export", (
            Key("stl_chordal_tolerance_mm", 0.005, "gear STL within 5 um of the exact flanks"),
            Key("stl_chordal_tolerance_parts_mm", 0.05),
            Key("stl_angular_tolerance_deg", 30),
            Key("render_view", [-55, 30]),
        )),
    ))

STARTERS: dict[str, Starter] = {s.kind: s for s in (_DUAL_PINION, _SPLIT_PINION)}


# ---------------------------------------------------------------- writing


def toml_value(value: Any) -> str:
    """``value`` as TOML (numbers, strings, booleans and lists of them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"no TOML form for {value!r}")


def _comment_lines(text: str, indent: str = "") -> list[str]:
    return [indent + "# " + line for line in textwrap.wrap(text, LINE_WIDTH - len(indent) - 2)]


def starter_data(kind: str, name: str) -> dict[str, Any]:
    """The parsed form of the starter ``kind`` named ``name`` (what ``tomllib`` reads back)."""
    data: dict[str, Any] = {"name": name}
    for table in STARTERS[kind].tables:
        target = data
        for part in table.header.split(".") if table.header else ():
            target = target.setdefault(part, {})
        for k in table.keys:
            target[k.key] = k.value
    return data


def starter_text(kind: str, name: str) -> str:
    """The commented TOML of the starter ``kind`` (one of :data:`STARTERS`) with ``name = name``."""
    if kind not in STARTERS:
        raise DesignError("KIND", f"{kind!r} is not a starter", ", ".join(STARTERS))
    starter = STARTERS[kind]
    data = starter_data(kind, name)
    lines = [f"# {name}: {starter.summary}.", "#"]
    lines += _comment_lines(starter.intro)
    lines += ["#"] + _comment_lines(f"Written by `geargen new {kind}`. Each key's comment gives its meaning and "
                                    "[unit]; docs/design-files.md lists every key of every section. Try it: "
                                    f"geargen check {name}.toml, then geargen build {name}.toml.") + [""]
    top = Table("", (Key("name", name),) + starter.tables[0].keys) if starter.tables[0].header == "" else None
    for table in ([top] if top else []) + [t for t in starter.tables if t.header]:
        path = tuple(table.header.split(".")) if table.header else ()
        if table.note:
            lines += _comment_lines(table.note)
        if table.header:
            lines.append(f"[{table.header}]")
        for k in table.keys:
            schema = key_schema(data, path + (k.key,))
            if schema is None or not schema.help:
                raise KeyError(f"starter {kind}: {'.'.join(path + (k.key,))} has no schema with a meaning")
            if k.why:
                lines += _comment_lines(k.why)
            assignment = f"{k.key} = {toml_value(k.value)}"
            column = max(COMMENT_COLUMN, len(assignment) + 2)
            if LINE_WIDTH - column < 40:  # a long value: its meaning goes above it
                lines += _comment_lines(key_comment(schema, k.key))
                lines.append(assignment)
                continue
            comment = textwrap.wrap(key_comment(schema, k.key), LINE_WIDTH - column - 2)
            lines.append(f"{assignment:<{column - 1}} # {comment[0]}")
            lines += [" " * column + "# " + more for more in comment[1:]]
        lines.append("")
    return "\n".join(lines)


__all__ = ["STARTERS", "Starter", "Table", "Key", "starter_text", "starter_data", "toml_value"]
