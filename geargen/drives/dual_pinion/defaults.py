"""The dual pinion's default hardware: what a design file that gives only gears and a synthesis is built with.

A dual-pinion drive with radial preload (the carriage hardware of `geargen.design.parts`) needs
shafts, bearings, a motor, a preload carriage on blade flexures, springs, a load rating and the
stiffness components. Where the file gives none of a section ([parts], [preload], [flexures],
[springs], [stiffness]) or a loop gear no bore, geargen sizes it from the gears by the rules
below, each value with the rule that chose it: `geargen check` prints them, the build's report
and `resolved.json` list them, and a designer copies a line into the file to change it. A
section or bore the file gives is never changed; a partial [parts] is completed key by key. A
dual pinion with [stages] gets its [parts] only (its file gives the other sections).

Rules (lengths in mm; inch designs are rounded to 1/32 in and use inch bearings):

- shaft and bore: the largest standard bearing bore no larger than a third of the reference
  diameter of the smallest gear on the shaft, nor than its root diameter less a rim of 2.5
  modules each side; its bearing from the standard series (ISO 15 dimension series 18, shielded
  widths; inch: ABMA R series). A bore the file gives must be a standard one;
- load (`[preload] max_output_torque`): the Lewis bending rating of the loop's two meshes at 110
  MPa (through-hardened steel, half the AGMA strength of grade 1 at 250 HB), 20 deg full-depth
  form factors of the weaker gear, the narrower face, the loaded path carrying half the load plus
  the preload; gears under 20 deg pressure angle need the torque given;
- preload: 0.6 of that load (the paper asks for at least half), set by two music-wire springs of
  index 10 and 6 active coils, the thinnest standard wire that stays below 0.45 of its tensile
  strength even closed solid, installed 15 % of the working deflection above solid height;
- carriage: three spring-steel blades 0.25 mm (0.010 in) thick, long enough for half their
  allowable stress at the 0.5 mm (0.02 in) travel; plates 2.5 mesh-1 modules thick, at least 3 mm;
- motor: the smallest NEMA frame whose torque covers the motor's share of the rated load (the
  designer adds for acceleration), through a 15:30 bevel pair of the input's module, the bevel
  gear high enough on the input shaft for the motor to clear the carriage plate; with [stages],
  through the stages instead (their ratios, a planetary's 1 + ring / sun), and the stage shafts'
  bearings (`stage_bearing_*`) the series 18 bearing of the stage shafts' bore (with no stage
  shaft, of the motor shaft's, the first driver's bore);
- the springs' offset from the symmetry line: side by side, from the file's [springs] where it
  gives them;
- stiffness: each cluster shaft twisting and bending on its bearings (10 N/um each) and the input
  shaft, all from the placed shafts' lengths, the meshes from the gears.

Pure arithmetic on the parsed file: no CAD kernel.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

from geargen.design.catalogue import (STEEL_E_GPA, STEEL_G_GPA, WIRE_DIAMETERS, Completion, Readers, coil_rate,
                                      given_number, in_unit, motor_for, music_wire_allowable, partial_table,
                                      put_bearing, put_motor, rounded, standard_bearing, standard_bores,
                                      wahl_stress_per_newton)
from geargen.design.schema import PLAUSIBLE
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN, length_text

#: through-hardened steel gears: about half the AGMA bending strength of grade 1 at 250 HB (221 MPa)
STEEL_BENDING_ALLOWABLE_MPA = 110.0
#: loop preload as a fraction of the rated output torque: above the paper's half, for the loop error band
PRELOAD_FRACTION = 0.6
#: radial stiffness of one small deep-groove ball bearing with light axial preload (N/um)
BEARING_STIFFNESS_N_PER_UM = 10.0

#: Lewis form factor, 20 deg full-depth teeth, load at the tip: (teeth, Y)
LEWIS_Y_20DEG = ((12, 0.245), (13, 0.261), (14, 0.277), (15, 0.290), (16, 0.296), (17, 0.303), (18, 0.309),
                 (19, 0.314), (20, 0.322), (21, 0.328), (22, 0.331), (24, 0.337), (26, 0.346), (28, 0.353),
                 (30, 0.359), (34, 0.371), (38, 0.384), (43, 0.397), (50, 0.409), (60, 0.422), (75, 0.435),
                 (100, 0.447), (150, 0.460), (300, 0.472), (400, 0.480))

SPRING_INDEX, SPRING_ACTIVE_COILS, SPRING_CLASH = 10.0, 6, 0.15
BEVEL_TEETH = (15, 30)
LOOP = ("input", "cluster_large", "cluster_small", "output")
#: [parts] keys that say the same thing in two ways: giving one gives the other
SYNONYMS = {"bevel_module": "bevel_diametral_pitch", "bevel_diametral_pitch": "bevel_module"}


def lewis_form_factor(teeth: int) -> float:
    """Y of a 20 deg full-depth tooth (interpolated in 1/z between the table's counts)."""
    if teeth < LEWIS_Y_20DEG[0][0]:
        raise DesignError("gears.teeth", f"{teeth} teeth: below the Lewis table", f">= {LEWIS_Y_20DEG[0][0]}")
    for (z0, y0), (z1, y1) in zip(LEWIS_Y_20DEG, LEWIS_Y_20DEG[1:]):
        if z0 <= teeth <= z1:
            f = (1 / z0 - 1 / teeth) / (1 / z0 - 1 / z1)
            return y0 + f * (y1 - y0)
    return LEWIS_Y_20DEG[-1][1]


def lewis_force(gear, allowable: float = STEEL_BENDING_ALLOWABLE_MPA, face: float | None = None) -> float:
    """Tangential tooth force (N) at which the Lewis root stress ``F / (b m Y)`` reaches ``allowable``."""
    return allowable * (face or gear.face_width) * gear.module * lewis_form_factor(gear.teeth)


def rated_output_torque(gears: Mapping[str, Any], preload_fraction: float = PRELOAD_FRACTION) -> float:
    """Largest output torque (N·mm) the loop's meshes carry by Lewis, the loaded path carrying the
    load's half plus the preload (``1/2 + preload_fraction`` of the torque)."""
    share = 0.5 + preload_fraction
    inp, large, small, out = (gears[n] for n in LOOP)
    ratio2 = out.teeth / small.teeth
    limits = []
    for a, b, radius_at_output in ((inp, large, large.reference_radius * ratio2), (small, out, out.reference_radius)):
        face = min(a.face_width, b.face_width)
        force = min(lewis_force(a, face=face), lewis_force(b, face=face))
        limits.append(force * radius_at_output / share)
    return min(limits)


def shaft_bearing(gears, unit: str, shaft: str):
    """The bearing (and bore) of a shaft carrying ``gears``: see the module's rule."""
    limit = min(min(2 * g.reference_radius / 3, 2 * g.root_radius_standard - 5 * g.module) for g in gears)
    found = standard_bearing(limit, unit)
    if found is None:
        names = ", ".join(g.name for g in gears)
        raise DesignError(f"gears.{gears[0].name}.bore_diameter", f"missing, and no standard bearing fits the "
                          f"{shaft} shaft under {names} (at most {length_text(limit, unit, 3)})", "bore_diameter_* and a [parts] table")
    return found


def _spring(force_each: float) -> dict[str, float]:
    """A music-wire compression spring (mm, N) giving ``force_each`` at its installed length, closed
    solid still below the allowable stress (0.45 of the wire's tensile strength)."""
    for d in WIRE_DIAMETERS:
        D = SPRING_INDEX * d
        allowable = music_wire_allowable(d)
        rate = coil_rate(d, D, SPRING_ACTIVE_COILS)
        deflection = force_each / rate
        solid = d * (SPRING_ACTIVE_COILS + 2)  # squared and ground ends: two dead coils
        clash = max(SPRING_CLASH * deflection, 1.2 * d)  # the swept-wire model needs a pitch above the wire
        if wahl_stress_per_newton(d, D) * rate * (deflection + clash) <= allowable:
            installed = solid + clash
            return dict(wire=d, mean=D, installed=installed, free=installed + deflection, allowable=allowable)
    raise DesignError("preload.max_output_torque", f"needs {force_each:.4g} N per spring, beyond the "
                      f"{WIRE_DIAMETERS[-1]} mm music wire of the default springs", "a [springs] table")


def _file_spring(table: Any) -> dict[str, float] | None:
    """The file's [springs] wire and mean coil diameter (mm), or None when it does not give both."""
    if not isinstance(table, Mapping):
        return None
    wire, mean = given_number(table, "wire_diameter"), given_number(table, "mean_coil_diameter")
    return dict(wire=wire, mean=mean) if wire is not None and mean is not None else None


def _needs_defaults(data: Mapping[str, Any]) -> bool:
    drive = data.get("drive") or {}
    layout = data.get("layout") or {}
    if not all(isinstance(data.get(k, {}), Mapping) for k in ("drive", "layout", "synthesis", "gears", "gear_defaults",
                                                               "preload")):
        return False  # malformed: the validating load names the problem
    return (drive.get("type") == "type2" and drive.get("preload") == "radial" and "synthesis" in data
            and layout.get("kind", "dual_pinion") == "dual_pinion" and not data.get("beam_pinion"))


def complete(data: Mapping[str, Any], readers: Readers, fields: list) -> tuple[dict[str, Any], tuple]:
    """``data`` (the parsed design file) completed with the dual pinion's default hardware (the
    module's rules), and what was added (:class:`geargen.design.catalogue.Defaulted`); ``fields``:
    the kind's [parts] fields. Unchanged (and nothing added) where the file gives every section. A
    drive with [stages] gets its [parts] only: its file gives the other sections."""
    if not isinstance(data, Mapping) or not _needs_defaults(data):
        return dict(data) if isinstance(data, Mapping) else data, ()
    wanted = [s for s in ("parts", "preload", "flexures", "springs", "stiffness") if s not in data]
    if partial_table(data.get("parts"), fields):
        wanted.append("parts")  # a partial [parts]: the keys it leaves out are defaulted
    if data.get("stages") and (set(wanted) - {"parts"} or not isinstance(data["stages"], Mapping)):
        return dict(data), ()  # the stages' own sections are the file's: the validating load names what is missing
    gear_tables = data.get("gears") or {}
    defaults_table = data.get("gear_defaults") or {}
    if not all(isinstance(t, Mapping) for t in gear_tables.values()):
        return dict(data), ()
    bare = [n for n in LOOP if isinstance(gear_tables.get(n), dict)
            and not any(k.startswith("bore_diameter") for k in {**defaults_table, **gear_tables[n]})]
    if not wanted and not bare:
        return dict(data), ()
    try:
        rough = readers.design(data)  # the gears as read; the validating load reports any problem
    except DesignError:
        return dict(data), ()
    if any(n not in rough.gears for n in LOOP):
        return dict(data), ()
    completion = Completion(data, SYNONYMS, rough.length_unit)
    put = completion.put
    unit = rough.length_unit
    sfx = unit  # length keys end in the design's unit

    g = rough.gears
    # --- shafts and bearings
    shafts = {"input": [g["input"]], "cluster": [g["cluster_large"], g["cluster_small"]], "output": [g["output"]]}
    bearings = {}
    for shaft, members in shafts.items():
        given = [m.hub.bore_diameter for m in members if m.name not in bare and m.hub.bore_diameter > 0]
        od = given_number(completion.parts, f"{shaft}_bearing_outer_diameter")
        width = given_number(completion.parts, f"{shaft}_bearing_width")
        if given:
            bore = given[0]
            found = standard_bearing(bore, unit)
            if found is None or abs(found[0] - bore) > 1e-6:
                if "parts" in wanted and (od is None or width is None):
                    key = f"parts.{shaft}_bearing_outer_diameter_{unit}" if od is None else \
                        f"parts.{shaft}_bearing_width_{unit}"
                    raise DesignError(key, f"missing, and the {shaft} shaft's bore {in_unit(bore, unit):g} {unit} "
                                      f"(gears.{members[0].name}) is no standard bearing bore to size it from",
                                      "the bearing's outer diameter and width, or a standard bore: "
                                      + standard_bores(unit))
                found = (bore, od, width, "the file's bearing")
            bearings[shaft] = found
        else:
            bearings[shaft] = shaft_bearing(members, unit, shaft)
        for m in members:
            if m.name in bare:
                put("gears", f"{m.name}.bore_diameter_{sfx}", in_unit(bearings[shaft][0], unit),
                    f"the {shaft} shaft: the largest {bearings[shaft][3]} bearing bore the gears allow")
    # --- rating and preload
    if "preload" in wanted and min(g[n].pressure_angle for n in LOOP) < math.radians(20) - 1e-9:
        raise DesignError("preload", "missing: the default rating's Lewis factors are for 20 deg teeth or more",
                          "a [preload] table with max_output_torque_*")
    rated = rated_output_torque(g)  # N·mm
    torque_suffix = "Nm" if unit == "mm" else "in_lbf"
    torque_key, torque_scale = f"max_output_torque_{torque_suffix}", readers.torque_units[torque_suffix]
    if "preload" in wanted:
        value = float(f"{rated / torque_scale:.2g}")
        put("preload", torque_key, value, f"Lewis rating of the loop's meshes at {STEEL_BENDING_ALLOWABLE_MPA:g} MPa "
            f"(through-hardened steel), the loaded path carrying {0.5 + PRELOAD_FRACTION:g} x the output torque")
        put("preload", "line_of_action_angle_deg", 0.0, "the optimal configuration of Fig. 9")
        max_torque = value * torque_scale
    else:
        try:
            max_torque = readers.preload(data["preload"]).max_output_torque
        except DesignError:
            return dict(data), ()  # the validating load reports the [preload] problem
    # the radial preload lever and carriage force of geargen.core.stiffness (preload_lever, carriage_force)
    # at the optimal line of action; written out because the design layer sits below core. A test holds
    # the two equal.
    lever = 1.0 / (g["output"].teeth / g["cluster_small"].teeth * g["cluster_large"].base_radius)
    force_on_carriage = 2.0 * lever * PRELOAD_FRACTION * max_torque
    m1 = g["input"].module
    gap = 0.5
    plate = max(3.0, 2.5 * m1)
    # --- springs and blades (the file's springs, where it gives them, set the springs' offset)
    spring = _file_spring(data.get("springs")) if "springs" not in wanted else None
    spring = spring or _spring(force_on_carriage / 2)
    if "springs" in wanted:
        why = (f"two springs give {force_on_carriage:.3g} N on the carriage: preload {PRELOAD_FRACTION:g} x the rated "
               "torque")
        put("springs", "count", 2, why)
        put("springs", f"wire_diameter_{sfx}", in_unit(spring["wire"], unit), "music wire: the thinnest standard "
            "size whose stress stays below 0.45 of its tensile strength, even closed solid")
        put("springs", f"mean_coil_diameter_{sfx}", in_unit(spring["mean"], unit), f"spring index {SPRING_INDEX:g}")
        put("springs", "active_coils", SPRING_ACTIVE_COILS, "a soft spring: k3 well below the paths")
        put("springs", "end_type", "squared_ground", "seats square on the carriage and the link wall")
        put("springs", f"free_length_{sfx}", in_unit(spring["free"], unit), "installed length plus the working "
            "deflection")
        put("springs", f"installed_length_{sfx}", in_unit(spring["installed"], unit), f"solid height plus "
            f"{SPRING_CLASH:.0%} of the working deflection (at least 1.2 wires)")
        put("springs", "shear_modulus_GPa", STEEL_G_GPA, "music wire")
        put("springs", "allowable_shear_stress_MPa", round(spring["allowable"], 1),
            "0.45 of the wire's tensile strength 2211 / d^0.145 MPa")
    travel = 0.5 if unit == "mm" else 0.02 * MM_PER_IN
    if "flexures" in wanted:
        thickness = 0.25 if unit == "mm" else 0.010 * MM_PER_IN
        allowable = 500.0
        # guided blade: stress 3 E t x / L^2 at the travel x; kept below half the allowable
        length = math.sqrt(3 * STEEL_E_GPA * 1e3 * thickness * travel / (0.5 * allowable))
        width = max(8.0, 2 * (bearings["input"][1] / 2 + plate))
        why = "three spring-steel blades under the carriage"
        put("flexures", "count", 3, why)
        put("flexures", f"thickness_{sfx}", in_unit(thickness, unit), "hardened spring-steel shim")
        put("flexures", f"length_{sfx}", rounded(max(length, 20.0), unit), "stress at the travel below half the "
            "allowable")
        put("flexures", f"width_{sfx}", rounded(width, unit), "the input bearing's seat and the carriage plates")
        put("flexures", "elastic_modulus_GPa", STEEL_E_GPA, "spring steel")
        put("flexures", "allowable_stress_MPa", allowable, "hardened spring-steel shim, long life")
        put("flexures", f"travel_{sfx}", in_unit(travel, unit), "either way from neutral: the loop errors and "
            "assembly adjustment")
        put("flexures", f"neutral_offset_{sfx}", 0.0, "blades unstressed at the operating position")
    # --- [parts]: bearings, motor, carriage, link
    if "parts" in wanted:
        _default_parts(completion, g, unit, bearings, max_torque, plate, gap, spring)
    # --- [stiffness]: the placed shafts' lengths (from_geometry), the meshes from the gears
    if "stiffness" in wanted:
        put("stiffness", "elastic_modulus_GPa", STEEL_E_GPA, "steel gears and shafts")
        put("stiffness", "shear_modulus_GPa", STEEL_G_GPA, "steel")
        put("stiffness", "reduce_to", "output", "the joint's side")
        for name, kind, extra, why in (
                ("cluster_shaft", "shaft_torsion", {"shaft": "cluster"}, "each cluster shaft twisting between its gears"),
                ("cluster_support", "shaft_support", {"gear": "cluster_small",
                                                      "stiffness_N_per_um": BEARING_STIFFNESS_N_PER_UM},
                 "the cluster pinion on its shaft and two bearings"),
                ("input_shaft", "shaft_torsion", {"shaft": "input", "scope": "common"},
                 "the input shaft from its gear to the bevel gear")):
            put("stiffness", f"components.{name}.kind", kind, why)
            for key, value in extra.items():
                put("stiffness", f"components.{name}.{key}", value, why)
            put("stiffness", f"components.{name}.from_geometry", True, "lengths of the placed shafts")
    return completion.result()


def _default_parts(completion: Completion, g, unit: str, bearings, max_torque: float, plate: float, gap: float,
                   spring) -> None:
    """The carriage hardware's [parts] (see the module's rules): every key the file's [parts]
    leaves out, each sized from what the file gives."""
    put = completion.put

    def number(name, default):
        if name == "bevel_module":
            pitch = given_number(completion.parts, "bevel_diametral_pitch_per_in")
            if pitch is not None:
                return MM_PER_IN / pitch
        return completion.number(name, default)

    m1 = g["input"].module
    for shaft in ("cluster", "input", "output"):
        d, od, w, name = bearings[shaft]
        why = f"{name}, {d:.4g} x {od:.4g} x {w:.4g} mm"
        put("parts", f"{shaft}_bearing_outer_diameter_{unit}", in_unit(od, unit), why)
        put("parts", f"{shaft}_bearing_width_{unit}", in_unit(w, unit), why)
    put("parts", f"bearing_clearance_{unit}", rounded(gap, unit), "axial gap between a bearing and a gear face")
    plate = number("carriage_plate_thickness", plate)
    gap = number("bearing_clearance", gap)
    inp = g["input"]
    if completion.data.get("stages"):
        _stage_drive(completion, g, unit, max_torque)
    else:
        _bevel_drive(completion, g, unit, bearings, max_torque, plate, gap, number)
    put("parts", f"carriage_plate_thickness_{unit}", rounded(plate, unit), "2.5 mesh-1 modules, at least 3 mm")
    d_in = max(2 * inp.tip_radius, bearings["input"][1])
    put("parts", f"carriage_width_{unit}", rounded(d_in + 4 * plate, unit), "the input gear and its bearing seats "
        "with two plates either side")
    # the link's round end encloses every gear with a wall's clearance
    reach = _loop_reach(completion.data, g)
    wall = max(3.0, 2.0 * m1)
    put("parts", f"link_wall_{unit}", rounded(wall, unit), "two mesh-1 modules, at least 3 mm")
    put("parts", f"link_floor_{unit}", rounded(wall + 1.0, unit), "a wall plus 1 mm: the bosses stand on it")
    put("parts", f"link_radius_{unit}", rounded(reach + 2 * gap + wall + 2.0, unit), "the gears' reach from the "
        "symmetry line, 2 mm inside the walls")
    put("parts", f"link_top_clearance_{unit}", rounded(2.5, unit), "above the highest part")
    outer = spring["mean"] + spring["wire"]
    put("parts", f"spring_y_offset_{unit}", rounded(0.75 * outer + 1.0, unit), "the two springs side by side, "
        "clear of each other")


def _bevel_drive(completion: Completion, g, unit: str, bearings, max_torque: float, plate: float, gap: float,
                 number) -> None:
    """The motor driving the input through the 15:30 bevel pair (see the module's rules)."""
    put = completion.put
    m1 = g["input"].module
    # the bevel pair: 15:30 of the input's module, face a third of the cone distance
    zp, zg = (int(number("bevel_pinion_teeth", BEVEL_TEETH[0])), int(number("bevel_gear_teeth", BEVEL_TEETH[1])))
    module = number("bevel_module", m1)
    cone = math.hypot(zp, zg) * module / 2
    ratio = g["output"].teeth / g["cluster_small"].teeth * g["cluster_large"].teeth / g["input"].teeth
    motor_torque = max_torque / (ratio * zg / zp) * 1e-3
    frame = motor_for(motor_torque)
    _, flange, _, shaft_d, _ = frame
    put("parts", "bevel_pinion_teeth", zp, "a 2:1 bevel pair between motor and input")
    put("parts", "bevel_gear_teeth", zg, "a 2:1 bevel pair between motor and input")
    if unit == "mm":
        put("parts", "bevel_module_mm", round(module, 6), "the input gear's module")
    else:
        put("parts", "bevel_diametral_pitch_per_in", round(MM_PER_IN / module, 6), "the input gear's pitch")
    put("parts", f"bevel_face_width_{unit}", rounded(cone / 3.5, unit, up=False), "under a third of the cone distance")
    # the bevel gear's heel above the carriage arm, which holds the input's upper bearing
    inp = g["input"]
    above = inp.face_width / 2 + gap + bearings["input"][2] + plate + 2 * gap
    # the motor lies on the pinion's axis, at the gear's cone apex (zg m / 2 / tan(gamma_g) above its
    # heel): its body clears the carriage's base plate by a plate (the saddle)
    apex = zg * module / 2 * zp / zg
    below = inp.face_width / 2 + gap + bearings["input"][2]
    above = max(above, flange / 2 + plate + gap - apex - below)
    # the toothed gear's back (the plane of its heel root circle, dedendum 1.25 m) lies below its
    # heel pitch circle: R_e cos(delta_f) - r / tan(delta) further down
    delta = math.atan2(zg, zp)
    above += cone * math.cos(delta - math.atan(1.25 * module / cone)) - zg * module / 2 / math.tan(delta)
    put("parts", f"input_shaft_to_bevel_{unit}", rounded(above, unit), "the bevel gear's heel clear above the "
        "carriage arm over the input's upper bearing")
    if not (completion.data.get("train") or {}).get("upstream_backlash_arcmin"):
        put("parts", f"bevel_backlash_{unit}", in_unit(0.0015 * MM_PER_IN, unit),
            "0.0015 in circumferential, the fine-pitch allowance of AGMA 2002 (the robot joint's)")
    put_motor(completion, frame, motor_torque)
    put("parts", f"motor_shaft_diameter_{unit}", in_unit(shaft_d, unit) if unit == "mm" else
        round(shaft_d / MM_PER_IN, 4), f"{frame[0]} envelope: the smallest frame for {motor_torque:.3g} N·m at the motor")
    put("parts", f"motor_shaft_length_{unit}", rounded(3.0, unit), "the stub from the flange to the bevel pinion")


def _stage_drive(completion: Completion, g, unit: str, max_torque: float) -> None:
    """The motor driving the input through the design's [stages] standing on the carriage (see the
    module's rules): the stage shafts' bearings and the motor's envelope."""
    stages = [t for t in completion.data["stages"].values() if isinstance(t, Mapping)]
    ratio = g["output"].teeth / g["cluster_small"].teeth * g["cluster_large"].teeth / g["input"].teeth
    shafts = []  # the gears on each stage shaft: a stage's driven gear with the next stage's driver
    first = None
    for i, st in enumerate(stages):
        if st.get("kind") == "planetary":
            sun, ring = g.get(st.get("sun")), g.get(st.get("ring"))
            if sun is None or ring is None:
                return  # the validating load names the stage's missing gear
            ratio *= 1 + ring.teeth / sun.teeth
            first = first or sun
            continue
        driver, driven = g.get(st.get("driver")), g.get(st.get("driven"))
        if driver is None or driven is None:
            return
        ratio *= driven.teeth / driver.teeth
        first = first or driver
        if i + 1 < len(stages) and stages[i + 1].get("kind") != "planetary":
            shafts.append(driven)
    # a stage shaft's bearing, or with none the motor shaft's (the first driver's bore)
    shaft_gear = max(shafts, key=lambda gear: gear.hub.bore_diameter) if shafts else first
    if shaft_gear is None:
        return
    put_bearing(completion, unit, "stage_bearing", shaft_gear.hub.bore_diameter, "18", shaft_gear.name,
                "the stage shafts' bearings" if shafts else "no stage shaft: the motor shaft's size")
    motor_torque = max_torque / ratio * 1e-3
    put_motor(completion, motor_for(motor_torque), motor_torque)


def _loop_reach(data, gears) -> float:
    """How far from the symmetry line (y = 0) the loop's gears can reach: the clusters' tips at the
    synthesis's mesh-2 centre distance and any direction, the output's tip (mm)."""
    syn = data.get("synthesis") or {}
    a2 = None
    for unit, scale in LENGTH_SUFFIXES.items():
        value = syn.get(f"centre_distance_mesh2_{unit}")
        # read before the file is validated: an absurd value (inf, 1e308) is left to the validation to refuse
        if isinstance(value, (int, float)) and not isinstance(value, bool) and 0 < value * scale <= PLAUSIBLE["length"][1]:
            a2 = value * scale
    small, large, out = gears["cluster_small"], gears["cluster_large"], gears["output"]
    if a2 is None:
        a2 = small.reference_radius + out.reference_radius
    return max(a2 + max(small.tip_radius, large.tip_radius), out.tip_radius)


__all__ = ["complete", "lewis_form_factor", "lewis_force", "rated_output_torque", "shaft_bearing",
           "STEEL_BENDING_ALLOWABLE_MPA", "PRELOAD_FRACTION", "LOOP"]
