"""The ``[layout]`` section: how the build places the gears (read by ``geargen.pipeline.place``).

Layout::

    [layout]
    kind = "dual_pinion"              # gears placed by the centre synthesis of [synthesis]
                                      # ("split_pinion": two pinions side by side on one output)
    model_backlash = "mid"            # tooth thickness of the model: "mid", "max", "min" of the
                                      # backlash range, or "as_designed" (the gears' own thinning)
    loaded_flank_gap_mm = 0.0005      # left on the working flanks so the solids do not touch
    position = "engaged"              # sliding pinions ("disengaged" needs [engagement])
    upstream_stages = [[15, 30]]      # [driver_teeth, driven_teeth] between encoder and input
    required_ratios = [32]            # whole-number ratios, encoder to output, the controller needs

A split pinion also needs ``centre_distance_*`` and ``circumferential_backlash_min_*`` /
``_max_*``; an axial preload (``kind = "axial_preload"``, :mod:`geargen.model.axial_drive`) those
and ``input_stroke_*``, its four helical gears named by ``pinion_left``, ``pinion_right``,
``output_right``, ``output_left`` (rules: :mod:`geargen.design.axial_preload`), its preload and
spring in ``[preload]``. :func:`layout_settings` reads the table; :func:`check_layout` adds the rules that
involve other sections (the gears named, the synthesis, the engagement).
"""

from __future__ import annotations

from typing import Any

from geargen.design.schema import Field, read_table, shown
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

LAYOUT_KINDS = ("dual_pinion", "split_pinion", "axial_preload", "rack_dual_pinion")
MODEL_BACKLASH = ("mid", "max", "min", "as_designed")
POSITIONS = ("engaged", "disengaged")
#: the most teeth of an upstream stage's gear (a GearSpec's most) and the largest required ratio
#: (far past a 360:1 indexing drive)
MAX_TEETH = 2000
MAX_RATIO = 1_000_000

LAYOUT_FIELDS = [
    Field("kind", "string", required=False, default=None, choices=LAYOUT_KINDS,
          help="dual_pinion: gears placed by the centre synthesis of [synthesis] (the default when there is one); "
               "split_pinion: two pinions side by side on one output; axial_preload: a left- and a right-hand helical "
               "pinion on an input shaft that slides axially under a preload spring, each meshing its own output gear "
               "of the opposite hand (geargen.model.axial_drive)"),
    Field("model_backlash", "string", required=False, default=None, choices=MODEL_BACKLASH,
          help="tooth thickness of the model: mid, max or min of the backlash range, or as_designed (the gears' own "
               "thinning; the default when a gear gives one, else mid)"),
    Field("loaded_flank_gap", "length", required=False, default=0.0, minimum=0.0,
          help="left open on the working flanks so that the solids do not touch"),
    Field("position", "string", required=False, default="engaged", choices=POSITIONS,
          help="sliding pinions engaged or disengaged (disengaged needs [engagement])"),
    # dual pinion
    Field("cluster", "string", required=False, default="one_piece", choices=("one_piece", "separate"),
          help="dual pinion: each cluster one part, or its large and small gear as two parts"),
    Field("cluster_axial_gap", "length", required=False, default=None, minimum=0.0,
          help="dual pinion: axial gap between a cluster's large and small gear (default: a quarter of the narrower "
               "face)"),
    Field("input_face_offset", "length", required=False, default=None,
          help="dual pinion: how far the input's face sits below the cluster's large gear face (default: the input "
               "centred on it)"),
    Field("carriage_travel", "length", required=False, default=None, minimum=0.0,
          help="dual pinion and rack drive: travel of the preload carriage either way, drawn in the layout and the report"),
    # split pinion
    Field("centre_distance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="split pinion and axial preload: centre distance of both pinions from the output"),
    Field("pinion_stiff", "string", required=False, default="pinion_stiff",
          help="split pinion: the gear table of the stiff (outer) path's pinion"),
    Field("pinion_compliant", "string", required=False, default="pinion_compliant",
          help="split pinion: the gear table of the compliant (inner) path's pinion"),
    Field("output", "string", required=False, default="output",
          help="split pinion: the gear table of the output gear"),
    Field("pinion_axial_gap", "length", required=False, default=0.0, minimum=0.0,
          help="split pinion and axial preload: axial gap between the two pinions"),
    Field("circumferential_backlash_min", "length", required=False, default=None, minimum=0.0,
          help="split pinion and axial preload: smallest backlash of each pinion with the output (circumferential, at "
               "the reference circles)"),
    Field("circumferential_backlash_max", "length", required=False, default=None, minimum=0.0,
          help="split pinion and axial preload: largest backlash of each pinion with the output (circumferential, at "
               "the reference circles)"),
    # rack dual pinion (Type 2, geargen.model.rack_drive): gear tables "pinion", "path_gear", "input"
    Field("pinion_spacing", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="rack drive: distance along the rack between the two path shafts (each carries a rack pinion and a "
               "path gear)"),
    Field("input_centre_distance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="rack drive: design centre distance of the input gear (on the preload carriage) from each path gear: "
               "the carriage's nominal height"),
    Field("rack_backlash_min", "length", required=False, default=None, minimum=0.0,
          help="rack drive: smallest circumferential backlash of each pinion on the rack (set by the pinions' centre "
               "height)"),
    Field("rack_backlash_max", "length", required=False, default=None, minimum=0.0,
          help="rack drive: largest circumferential backlash of each pinion on the rack"),
    Field("path_backlash_min", "length", required=False, default=None, minimum=0.0,
          help="rack drive: smallest circumferential backlash of the input with each path gear (at the input's "
               "reference circle)"),
    Field("path_backlash_max", "length", required=False, default=None, minimum=0.0,
          help="rack drive: largest circumferential backlash of the input with each path gear"),
    Field("slide_travel", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="rack drive: travel of the machine slide; the rack is this plus the pinions' span long"),
    Field("rack_face_width", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="rack drive: face width of the rack (default: the pinion's)"),
    Field("rack_back_height", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="rack drive: rack back face to its root line (default: 2 modules)"),
    Field("path_gear_axial_gap", "length", required=False, default=2.0, minimum=0.0,
          help="rack drive: axial gap between the pinion and the path gear on each path shaft"),
    Field("rack_loop_error", "length", required=False, default=0.0, minimum=0.0,
          help="rack drive: anticipated loop error as a rack displacement, peak to peak (rack pitch error over the "
               "pinion span, runouts); the carriage must travel far enough to absorb it, and teeth made anywhere in the "
               "backlash ranges"),
    Field("carriage_preload_force_N", "number", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="rack drive: the carriage spring's force on the input gear, toward the path shafts (N)"),
    Field("carriage_spring_rate_N_per_mm", "number", required=False, default=None, minimum=0.0,
          exclusive_minimum=True, help="rack drive: the carriage spring's rate along its motion (N/mm)"),
    Field("gear_elastic_modulus_GPa", "number", required=False, default=207.0, minimum=1.0, maximum=1000.0,
          help="rack drive: Young's modulus of the gears and rack for the mesh stiffness of Eq. 1 (steel: 207)"),
    Field("shaft_shear_modulus_GPa", "number", required=False, default=79.3, minimum=1.0, maximum=1000.0,
          help="rack drive: shear modulus of the path shafts, whose torsion between pinion and path gear is in each "
               "path (steel: 79.3)"),
    Field("max_rack_force_N", "number", required=False, default=None, minimum=0.0,
          help="rack drive: largest drive force on the rack (N); both paths must stay loaded up to it"),
    # axial preload (geargen.model.axial_drive); centre_distance, circumferential_backlash_min/_max and
    # pinion_axial_gap as the split pinion's, the backlash being each mesh's own
    Field("pinion_left", "string", required=False, default="pinion_left",
          help="axial preload: the gear table of the left-hand pinion (meshes output_right)"),
    Field("pinion_right", "string", required=False, default="pinion_right",
          help="axial preload: the gear table of the right-hand pinion, above the left-hand one (meshes output_left)"),
    Field("output_right", "string", required=False, default="output_right",
          help="axial preload: the gear table of the right-hand output gear, meshing pinion_left"),
    Field("output_left", "string", required=False, default="output_left",
          help="axial preload: the gear table of the left-hand output gear, meshing pinion_right (clamped to "
               "output_right on the output shaft)"),
    Field("input_stroke", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="axial preload: travel the input shaft's sliding bearings allow along +z (the spring's push) from the "
               "reference position where both meshes sit in the middle of their play"),
    Field("sliding_friction_coefficient", "number", required=False, default=0.1, minimum=0.0, maximum=1.0,
          help="axial preload: friction coefficient of the input shaft's sliding fit (the floating bearings' outer "
               "rings in their bores)"),
    Field("max_friction_to_preload", "number", required=False, default=0.15, minimum=0.0, exclusive_minimum=True,
          help="axial preload: the largest friction force of the sliding fit over the spring force the design "
               "accepts (the helix angle must be large enough)"),
    # the gear ratio the controller needs, from encoder to output
    Field("upstream_stages", "list", required=False, default=(),
          help="[driver_teeth, driven_teeth] of each stage between the encoder and the input gear"),
    Field("required_ratios", "list", required=False, default=(),
          help="whole-number ratios, encoder to output, that the controller accepts (the build checks one is met)"),
]

#: the [layout] keys each kind reads besides the common ones (kind, model_backlash, loaded_flank_gap,
#: upstream_stages, required_ratios): a key of another kind is refused by name, never ignored
KIND_KEYS: dict[str, tuple[str, ...]] = {
    "dual_pinion": ("position", "cluster", "cluster_axial_gap", "input_face_offset", "carriage_travel"),
    "split_pinion": ("centre_distance", "pinion_stiff", "pinion_compliant", "output", "pinion_axial_gap",
                     "circumferential_backlash_min", "circumferential_backlash_max"),
    "axial_preload": ("centre_distance", "pinion_axial_gap", "circumferential_backlash_min",
                      "circumferential_backlash_max", "pinion_left", "pinion_right", "output_right", "output_left",
                      "input_stroke", "sliding_friction_coefficient", "max_friction_to_preload"),
    "rack_dual_pinion": ("carriage_travel", "pinion_spacing", "input_centre_distance", "rack_backlash_min", "rack_backlash_max",
                         "path_backlash_min", "path_backlash_max", "slide_travel", "rack_face_width",
                         "rack_back_height", "path_gear_axial_gap", "rack_loop_error", "carriage_preload_force_N",
                         "carriage_spring_rate_N_per_mm", "gear_elastic_modulus_GPa", "shaft_shear_modulus_GPa",
                         "max_rack_force_N"),
}
COMMON_KEYS = ("kind", "model_backlash", "loaded_flank_gap", "upstream_stages", "required_ratios")


def _refuse_other_kinds_keys(table: dict, kind: str) -> None:
    """A key another layout kind reads, given for ``kind``: refused naming it (it would change nothing)."""
    names = {f.name for f in LAYOUT_FIELDS}
    mine = set(COMMON_KEYS) | set(KIND_KEYS[kind])
    for key in table:
        base = key if key in names else next((key[:-len(u) - 1] for u in LENGTH_SUFFIXES
                                             if key.endswith("_" + u) and key[:-len(u) - 1] in names), None)
        if base is not None and base not in mine:
            owners = [k for k, keys in KIND_KEYS.items() if base in keys]
            raise DesignError(f"layout.{key}", f"does not apply to layout.kind = {kind!r} (a key of "
                              f"{' and '.join(map(repr, owners))})",
                              "leave it out; the keys of this kind: " + ", ".join(sorted(mine - {"kind"})))


#: keys [layout] no longer has -> (what they gave, the key that gives it now: its one home); a file
#: that still has one is told where it went rather than offered the nearest spelling of another key
MOVED_KEYS = {"disengaged_clearance": ("the retracted pinions' axial gap", "[engagement] clearance_<unit>")}

#: the keys a rack dual-pinion layout must give
RACK_DRIVE_KEYS = ("pinion_spacing", "input_centre_distance", "rack_backlash_min", "rack_backlash_max",
                   "path_backlash_min", "path_backlash_max", "slide_travel", "carriage_travel",
                   "carriage_preload_force_N", "carriage_spring_rate_N_per_mm")

#: the keys a split-pinion layout must give (a dual-pinion one takes them from [synthesis])
SPLIT_PINION_KEYS = ("centre_distance", "circumferential_backlash_min", "circumferential_backlash_max")
#: the keys an axial-preload layout must give
AXIAL_PRELOAD_KEYS = SPLIT_PINION_KEYS + ("input_stroke",)


def is_split_pinion(data) -> bool:
    """A loaded design or the parsed file whose ``[layout]`` says ``kind = "split_pinion"`` (the
    drive decides its hardware and its stiffness train)."""
    sections = data.sections if hasattr(data, "sections") else data
    return (sections.get("layout") or {}).get("kind") == "split_pinion"


def is_axial_preload(data) -> bool:
    """A loaded design or the parsed file whose ``[layout]`` says ``kind = "axial_preload"``."""
    sections = data.sections if hasattr(data, "sections") else data
    return (sections.get("layout") or {}).get("kind") == "axial_preload"


def layout_settings(design) -> dict[str, Any]:
    """``[layout]`` read and checked on its own (internal units); see :func:`check_layout`.

    A design without ``[layout]`` (or without its ``kind``) that has a ``[synthesis]`` is a
    dual-pinion drive; ``model_backlash`` left out follows the gear tables: "as_designed" when a
    gear states its thinning, else "mid" (the thinning is then derived, and said so)."""
    table = design.section("layout") or {}
    for key in table:
        for name, (what, home) in MOVED_KEYS.items():
            if key == name or (key.startswith(name + "_") and key[len(name) + 1:] in LENGTH_SUFFIXES):
                raise DesignError(f"layout.{key}", f"no longer a key of [layout]: {what} has one home, {home}",
                                  f"leave it out; give {home}")
    v = read_table(table, LAYOUT_FIELDS, "layout")
    if v["kind"] is None:
        if not design.section("synthesis"):
            raise DesignError("layout.kind", "missing", " | ".join(map(repr, LAYOUT_KINDS))
                              + " (or a [synthesis] section: a dual-pinion drive)")
        v["kind"] = "dual_pinion"
    _refuse_other_kinds_keys(table, v["kind"])
    if v["model_backlash"] is None:
        v["model_backlash"] = "as_designed" if any(g.thinning > 0 for g in design.gears.values()) else "mid"
    for i, stage in enumerate(v["upstream_stages"]):
        if not (isinstance(stage, list) and len(stage) == 2
                and all(isinstance(t, int) and not isinstance(t, bool) and 0 < t <= MAX_TEETH for t in stage)):
            raise DesignError(f"layout.upstream_stages[{i}]", f"{shown(stage)} is not [driver_teeth, driven_teeth]",
                              f"two whole numbers in [1, {MAX_TEETH}] (a worm's starts, a gear's teeth)")
    for i, ratio in enumerate(v["required_ratios"]):
        if isinstance(ratio, bool) or not isinstance(ratio, int) or not 0 < ratio <= MAX_RATIO:
            raise DesignError(f"layout.required_ratios[{i}]", f"{shown(ratio)} is not a whole-number ratio",
                              f"whole numbers in [1, {MAX_RATIO}], e.g. 180 or 360")
    if v["kind"] in ("split_pinion", "axial_preload"):
        for name in SPLIT_PINION_KEYS if v["kind"] == "split_pinion" else AXIAL_PRELOAD_KEYS:
            if v[name] is None:
                raise DesignError(f"layout.{name}", f"missing for {'a split pinion' if v['kind'] == 'split_pinion' else 'an axial preload'}",
                                  " or ".join(f"{name}_{u}" for u in LENGTH_SUFFIXES))
        lo, hi = v["circumferential_backlash_min"], v["circumferential_backlash_max"]
        if lo > hi:
            unit = v["_units"]["circumferential_backlash_min"]
            scale = LENGTH_SUFFIXES[unit]
            raise DesignError(f"layout.circumferential_backlash_min_{unit}",
                              f"{lo / scale:.6g} {unit} is larger than the maximum {hi / scale:.6g} {unit}",
                              f"[0, {hi / scale:.6g}] {unit}")
    if v["kind"] == "rack_dual_pinion":
        for name in RACK_DRIVE_KEYS:
            if v[name] is None:
                allowed = name if name.endswith("_N") or "_N_" in name else " or ".join(
                    f"{name}_{u}" for u in LENGTH_SUFFIXES)
                raise DesignError(f"layout.{name}", "missing for a rack dual-pinion drive", allowed)
        for lo_key, hi_key in (("rack_backlash_min", "rack_backlash_max"), ("path_backlash_min", "path_backlash_max")):
            if v[lo_key] > v[hi_key]:
                unit = v["_units"][lo_key]
                scale = LENGTH_SUFFIXES[unit]
                raise DesignError(f"layout.{lo_key}_{unit}", f"{v[lo_key] / scale:.6g} {unit} is larger than the "
                                  f"maximum {v[hi_key] / scale:.6g} {unit}", f"[0, {v[hi_key] / scale:.6g}] {unit}")
    return v


def check_layout(design, v: dict[str, Any]) -> None:
    """The ``[layout]`` rules that involve other sections of ``design``."""
    if v["kind"] == "dual_pinion" and not design.section("synthesis"):
        raise DesignError("synthesis", "missing: layout.kind = 'dual_pinion' places the gears by the centre synthesis",
                          "a [synthesis] table, or layout.kind = 'split_pinion'")
    if v["kind"] == "split_pinion":
        for role in ("pinion_stiff", "pinion_compliant", "output"):
            if v[role] not in design.gears:
                key = f"layout.{role}" if role in design.section("layout") else f"gears.{v[role]}"
                raise DesignError(key, f"no gear named {v[role]!r} in the design", ", ".join(design.gears))
        stiff, compliant = design.gears[v["pinion_stiff"]], design.gears[v["pinion_compliant"]]
        if compliant.teeth != stiff.teeth:
            # the pinions turn together: with other teeth they would drive the output at two speeds
            raise DesignError(f"gears.{v['pinion_compliant']}.teeth", f"{compliant.teeth} teeth, but "
                              f"gears.{v['pinion_stiff']} has {stiff.teeth}: the two pinions turn together on one "
                              "axis and mesh one output", f"{stiff.teeth}")
    if v["kind"] == "axial_preload":
        from geargen.design.axial_preload import check_axial_gears
        check_axial_gears(design, v)
    if v["position"] == "disengaged" and not design.section("engagement"):
        raise DesignError("layout.position", "'disengaged' needs an [engagement] section", "'engaged'")
    if v["model_backlash"] != "as_designed":
        # a gear's own tooth thinning is never replaced quietly
        thinned = [name for name, g in design.gears.items() if g.thinning > 0]
        if thinned:
            raise DesignError("layout.model_backlash", f"{v['model_backlash']!r} would replace the tooth thinning "
                              f"given for gears.{thinned[0]}", "'as_designed' when a gear table gives thinning_*")


__all__ = ["LAYOUT_KINDS", "MODEL_BACKLASH", "POSITIONS", "LAYOUT_FIELDS", "MOVED_KEYS", "SPLIT_PINION_KEYS",
           "AXIAL_PRELOAD_KEYS", "RACK_DRIVE_KEYS", "is_split_pinion", "is_axial_preload",
           "layout_settings", "check_layout"]
