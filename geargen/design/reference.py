"""The design-file reference, written from the schema itself (``docs/design-files.md``).

Every key of every section comes from the :class:`~geargen.design.schema.Field` (or
:class:`~geargen.design.stiffness.Quantity`) that reads it, through
:func:`geargen.design.validate.table_schema`: its unit suffixes, range, default, choices and
one-line meaning (``help``). The examples are cut from the shipped ``assemblies/*.toml``. So the
document cannot drift from what ``load_design`` accepts: ``tests/design/test_reference.py``
regenerates it and compares it with the committed file. To regenerate::

    python -m geargen.design.reference > docs/design-files.md

:func:`key_type` and :func:`key_comment` describe one key in a line; the starter designs of
``geargen new`` (:mod:`geargen.design.starters`) comment their keys with them.
"""

from __future__ import annotations

import dataclasses
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from geargen.design.assembly import SECTIONS
from geargen.design.schema import (key_comment, GEAR_NAME_MAX, MAX_FILE_BYTES, MAX_NESTING, NAME_MAX, PLAUSIBLE, Field, number_text,
                                   field_range_text, plausible)
from geargen.design.stiffness import (KIND_KEYS, INTERNAL_UNITS, QUANTITY_SUFFIXES, BeamPinionSpec, ComponentSpec,
                                      FlexureSpec, PreloadSpec, Quantity, SpringSpec, StiffnessSpec)
from geargen.design.validate import table_schema
from geargen.design.written_units import FACTOR
from geargen.units import ANGLE_SUFFIXES, LENGTH_SUFFIXES

DEG = math.pi / 180.0

#: the shipped designs the examples are cut from
ASSEMBLIES = Path(__file__).resolve().parents[2] / "assemblies"

#: per table, the dataclass whose defaults a :class:`Quantity` left out takes (a Quantity has none of its own)
_QUANTITY_DEFAULTS = {("stiffness",): StiffnessSpec, ("preload",): PreloadSpec, ("flexures",): FlexureSpec,
                      ("springs",): SpringSpec, ("beam_pinion",): BeamPinionSpec,
                      ("stiffness", "components", "NAME"): ComponentSpec}

_FAMILY_NAMES = {"force": "force", "torque": "torque", "linear_stiffness": "linear stiffness",
                 "torsional_stiffness": "torsional stiffness", "stress": "stress",
                 "inertia": "moment of inertia", "rotary_damping": "rotary damping",
                 "torque_constant": "torque constant", "frequency": "frequency"}


@dataclass(frozen=True)
class Example:
    """Tables cut from a shipped design: ``headers`` (``"gears.input"``; ``""`` the top-level keys)."""

    file: str
    headers: tuple[str, ...]


@dataclass(frozen=True)
class Table:
    """One documented table: its heading, the path :func:`table_schema` knows it by, the parsed-file
    context the schema depends on, a short introduction and the example."""

    heading: str
    path: tuple[str, ...]
    intro: str
    example: Example | None = None
    example_text: str = ""  # when no shipped design has the table
    context: dict = dataclasses.field(default_factory=dict)
    sections: tuple[str, ...] = ()  # the SECTIONS entries it documents


_CHECKS_EXAMPLE = '''[checks]
steps_per_tooth = 24
min_contact_ratio = 1.2
monte_carlo_samples = 1000
seed = 7
# a design without [synthesis] or [layout]: the pairs to check and their centre distances
meshes = [["pinion", "wheel"]]
centre_distance_mm = 25.5
'''

_RACK_EXAMPLE = '''[gears.slide_rack]
kind = "rack"
module_mm = 2
pressure_angle_deg = 20
helix_angle_deg = 20
hand = "right"
teeth = 60
face_width_mm = 20
pitch_line_height_mm = 20
tip_rounding = "generating"
thinning_circumferential_mm = 0.02
'''

_WORM_EXAMPLE = '''[gears.wheel]
kind = "worm_wheel"
module_mm = 3
starts = 2
wheel_teeth = 30
worm_reference_diameter_mm = 44
pressure_angle_deg = 20
hand = "right"
worm_face_length_mm = 45
wheel_face_width_mm = 28
backlash_mm = 0.05
backlash_on = "wheel"
'''

_BEVEL_EXAMPLE = '''[gears.bevel_pinion]
kind = "bevel"
teeth = 15
mate_teeth = 30
shaft_angle_deg = 90
diametral_pitch_per_in = 32
pressure_angle_deg = 20
face_width_in = 0.15
'''

_DUTY_EXAMPLE = '''[duty]
output_torque_levels_Nm = [5.0, 2.5, 0.5]   # the load spectrum at the output
level_shares = [0.05, 0.25, 0.70]           # of the life at each level
direction = "both"                          # each level half its share each way
output_speed_rpm = 10
life_hours = 20000
viscosity_mm2_per_s = 220                   # ISO VG 220
roughness_Ra_um = 0.4                       # ground flanks
accuracy_grade = 5
material = "case_carburised"                # every gear without its own [materials.GEAR]
quality = "MQ"
'''

_MATERIALS_EXAMPLE = '''[materials.output]
material = "through_hardened"
quality = "MQ"
hardness_HV = 320
'''

TABLES: tuple[Table, ...] = (
    Table("Top-level keys", (), "Keys before the first table. Everything is optional.",
          Example("robot_joint.toml", ("",))),
    Table("[drive]", ("drive",), "The drive after Hale & Slocum. Sections that describe a drive of a type "
          "([stiffness], [preload], [flexures], [springs], [beam_pinion], [engagement]) need `type`.",
          Example("robot_joint.toml", ("drive",)), sections=("drive",)),
    Table("[gears.NAME] and [gear_defaults]", ("gears", "NAME"),
          "One table per gear; `NAME` is the gear's name in the rest of the file. `[gear_defaults]` takes any "
          "of the same keys and gives them to every gear (a gear's own table wins). A key is required when "
          "neither gives it. Give exactly one of `module_mm` and `diametral_pitch_per_in`. A dual-pinion drive "
          "names its gears `input`, `cluster_large`, `cluster_small` and `output` (the paper's gears 1 to 4); "
          "a split pinion `pinion_stiff`, `pinion_compliant` and `output` (or the names its [layout] gives).",
          Example("c_axis.toml", ("gear_defaults", "gears.input")), sections=("gears", "gear_defaults")),
    Table("[gear] or [gears.NAME] with kind = \"rack\"", ("gears", "NAME"),
          "A spur or helical gear rack (`geargen gear --kind rack`): straight flanks at the normal pressure angle, "
          "tip and root lands, root fillets and optionally the generating tip rounding; its length is a whole "
          "number of transverse pitches. Give exactly one of `module_mm` and `diametral_pitch_per_in`, and one of "
          "`teeth` and `length_<unit>`.",
          example_text=_RACK_EXAMPLE, context={"gears": {"NAME": {"kind": "rack"}}}),
    Table("[gear] or [gears.NAME] with kind = \"worm\" or \"worm_wheel\"", ("gears", "NAME"),
          "A ZA cylindrical worm (straight-sided axial profile, DIN 3975) and its throated wheel, defined together "
          "as one set (`geargen gear --kind worm` / `--kind worm_wheel`); the wheel's flank is the envelope of the "
          "worm's thread. The set is written in the worm's axial system: `module_mm` is the axial module m_x.",
          example_text=_WORM_EXAMPLE, context={"gears": {"NAME": {"kind": "worm"}}}),
    Table("[gear] or [gears.NAME] with kind = \"bevel\"", ("gears", "NAME"),
          "A straight bevel gear with spherical-involute teeth (`geargen gear --kind bevel`), defined with its mate: "
          "the pitch cone follows from both tooth numbers and the shaft angle. Module or diametral pitch and the "
          "thinning are the heel's; the face width is measured along the cone; tip and root cones pass through "
          "the apex; toe and heel are spheres about the apex.",
          example_text=_BEVEL_EXAMPLE, context={"gears": {"NAME": {"kind": "bevel"}}}),
    Table("[synthesis]", ("synthesis",),
          "Centre synthesis of a dual-pinion drive (the paper's Eqs. 7-8 and Appendix): where the clusters sit "
          "so that both paths mesh. Backlash B is circumferential, at the reference pitch circles "
          "(B = j_bt / cos alpha_t); max is with the thinnest teeth the tolerances allow, min with the thickest.",
          Example("robot_joint.toml", ("synthesis",)), sections=("synthesis",)),
    Table("[errors.GEAR]", ("errors", "GEAR"),
          "The error budget of one gear, as total indicator readings. With a [synthesis] every gear of the "
          "train needs its table and every key is required; without one (declared [checks] meshes) a key left "
          "out is 0.", Example("robot_joint.toml", ("errors.input",)), context={"synthesis": {}},
          sections=("errors",)),
    Table("[monte_carlo]", ("monte_carlo",),
          "The tolerance simulation of `geargen synth --monte-carlo`: the carriage travel over random builds "
          "of the error budget.", Example("robot_joint.toml", ("monte_carlo",)), sections=("monte_carlo",)),
    Table("[checks]", ("checks",),
          "What the geometric mesh checks (`geargen check`, and the build's gate) sweep, require and compare. A "
          "design without [synthesis] or [layout] places no drive: `geargen check` checks the pairs `meshes` names, "
          "and `geargen build` builds its gear set once that same verdict passes (each [gears.NAME] as `geargen gear "
          "DESIGN --gear NAME` writes it, with report.md and manifest.json; no assembly file: where the gears sit "
          "around each other is not in the design).",
          example_text=_CHECKS_EXAMPLE, sections=("checks",)),
    Table("[stiffness]", ("stiffness",),
          "Materials and the train whose path stiffnesses, drive stiffness (Eqs. 2, 5) and loop stiffness "
          "(Eqs. 3, 6) `geargen stiffness` computes. The meshes of a dual-pinion train come from the gears "
          "(Eq. 1, or ISO 6336-1 method B with mesh_stiffness = \"iso6336\"); further components are tables "
          "[stiffness.components.NAME]. In a dual or split pinion "
          "each component's speed comes from the teeth of the shaft or gear it names; only a custom train "
          "types ratios.",
          Example("robot_joint.toml", ("stiffness",)), sections=("stiffness",)),
    Table("[stiffness.components.NAME]", ("stiffness", "components", "NAME"),
          "One compliance of a path, in series with the rest of it; `count` identical ones act in parallel. "
          "Each kind reads its own keys (below); a key another kind reads is refused.",
          Example("robot_joint.toml", ("stiffness.components.cluster_shaft",
                                       "stiffness.components.cluster_support"))),
    Table("[preload]", ("preload",),
          "The load the drive carries, the preload and the loop errors it must absorb.",
          Example("robot_joint.toml", ("preload",)), sections=("preload",)),
    Table("[flexures]", ("flexures",),
          "Parallel blade flexures (clamped at both ends) guiding the preload carriage of a radial-preload "
          "drive. Checked on load: thinner than wide, within the allowable stress at the travel.",
          Example("robot_joint.toml", ("flexures",)), sections=("flexures",)),
    Table("[springs]", ("springs",),
          "Helical compression springs pushing the preload carriage. Checked on load: index above 2, free "
          "length above solid, installed length above solid and within the allowable shear stress.",
          Example("robot_joint.toml", ("springs",)), sections=("springs",)),
    Table("[beam_pinion]", ("beam_pinion",),
          "A long pinion, simply supported, whose bending is the preload spring (the C-axis, Fig. 12). Give "
          "`span_*` or `target_stiffness_*`.", Example("c_axis.toml", ("beam_pinion",)), sections=("beam_pinion",)),
    Table("[engagement]", ("engagement",),
          "Helical dual pinions that slide axially into mesh, one leading the other so that the helix opens "
          "backlash (the C-axis). The lead (backlash + preload windup) / tan(helix) must fit in the "
          "engagement length.", Example("c_axis.toml", ("engagement",)), sections=("engagement",)),
    Table("[stages.NAME]", ("stages", "NAME"),
          "The plain gear stages between the motor and a dual-pinion loop, one table per stage, in order from the "
          "motor: each stage's driven gear shares a shaft with the next stage's driver, the last driven gear sits on "
          "the input gear's shaft, the first driver on the motor. They stand with the motor on the preload carriage, "
          "in levels above its arm; each keeps its backlash (checked against its range) and counts in the ratio and, "
          "as [stiffness.components] of kind mesh, in the stiffness.",
          Example("metric_dual_pinion.toml", ("stages.motor", "stages.idler")), sections=("stages",)),
    Table("[stages.NAME] of kind planetary", ("stages", "NAME"),
          "A planetary stage (ring fixed, sun in, carrier out: ratio 1 + z_r/z_s), the only upstream stage: the "
          "sun on the motor shaft, the carrier on the input gear's shaft, sun, carrier and ring coaxial with it. "
          "Refused on load when N equally spaced planets cannot be assembled ((z_s + z_r)/N not whole; "
          "`planet_spacing = \"nearest_allowed\"` takes the assembly angles 2 pi k/(z_s + z_r) nearest to equal "
          "spacing instead). Each planet is placed in the middle of its play with the sun and the ring; the "
          "sun-planet meshes are checked like any mesh, the planet-ring meshes and the stage's coaxiality and "
          "neighbour clearance on the exact outlines as placed.",
          Example("planetary_dual_pinion.toml", ("stages.planetary",)), sections=("stages",),
          context={"stages": {"NAME": {"kind": "planetary"}}}),
    Table("[layout]", ("layout",),
          "How the build places the gears. A file with [synthesis] and no [layout] is a dual-pinion drive "
          "with every default. A split pinion also needs `centre_distance_*` and the backlash range; an axial "
          "preload those, `input_stroke_*` and its four helical gears (its preload and spring in [preload]: "
          "assemblies/axial_preload.toml).",
          Example("split_pinion.toml", ("layout",)), sections=("layout",)),
    Table("[parts] of a dual pinion on a preload carriage", ("parts",),
          "The sizes of the non-gear parts; the drive the file describes decides which (a dual pinion with "
          "[flexures] and [springs]: this table). The robot joint's layout (Fig. 10): the preload carriage on "
          "its [flexures] pushed by its [springs], carrying the input and the motor, which drives the input "
          "through a bevel pair (the bevel keys) or through the [stages] standing on the carriage (the stage "
          "keys); the loop's shafts and bearings, the link and its cover around it all. Every length is "
          "required unless a default is shown or it belongs to the other motor drive.",
          Example("robot_joint.toml", ("parts",)), sections=("parts",)),
    Table("[parts] of a dual pinion with a beam-spring pinion", ("parts",),
          "A dual pinion whose long input pinion is the preload spring ([beam_pinion]; the machine-tool "
          "C-axis, Fig. 12): spindle stub, the long pinion with its gearhead and motor, the dual pinions with "
          "their locking rings and locknuts, each on two bearings in a quill that slides in the housing block, "
          "its lug between the travel stops under the block; the drive column on the block with the plates "
          "that seat the long pinion's bearings and carry gearhead and motor. Sized from [beam_pinion] and "
          "[engagement].",
          Example("c_axis.toml", ("parts",)), context={"beam_pinion": {"span_mm": 1}}),
    Table("[parts] of a split pinion", ("parts",),
          "The concentric split pinion (Fig. 8): hollow shaft and its bearing pair, the clamp collar (the "
          "frictional interface), the inner shaft from the collar through the compliant pinion to its outboard "
          "bearing (the stiffness model reads the same shafts), the output shaft and bearings, the housing's "
          "bottom and top plates that hold every bearing.", Example("split_pinion.toml", ("parts",)),
          context={"layout": {"kind": "split_pinion"}}),
    Table("[parts] of an axial preload", ("parts",),
          "The axial-motion preload (geargen.drives.axial_preload.place): the input shaft through both helical pinions on "
          "two bearings whose outer rings slide in the housing plates' bores, its stroke and the motor stub above; "
          "the preload spring in a cup under the bottom plate pushing the lower bearing's outer ring (its active "
          "coils follow from [layout] preload_spring_rate_N_per_mm); the output shaft and bearings; the housing's "
          "bottom and top plates.", Example("axial_preload.toml", ("parts",)),
          context={"layout": {"kind": "axial_preload"}}),
    Table("[export]", ("export",), "Tolerances of the exported files and the rendered view. Every key is optional.",
          Example("robot_joint.toml", ("export",)), sections=("export",)),
    Table("[train]", ("train",),
          "What `geargen train` needs beyond the drive: the rotating parts' material (sub-tables "
          "[train.materials], density in kg/m^3 per material name, and [train.part_materials], part name to "
          "material), mesh friction, the lost motion the output may have, the motor's data sheet, the load and "
          "the position loop (a bandwidth with a damping ratio, or the gains at the motor), and what a "
          "[layout] upstream_stages entry (teeth only) has for backlash and stiffness. Every key is optional.",
          Example("robot_joint.toml", ("train",)), sections=("train",)),
    Table("[duty]", ("duty",),
          "What the load capacity of every mesh is rated for (ISO 6336-2/-3:2019 method B; a spectrum by ISO "
          "6336-6, Palmgren-Miner): the drive torques at the output with their shares of the life, the output speed, "
          "the life, K_A, the lubricant, the roughness, the accuracy grade of gears whose table gives none, and the "
          "ISO 6336-5 material of gears without a [materials.GEAR] table. Every key is optional: without the section "
          "a drive is rated for the paper's maximum load ([preload] max_output_torque_*) both ways for the whole "
          "life, each default below chosen so that nothing is credited the file does not state. Each preloaded mesh "
          "carries its path's preload plus its share of the drive torque (Eqs. 2-6), upstream stages the drive "
          "torque; the minimum safety factors are [checks] min_S_H and min_S_F.",
          example_text=_DUTY_EXAMPLE, sections=("duty",)),
    Table("[materials.GEAR]", ("materials", "GEAR"),
          "The ISO 6336-5 material, quality grade and surface hardness of one gear (`GEAR` a [gears] table name), "
          "over [duty]'s. The hardness is checked against the range the standard's line covers for the material "
          "and grade (through hardened alloy steel MQ: 200-360 HV; case carburised MQ: 660-800 HV).",
          example_text=_MATERIALS_EXAMPLE, sections=("materials",)),
    Table("[dual_motor]", ("dual_motor",),
          "Two motors, each with its own pinion on one output gear, and their coordination (Fig. 1): a constant "
          "bias or unidirectional torques. The two meshes and their centre distances are [checks] meshes.",
          Example("dual_motor.toml", ("dual_motor",)), sections=("dual_motor",)),
)


# ---------------------------------------------------------------- one key


def _quantity_families(q: Quantity) -> str:
    return " or ".join(_FAMILY_NAMES[f] for f in q.families)


def key_type(schema: Field | Quantity) -> str:
    """What the key takes, with its unit suffixes: ``"length: _mm _in _um _m"``, ``"whole number"``."""
    if isinstance(schema, Quantity):
        return "; ".join(f"{_FAMILY_NAMES[f]}: " + " ".join(f"_{s}" for s in QUANTITY_SUFFIXES[f])
                         for f in schema.families)
    if schema.kind in ("length", "angle"):
        return f"{schema.kind}: " + " ".join(f"_{s}" for s in schema.suffixes())
    if schema.kind == "string" and schema.choices:
        return "one of " + ", ".join(f'"{c}"' for c in schema.choices)
    if schema.kind == "string" and schema.maximum is not None:
        return f"text: at most {int(schema.maximum)} characters, one line (what the drawing's cell holds)"
    if schema.kind == "name":
        return f"name: at most {int(schema.maximum or NAME_MAX)} of A-Z a-z 0-9 _ - ."
    return {"integer": "whole number", "number": "number", "string": "string", "bool": "true or false",
            "list": "list", "table": "table"}[schema.kind]


def range_text(schema: Field | Quantity) -> str:
    """The allowed values: lengths in mm, angles in degrees, quantities in their internal unit."""
    if isinstance(schema, Quantity):
        bounds = Field(schema.name, "number", minimum=schema.minimum, maximum=schema.maximum,
                       exclusive_minimum=schema.exclusive_minimum)
        return "; ".join(field_range_text(plausible(bounds, family), 1.0, INTERNAL_UNITS[family])
                         for family in schema.families)
    if schema.kind not in ("length", "angle", "number", "integer"):
        return ""
    schema = plausible(schema)
    if schema.kind == "length":
        return field_range_text(schema, 1.0, "mm")
    if schema.kind == "angle":
        return field_range_text(schema, DEG, "deg")
    return field_range_text(schema, 1.0, "")


def _value_text(value: Any, kind: str) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(_value_text(v, kind) for v in value) + "]"
    if kind == "length":
        return f"{number_text(value)} mm"
    if kind == "angle":
        degrees = value / DEG
        return f"{number_text(degrees)} deg" if math.isclose(degrees, float(number_text(degrees)), abs_tol=1e-12) else f"{number_text(value)} rad"
    return number_text(value) if isinstance(value, float) else str(value)


def _quantity_default(q: Quantity, path: tuple[str, ...]) -> str:
    spec = _QUANTITY_DEFAULTS.get(path)
    field = next((f for f in dataclasses.fields(spec) if f.name == q.name), None) if spec else None
    value = None if field is None else field.default
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return ""
    family = q.families[0]
    if family == "stress" and value >= 1e3:
        return f"{number_text(value / 1e3)} GPa"
    return f"{number_text(value)} {INTERNAL_UNITS[family]}"


def default_text(schema: Field | Quantity, path: tuple[str, ...] = ()) -> str:
    """``"required"``, the default in internal units, or ``""`` (not set: the meaning says what happens)."""
    if schema.required:
        return "required"
    if isinstance(schema, Quantity):
        return _quantity_default(schema, path)
    if schema.default is None:
        return ""
    return _value_text(schema.default, schema.kind)


# ---------------------------------------------------------------- examples


def example_text(example: Example, root: Path = ASSEMBLIES) -> str:
    """The tables ``example.headers`` of a shipped design, as written there (comments included;
    comment lines at the start of a line after a table belong to the next one and are left out)."""
    lines = (root / example.file).read_text().splitlines()
    header = re.compile(r"^\s*\[")
    blocks = []
    for wanted in example.headers:
        if wanted == "":
            start = next(i for i, line in enumerate(lines) if line.strip() and not line.startswith("#"))
        else:
            start = next((i for i, line in enumerate(lines) if re.match(rf"^\[{re.escape(wanted)}\]", line)), None)
            if start is None:
                raise KeyError(f"[{wanted}] is not a table of {example.file}")
        end = next((i for i in range(start + 1, len(lines)) if header.match(lines[i])), len(lines))
        block = lines[start:end]
        while block and (not block[-1].strip() or block[-1].startswith("#")):
            block.pop()
        blocks.append("\n".join(block))
    return "\n\n".join(blocks) + "\n"


# ---------------------------------------------------------------- the document


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def _key_cell(schema: Field | Quantity) -> str:
    if isinstance(schema, Quantity) or schema.kind in ("length", "angle"):
        return f"`{schema.name}_<unit>`"
    return f"`{schema.name}`"


def table_rows(table: Table) -> list[tuple[Field | Quantity, tuple[str, str, str, str, str]]]:
    """(schema, (key, type and unit, range, default, meaning)) of every key of ``table``."""
    fields, quantities = table_schema(table.context, table.path)
    rows = []
    for schema in list(fields) + list(quantities):
        rows.append((schema, (_key_cell(schema), key_type(schema), range_text(schema),
                              default_text(schema, table.path), schema.help)))
    return rows


def _units_section() -> list[str]:
    out = ["## Units", "",
           "Every key that has a unit carries it as a suffix, and any suffix of its kind may be used: "
           "`face_width_mm = 8` and `face_width_in = 0.315` are the same key. Ranges below are given in "
           "internal units (mm, degrees for angles, N, N·mm, MPa); messages give them in the unit the file used.",
           "",
           "Every command's text (reports, tables, warnings, errors, plots) gives lengths in the design's "
           "`length_unit`, and forces, torques, stiffnesses and stresses in that unit's usual system (N, N·m, "
           "N/mm, MPa for mm; lbf, in·lbf, lbf/in, psi for in) unless the file wrote that quantity only in "
           "the other system: then in the unit it wrote (the robot joint's `max_output_torque_Nm` keeps its "
           "torques in N·m). JSON keys carry their unit.",
           "",
           "A length written in the other unit (`face_width_mm` in an inch design) is read in the unit it "
           "names, and `geargen check` notes it when its number reads like one in the design's unit: more "
           f"than {FACTOR:g} times from the file's typical size (the median of the sizes it wrote in its own "
           f"unit) as written, within {FACTOR:g} times of it in the design's unit (a `pinion_axial_gap_mm = "
           "0.0625` beside inch sizes). Tolerances, runouts, backlashes and thinnings, small by nature, are "
           "not compared.",
           "", "| kind | suffixes (factor to the internal unit) |", "|---|---|"]
    out.append("| length (mm) | " + ", ".join(f"`_{s}` ({number_text(f)})" for s, f in LENGTH_SUFFIXES.items()) + " |")
    out.append("| angle (deg) | " + ", ".join(f"`_{s}` ({number_text(f / DEG)})" for s, f in ANGLE_SUFFIXES.items())
               + " |")
    for family, table in QUANTITY_SUFFIXES.items():
        out.append(f"| {_FAMILY_NAMES[family]} ({INTERNAL_UNITS[family]}) | "
                   + ", ".join(f"`_{s}` ({number_text(f)})" for s, f in table.items()) + " |")
    out.append("")
    return out


def _component_kinds() -> list[str]:
    common = ("kind", "scope", "count", "shaft", "ratio")
    out = ["Keys each kind reads (besides `" + "`, `".join(common) + "`):", "",
           "| kind | keys |", "|---|---|"]
    for kind, keys in KIND_KEYS.items():
        out.append(f"| `{kind}` | " + ", ".join(f"`{k}`" for k in sorted(keys)) + " |")
    return out + [""]


def design_files_markdown(root: Path = ASSEMBLIES) -> str:
    """``docs/design-files.md``: every section and key of a design file, from the schema."""
    from geargen.drives.registry import DRIVES  # the kinds with starters

    kinds = ", ".join(f"`{d.name}`" for d in DRIVES.values() if d.starters)
    out = ["# Design files", "",
           "<!-- Generated by `python -m geargen.design.reference > docs/design-files.md` from the schema "
           "(geargen/design); edit the Fields' help there, not this file. -->", "",
           "A design file is TOML. Each table below is read by the module that uses it, every key checked "
           "when the file is loaded: an unknown key is refused with the closest known keys "
           "(`face_width_mn` -> did you mean `face_width_mm`?), a value out of range with the range in the "
           "key's unit, and every problem of a file is reported at once. `geargen new KIND FILE.toml` writes a "
           f"commented starter design ({kinds}) that builds, metric or with `--units in` inch.", "",
           f"The file is UTF-8 (a byte-order mark is accepted), at most {MAX_FILE_BYTES // 1024 // 1024} MiB, its "
           f"tables and arrays nested at most {MAX_NESTING} deep. A number whose key sets no bound of its own on a "
           "side has the plausible one of its kind there (the ranges below include them): a length at most "
           f"{PLAUSIBLE['length'][1] / 1e3:g} m and, when above zero, at least {PLAUSIBLE['length'][0] * 1e6:g} nm; "
           "an angle at most a turn. A name that becomes a file name (the design's, a gear table's, a stage's) is "
           f"ASCII letters, digits, `_`, `-` and `.`, at most {NAME_MAX} characters, a gear's at most "
           f"{GEAR_NAME_MAX} (what its drawing holds).", "",
           "Columns: the key (`_<unit>`: any suffix of its kind), what it takes, its range (`[a, b]` inclusive, "
           "`(a, b)` exclusive), its default (`required`, or blank: not set, the meaning says what happens), "
           "and its meaning.", ""]
    out += _units_section()
    out += _default_hardware_section()
    out += ["## Sections", ""]
    for table in TABLES:
        out += [f"### {table.heading}", "", table.intro, "",
                "| key | takes | range | default | meaning |", "|---|---|---|---|---|"]
        for _, cells in table_rows(table):
            out.append("| " + " | ".join(_cell(c) for c in cells) + " |")
        out.append("")
        if table.path == ("stiffness", "components", "NAME"):
            out += _component_kinds()
        text = example_text(table.example, root) if table.example else table.example_text
        source = f" (from `assemblies/{table.example.file}`)" if table.example else ""
        out += [f"Example{source}:", "", "```toml", text.rstrip("\n"), "```", ""]
    return "\n".join(out)


def _default_hardware_section() -> list[str]:
    """The default hardware of every drive kind: the rules of its ``defaults.py``, from its docstring
    (its first paragraph the heading's subject)."""
    import inspect

    from geargen.drives.keys import KEYS
    out = ["## Default hardware", "",
           "A file may leave out its `[parts]` table, or any of its keys: geargen sizes what is missing by the "
           "rules of the drive's kind below, each value with the rule that chose it. `geargen check` prints them "
           "and the resolved `[parts]` as a table to paste into the file; a value the file gives is never "
           "changed.", ""]
    for kind in KEYS.values():
        title, rules = inspect.getdoc(kind.defaults).split("\n\n", 1)
        out += [f"### {kind.NAME}", "", title.strip(), "",
                rules.replace("Pure arithmetic on the parsed file: no CAD kernel.", "").rstrip(), ""]
    return out


def documented_sections() -> set[str]:
    """The top-level sections (:data:`geargen.design.assembly.SECTIONS`) the reference covers."""
    return {s for t in TABLES for s in t.sections}


def main() -> int:
    sys.stdout.write(design_files_markdown())
    return 0


__all__ = ["TABLES", "Table", "Example", "design_files_markdown", "documented_sections", "example_text",
           "key_comment", "key_type", "range_text", "default_text", "table_rows", "SECTIONS"]

if __name__ == "__main__":
    sys.exit(main())
