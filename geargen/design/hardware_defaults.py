"""Default hardware: what a design file that gives only gears and a synthesis is built with.

A dual-pinion drive with radial preload (the carriage hardware of `geargen.design.parts`) needs
shafts, bearings, a motor, a preload carriage on blade flexures, springs, a load rating and the
stiffness components. Where the file gives none of a section ([parts], [preload], [flexures],
[springs], [stiffness]) or a loop gear no bore, geargen sizes it from the gears by the rules
below, each value with the rule that chose it: `geargen check` prints them, the build's report
and `resolved.json` list them, and a designer copies a line into the file to change it. A
section or bore the file gives is never changed. Drives with [stages], a split pinion or a
beam-spring pinion give their own hardware.

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
  gear high enough on the input shaft for the motor to clear the carriage plate;
- stiffness: each cluster shaft twisting and bending on its bearings (10 N/um each) and the input
  shaft, all from the placed shafts' lengths, the meshes from the gears.

Pure arithmetic on the parsed file: no CAD kernel.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any, Mapping

from geargen.errors import DesignError
from geargen.units import MM_PER_IN

#: through-hardened steel gears: about half the AGMA bending strength of grade 1 at 250 HB (221 MPa)
STEEL_BENDING_ALLOWABLE_MPA = 110.0
#: loop preload as a fraction of the rated output torque: above the paper's half, for the loop error band
PRELOAD_FRACTION = 0.6
#: radial stiffness of one small deep-groove ball bearing with light axial preload (N/um)
BEARING_STIFFNESS_N_PER_UM = 10.0

#: (bore, outer diameter, width, designation), mm: ISO 15 dimension series 18, shielded widths
METRIC_BEARINGS = (
    (3, 7, 3, "683ZZ"), (4, 9, 4, "684ZZ"), (5, 11, 5, "685ZZ"), (6, 13, 5, "686ZZ"), (7, 14, 5, "687ZZ"),
    (8, 16, 5, "688ZZ"), (9, 17, 5, "689ZZ"), (10, 19, 5, "6800ZZ"), (12, 21, 5, "6801ZZ"), (15, 24, 5, "6802ZZ"),
    (17, 26, 5, "6803ZZ"), (20, 32, 7, "6804ZZ"), (25, 37, 7, "6805ZZ"), (30, 42, 7, "6806ZZ"),
    (35, 47, 7, "6807ZZ"), (40, 52, 7, "6808ZZ"), (45, 58, 7, "6809ZZ"), (50, 65, 7, "6810ZZ"),
)
#: (bore, outer diameter, width, designation), inches: ABMA R series, shielded widths
INCH_BEARINGS = (
    (0.125, 0.375, 0.1562, "R2ZZ"), (0.1875, 0.5, 0.196, "R3ZZ"), (0.25, 0.625, 0.196, "R4ZZ"),
    (0.375, 0.875, 0.2812, "R6ZZ"), (0.5, 1.125, 0.3125, "R8ZZ"), (0.625, 1.375, 0.3438, "R10ZZ"),
    (0.75, 1.625, 0.4375, "R12ZZ"), (0.875, 1.875, 0.5, "R14ZZ"), (1.0, 2.0, 0.5, "R16ZZ"),
)

#: Lewis form factor, 20 deg full-depth teeth, load at the tip: (teeth, Y)
LEWIS_Y_20DEG = ((12, 0.245), (13, 0.261), (14, 0.277), (15, 0.290), (16, 0.296), (17, 0.303), (18, 0.309),
                 (19, 0.314), (20, 0.322), (21, 0.328), (22, 0.331), (24, 0.337), (26, 0.346), (28, 0.353),
                 (30, 0.359), (34, 0.371), (38, 0.384), (43, 0.397), (50, 0.409), (60, 0.422), (75, 0.435),
                 (100, 0.447), (150, 0.460), (300, 0.472), (400, 0.480))

#: NEMA frames as motor envelopes: (frame, flange side mm, body length mm, shaft mm, torque N·m)
MOTORS = (("NEMA 8", 20.3, 30.0, 4.0, 0.02), ("NEMA 11", 28.2, 32.0, 5.0, 0.06),
          ("NEMA 14", 35.2, 34.0, 5.0, 0.14), ("NEMA 17", 42.3, 40.0, 5.0, 0.40),
          ("NEMA 23", 56.4, 56.0, 6.35, 1.0), ("NEMA 34", 86.0, 80.0, 14.0, 3.5))

#: music-wire diameters (mm) and the tensile strength S = A / d^m (A in MPa mm^m)
WIRE_DIAMETERS = (0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.4, 1.6, 1.8, 2.0, 2.2, 2.5, 2.8, 3.0,
                  3.5, 4.0, 4.5, 5.0)
MUSIC_WIRE_A, MUSIC_WIRE_M = 2211.0, 0.145
SPRING_INDEX, SPRING_ACTIVE_COILS, SPRING_CLASH = 10.0, 6, 0.15
STEEL_E_GPA, STEEL_G_GPA = 207.0, 79.3
BEVEL_TEETH = (15, 30)
LOOP = ("input", "cluster_large", "cluster_small", "output")


@dataclass(frozen=True)
class Defaulted:
    """One value the file did not give: where it went (``section.key``), the value, the rule."""

    key: str
    value: Any
    why: str

    def __str__(self) -> str:
        return f"{self.key} = {self.value!r}  ({self.why})"


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


def _round(mm: float, unit: str, up: bool = True) -> float:
    """``mm`` rounded to 0.5 mm (or 1/32 in), up or down, in the design's unit."""
    step = 0.5 if unit == "mm" else MM_PER_IN / 32
    n = math.ceil(mm / step - 1e-9) if up else math.floor(mm / step + 1e-9)
    value = n * step
    return round(value, 6) if unit == "mm" else round(value / MM_PER_IN, 6)


def _in_unit(mm: float, unit: str) -> float:
    return round(mm if unit == "mm" else mm / MM_PER_IN, 6)


def standard_bearing(bore_mm_max: float, unit: str) -> tuple[float, float, float, str] | None:
    """The standard bearing (mm: bore, outer, width, designation) of the largest bore <= ``bore_mm_max``."""
    scale = 1.0 if unit == "mm" else MM_PER_IN
    table = METRIC_BEARINGS if unit == "mm" else INCH_BEARINGS
    fits = [b for b in table if b[0] * scale <= bore_mm_max + 1e-9]
    if not fits:
        return None
    d, od, w, name = fits[-1]
    return d * scale, od * scale, w * scale, name


def shaft_bearing(gears, unit: str, shaft: str):
    """The bearing (and bore) of a shaft carrying ``gears``: see the module's rule."""
    limit = min(min(2 * g.reference_radius / 3, 2 * g.root_radius_standard - 5 * g.module) for g in gears)
    found = standard_bearing(limit, unit)
    if found is None:
        names = ", ".join(g.name for g in gears)
        raise DesignError(f"gears.{gears[0].name}.bore_diameter", f"missing, and no standard bearing fits the "
                          f"{shaft} shaft under {names} (at most {limit:.3g} mm)", "bore_diameter_* and a [parts] table")
    return found


def _spring(force_each: float) -> dict[str, float]:
    """A music-wire compression spring (mm, N) giving ``force_each`` at its installed length, closed
    solid still below the allowable stress (0.45 of the wire's tensile strength)."""
    for d in WIRE_DIAMETERS:
        D = SPRING_INDEX * d
        allowable = 0.45 * MUSIC_WIRE_A / d ** MUSIC_WIRE_M
        wahl = (4 * SPRING_INDEX - 1) / (4 * SPRING_INDEX - 4) + 0.615 / SPRING_INDEX
        stress_per_newton = wahl * 8 * D / (math.pi * d ** 3)
        rate = STEEL_G_GPA * 1e3 * d ** 4 / (8 * D ** 3 * SPRING_ACTIVE_COILS)
        deflection = force_each / rate
        solid = d * (SPRING_ACTIVE_COILS + 2)  # squared and ground ends: two dead coils
        clash = max(SPRING_CLASH * deflection, 1.2 * d)  # the swept-wire model needs a pitch above the wire
        if stress_per_newton * rate * (deflection + clash) <= allowable:
            installed = solid + clash
            return dict(wire=d, mean=D, installed=installed, free=installed + deflection, allowable=allowable)
    raise DesignError("preload.max_output_torque", f"needs {force_each:.4g} N per spring, beyond the "
                      f"{WIRE_DIAMETERS[-1]} mm music wire of the default springs", "a [springs] table")


def _motor(torque_Nm: float):
    for frame in MOTORS:
        if frame[4] >= torque_Nm:
            return frame
    raise DesignError("preload.max_output_torque", f"the motor must give {torque_Nm:.3g} N·m, more than the largest "
                      "default frame", "a [parts] table with the motor")


def _needs_defaults(data: Mapping[str, Any]) -> bool:
    drive = data.get("drive") or {}
    layout = data.get("layout") or {}
    if not all(isinstance(data.get(k, {}), Mapping) for k in ("drive", "layout", "synthesis", "gears", "gear_defaults",
                                                               "preload")):
        return False  # malformed: the validating load names the problem
    return (drive.get("type") == "type2" and drive.get("preload") == "radial" and "synthesis" in data
            and layout.get("kind", "dual_pinion") == "dual_pinion" and not data.get("beam_pinion")
            and not data.get("stages"))


def default_hardware(data: Mapping[str, Any]) -> tuple[dict[str, Any], tuple[Defaulted, ...]]:
    """``data`` (the parsed design file) completed with the default hardware of its drive, and
    what was added; unchanged (and nothing added) where the file gives every section, or for a
    drive the defaults do not cover (a split pinion, a beam-spring pinion, [stages]: their files
    give their hardware)."""
    if not isinstance(data, Mapping) or not _needs_defaults(data):
        return dict(data) if isinstance(data, Mapping) else data, ()
    wanted = [s for s in ("parts", "preload", "flexures", "springs", "stiffness") if s not in data]
    if isinstance(data.get("parts"), Mapping):
        wanted.append("parts")  # a partial [parts]: the keys it leaves out are defaulted
    gear_tables = data.get("gears") or {}
    defaults_table = data.get("gear_defaults") or {}
    if not all(isinstance(t, Mapping) for t in gear_tables.values()):
        return dict(data), ()
    bare = [n for n in LOOP if isinstance(gear_tables.get(n), dict)
            and not any(k.startswith("bore_diameter") for k in {**defaults_table, **gear_tables[n]})]
    if not wanted and not bare:
        return dict(data), ()
    from geargen.design.assembly import design_from_dict
    try:
        rough = design_from_dict(data)  # the gears as read; the validating load reports any problem
    except DesignError:
        return dict(data), ()
    if any(n not in rough.gears for n in LOOP):
        return dict(data), ()
    out = copy.deepcopy(dict(data))
    added: list[Defaulted] = []
    unit = rough.length_unit
    sfx = unit  # length keys end in the design's unit

    def put(section: str, key: str, value: Any, why: str) -> None:
        if section == "parts" and _given(data.get("parts") or {}, key):
            return  # the file's value stands
        table = out.setdefault(section, {})
        if "." in key:  # a sub-table (stiffness.components.NAME)
            sub, key = key.rsplit(".", 1)
            for part in sub.split("."):
                table = table.setdefault(part, {})
            where = f"{section}.{sub}.{key}"
        else:
            where = f"{section}.{key}"
        table[key] = value
        added.append(Defaulted(where, value, why))

    g = rough.gears
    # --- shafts and bearings
    shafts = {"input": [g["input"]], "cluster": [g["cluster_large"], g["cluster_small"]], "output": [g["output"]]}
    bearings = {}
    for shaft, members in shafts.items():
        given = [m.hub.bore_diameter for m in members if m.name not in bare and m.hub.bore_diameter > 0]
        file_parts = data.get("parts") if isinstance(data.get("parts"), Mapping) else {}
        od = _given_number(file_parts, f"{shaft}_bearing_outer_diameter", unit)
        width = _given_number(file_parts, f"{shaft}_bearing_width", unit)
        if given:
            bore = given[0]
            found = standard_bearing(bore, unit)
            if found is None or abs(found[0] - bore) > 1e-6:
                if "parts" in wanted and (od is None or width is None):
                    key = f"parts.{shaft}_bearing_outer_diameter_{unit}" if od is None else \
                        f"parts.{shaft}_bearing_width_{unit}"
                    raise DesignError(key, f"missing, and the {shaft} shaft's bore {_in_unit(bore, unit):g} {unit} "
                                      f"(gears.{members[0].name}) is no standard bearing bore to size it from",
                                      "the bearing's outer diameter and width, or a standard bore: "
                                      + ", ".join(f"{b[0]:g}" for b in (METRIC_BEARINGS if unit == 'mm' else INCH_BEARINGS))
                                      + f" {unit}")
                found = (bore, od, width, "the file's bearing")
            bearings[shaft] = found
        else:
            bearings[shaft] = shaft_bearing(members, unit, shaft)
        for m in members:
            if m.name in bare:
                put("gears", f"{m.name}.bore_diameter_{sfx}", _in_unit(bearings[shaft][0], unit),
                    f"the {shaft} shaft: the largest {bearings[shaft][3]} bearing bore the gears allow")
    # --- rating and preload
    if "preload" in wanted and min(g[n].pressure_angle for n in LOOP) < math.radians(20) - 1e-9:
        raise DesignError("preload", "missing: the default rating's Lewis factors are for 20 deg teeth or more",
                          "a [preload] table with max_output_torque_*")
    rated = rated_output_torque(g)  # N·mm
    from geargen.design.stiffness import QUANTITY_SUFFIXES
    torque_suffix = "Nm" if unit == "mm" else "in_lbf"
    torque_key, torque_scale = f"max_output_torque_{torque_suffix}", QUANTITY_SUFFIXES["torque"][torque_suffix]
    if "preload" in wanted:
        value = float(f"{rated / torque_scale:.2g}")
        put("preload", torque_key, value, f"Lewis rating of the loop's meshes at {STEEL_BENDING_ALLOWABLE_MPA:g} MPa "
            f"(through-hardened steel), the loaded path carrying {0.5 + PRELOAD_FRACTION:g} x the output torque")
        put("preload", "line_of_action_angle_deg", 0.0, "the optimal configuration of Fig. 9")
        max_torque = value * torque_scale
    else:
        from geargen.design.stiffness import preload_spec_from_table
        try:
            max_torque = preload_spec_from_table(data["preload"]).max_output_torque
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
    # --- springs and blades
    spring = _spring(force_on_carriage / 2)
    if "springs" in wanted:
        why = (f"two springs give {force_on_carriage:.3g} N on the carriage: preload {PRELOAD_FRACTION:g} x the rated "
               "torque")
        put("springs", "count", 2, why)
        put("springs", f"wire_diameter_{sfx}", _in_unit(spring["wire"], unit), "music wire: the thinnest standard "
            "size whose stress stays below 0.45 of its tensile strength, even closed solid")
        put("springs", f"mean_coil_diameter_{sfx}", _in_unit(spring["mean"], unit), f"spring index {SPRING_INDEX:g}")
        put("springs", "active_coils", SPRING_ACTIVE_COILS, "a soft spring: k3 well below the paths")
        put("springs", "end_type", "squared_ground", "seats square on the carriage and the link wall")
        put("springs", f"free_length_{sfx}", _in_unit(spring["free"], unit), "installed length plus the working "
            "deflection")
        put("springs", f"installed_length_{sfx}", _in_unit(spring["installed"], unit), f"solid height plus "
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
        put("flexures", f"thickness_{sfx}", _in_unit(thickness, unit), "hardened spring-steel shim")
        put("flexures", f"length_{sfx}", _round(max(length, 20.0), unit), "stress at the travel below half the "
            "allowable")
        put("flexures", f"width_{sfx}", _round(width, unit), "the input bearing's seat and the carriage plates")
        put("flexures", "elastic_modulus_GPa", STEEL_E_GPA, "spring steel")
        put("flexures", "allowable_stress_MPa", allowable, "hardened spring-steel shim, long life")
        put("flexures", f"travel_{sfx}", _in_unit(travel, unit), "either way from neutral: the loop errors and "
            "assembly adjustment")
        put("flexures", f"neutral_offset_{sfx}", 0.0, "blades unstressed at the operating position")
    # --- [parts]: bearings, motor, carriage, link
    if "parts" in wanted:
        _default_parts(put, g, unit, bearings, max_torque, plate, gap, out, spring)
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
    return out, tuple(added)


#: [parts] keys that say the same thing in two ways: giving one gives the other
_SYNONYMS = {"bevel_module": "bevel_diametral_pitch", "bevel_diametral_pitch": "bevel_module"}


def _field_name(key: str) -> str:
    """A [parts] key without its unit suffix (``motor_flange_mm`` -> ``motor_flange``)."""
    for suffix in ("_mm", "_in", "_per_in"):
        if key.endswith(suffix):
            return key[: -len(suffix)]
    return key


def _given(table: Mapping[str, Any], key: str) -> bool:
    """Whether the file's ``[parts]`` gives ``key`` in any unit (or its synonym)."""
    name = _field_name(key)
    names = {_field_name(k) for k in table}
    return name in names or _SYNONYMS.get(name) in names


def _given_number(table: Mapping[str, Any], name: str, unit: str) -> float | None:
    """The file's value of the [parts] length or count ``name`` (mm for a length), or None."""
    from geargen.units import LENGTH_SUFFIXES
    for k, v in table.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            continue
        if k == name:
            return float(v)
        for suffix, scale in LENGTH_SUFFIXES.items():
            if k == f"{name}_{suffix}":
                return float(v) * scale
    if name == "bevel_module" and isinstance(table.get("bevel_diametral_pitch_per_in"), (int, float)):
        return MM_PER_IN / float(table["bevel_diametral_pitch_per_in"])
    return None


def _default_parts(put, g, unit: str, bearings, max_torque: float, plate: float, gap: float, out, spring) -> None:
    """The carriage hardware's [parts] (see the module's rules): every key the file's [parts]
    leaves out, each sized from what the file gives."""
    given = out.get("parts") or {}

    def number(name, default):
        value = _given_number(given, name, unit)
        return default if value is None else value

    m1 = g["input"].module
    for shaft in ("cluster", "input", "output"):
        d, od, w, name = bearings[shaft]
        why = f"{name}, {d:.4g} x {od:.4g} x {w:.4g} mm"
        put("parts", f"{shaft}_bearing_outer_diameter_{unit}", _in_unit(od, unit), why)
        put("parts", f"{shaft}_bearing_width_{unit}", _in_unit(w, unit), why)
    put("parts", f"bearing_clearance_{unit}", _round(gap, unit), "axial gap between a bearing and a gear face")
    # the bevel pair: 15:30 of the input's module, face a third of the cone distance
    zp, zg = (int(number("bevel_pinion_teeth", BEVEL_TEETH[0])), int(number("bevel_gear_teeth", BEVEL_TEETH[1])))
    module = number("bevel_module", m1)
    plate = number("carriage_plate_thickness", plate)
    gap = number("bearing_clearance", gap)
    cone = math.hypot(zp, zg) * module / 2
    ratio = g["output"].teeth / g["cluster_small"].teeth * g["cluster_large"].teeth / g["input"].teeth
    motor_torque = max_torque / (ratio * zg / zp) * 1e-3
    frame, flange, body_length, shaft_d, _ = _motor(motor_torque)
    why = f"{frame} envelope: the smallest frame for {motor_torque:.3g} N·m at the motor"
    put("parts", "bevel_pinion_teeth", zp, "a 2:1 bevel pair between motor and input")
    put("parts", "bevel_gear_teeth", zg, "a 2:1 bevel pair between motor and input")
    if unit == "mm":
        put("parts", "bevel_module_mm", round(module, 6), "the input gear's module")
    else:
        put("parts", "bevel_diametral_pitch_per_in", round(MM_PER_IN / module, 6), "the input gear's pitch")
    put("parts", f"bevel_face_width_{unit}", _round(cone / 3.5, unit, up=False), "under a third of the cone distance")
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
    put("parts", f"input_shaft_to_bevel_{unit}", _round(above, unit), "the bevel gear's heel clear above the "
        "carriage arm over the input's upper bearing")
    if not (out.get("train") or {}).get("upstream_backlash_arcmin"):
        put("parts", f"bevel_backlash_{unit}", _in_unit(0.0015 * MM_PER_IN, unit),
            "0.0015 in circumferential, the fine-pitch allowance of AGMA 2002 (the robot joint's)")
    put("parts", f"motor_body_diameter_{unit}", _round(flange, unit), why)
    put("parts", f"motor_body_length_{unit}", _round(body_length, unit), why)
    put("parts", f"motor_flange_{unit}", _round(flange, unit), why)
    put("parts", f"motor_flange_thickness_{unit}", _round(max(3.0, 0.08 * flange), unit), why)
    put("parts", f"motor_shaft_diameter_{unit}", _in_unit(shaft_d, unit) if unit == "mm" else
        round(shaft_d / MM_PER_IN, 4), why)
    put("parts", f"motor_shaft_length_{unit}", _round(3.0, unit), "the stub from the flange to the bevel pinion")
    put("parts", f"carriage_plate_thickness_{unit}", _round(plate, unit), "2.5 mesh-1 modules, at least 3 mm")
    d_in = max(2 * inp.tip_radius, bearings["input"][1])
    put("parts", f"carriage_width_{unit}", _round(d_in + 4 * plate, unit), "the input gear and its bearing seats "
        "with two plates either side")
    # the link's round end encloses every gear with a wall's clearance
    reach = _loop_reach(out, g)
    wall = max(3.0, 2.0 * m1)
    put("parts", f"link_wall_{unit}", _round(wall, unit), "two mesh-1 modules, at least 3 mm")
    put("parts", f"link_floor_{unit}", _round(wall + 1.0, unit), "a wall plus 1 mm: the bosses stand on it")
    put("parts", f"link_radius_{unit}", _round(reach + 2 * gap + wall + 2.0, unit), "the gears' reach from the "
        "symmetry line, 2 mm inside the walls")
    put("parts", f"link_top_clearance_{unit}", _round(2.5, unit), "above the highest part")
    outer = spring["mean"] + spring["wire"]
    put("parts", f"spring_y_offset_{unit}", _round(0.75 * outer + 1.0, unit), "the two springs side by side, "
        "clear of each other")


def _loop_reach(data, gears) -> float:
    """How far from the symmetry line (y = 0) the loop's gears can reach: the clusters' tips at the
    synthesis's mesh-2 centre distance and any direction, the output's tip (mm)."""
    from geargen.units import LENGTH_SUFFIXES
    syn = data.get("synthesis") or {}
    a2 = None
    for unit, scale in LENGTH_SUFFIXES.items():
        value = syn.get(f"centre_distance_mesh2_{unit}")
        if isinstance(value, (int, float)) and not isinstance(value, bool) and value > 0:
            a2 = value * scale
    small, large, out = gears["cluster_small"], gears["cluster_large"], gears["output"]
    if a2 is None:
        a2 = small.reference_radius + out.reference_radius
    return max(a2 + max(small.tip_radius, large.tip_radius), out.tip_radius)


__all__ = ["Defaulted", "default_hardware", "lewis_form_factor", "rated_output_torque", "standard_bearing",
           "METRIC_BEARINGS", "INCH_BEARINGS"]
