"""The ``[layout]`` section: how the build places the gears (read by ``geargen.pipeline.place``).

Layout::

    [layout]
    kind = "dual_pinion"              # gears placed by the centre synthesis of [synthesis]
                                      # ("split_pinion": two pinions side by side on one output)
    model_tooth_thickness = "mid_tolerance"  # where in its tooth-thickness allowance each gear of
                                      # the model is made: "mid_tolerance", "max_material" (thickest),
                                      # "min_material" (thinnest), or "as_designed" (the gears' own thinning)
    loaded_flank_gap_mm = 0.0005      # left on the working flanks so the solids do not touch
    position = "engaged"              # sliding pinions ("disengaged" needs [engagement])
    upstream_stages = [[15, 30]]      # [driver_teeth, driven_teeth] between encoder and input
    required_ratios = [32]            # whole-number ratios, encoder to output, the controller needs

A split pinion also needs ``centre_distance_*`` and ``circumferential_backlash_min_*`` /
``_max_*``; an axial preload (``kind = "axial_preload"``, :mod:`geargen.drives.axial_preload.place`) those
and ``input_stroke_*``, its four helical gears named by ``pinion_left``, ``pinion_right``,
``output_right``, ``output_left`` (rules: :mod:`geargen.drives.axial_preload.keys`), its preload and
spring in ``[preload]``. :func:`layout_settings` reads the table; :func:`check_layout` adds the rules that
involve other sections (the gears named, the synthesis, the engagement).
"""

from __future__ import annotations

from typing import Any

from geargen.design.schema import Field, read_table, shown
from geargen.drives.keys import KEYS, LAYOUT_KINDS, kind_of
from geargen.drives.dual_pinion.keys import POSITIONS
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

#: [layout] model_tooth_thickness: where in its tooth-thickness allowance each gear of the model is made
#: -> (the weight w of the upper deviation: the model's deviation is w upper + (1 - w) lower, what it is)
MODEL_POINTS = {
    "mid_tolerance": (0.5, "the middle of its tooth-thickness tolerance"),
    "max_material": (1.0, "its upper deviation (maximum material: the thickest tooth made)"),
    "min_material": (0.0, "its lower deviation (minimum material: the thinnest tooth made)"),
}
#: ... or "as_designed": the gear tables' own thinning
MODEL_TOOTH_THICKNESS = (*MODEL_POINTS, "as_designed")
#: the most teeth of an upstream stage's gear (a GearSpec's most) and the largest required ratio
#: (far past a 360:1 indexing drive)
MAX_TEETH = 2000
MAX_RATIO = 1_000_000

#: each [layout] kind with what it is (its keys module's LAYOUT_HELP), in KEYS' order
_KINDS_HELP = [f"{kind} ({KEYS[kind].LAYOUT_HELP})" for kind in LAYOUT_KINDS]
#: the [layout] keys of every drive kind; each kind reads its own besides (geargen.drives.<kind>.keys)
COMMON_FIELDS = [
    Field("kind", "string", required=False, default=None, choices=LAYOUT_KINDS,
          help="the drive: " + " or ".join((", ".join(_KINDS_HELP[:-1]), _KINDS_HELP[-1]))
               + "; each kind's keys are listed under it"),
    Field("model_tooth_thickness", "string", required=False, default=None, choices=MODEL_TOOTH_THICKNESS,
          help="where in its tooth-thickness allowance (taken where its mesh runs) each gear of the model - its solids, "
               "STEP, STL, DXF and gear data - is made: mid_tolerance (the default), max_material (the upper "
               "deviation, thickest) or min_material (the lower, thinnest); the split of a mesh's thinning between its "
               "gears is the allowance's; or as_designed, the gears' own thinning (the default when a gear gives one; "
               "the check fails a gear whose thinning leaves its allowance)"),
    Field("loaded_flank_gap", "length", required=False, default=0.0, minimum=0.0,
          help="left open on the working flanks so that the solids do not touch"),
    # the gear ratio the controller needs, from encoder to output
    Field("upstream_stages", "list", required=False, default=(),
          help="[driver_teeth, driven_teeth] of each stage between the encoder and the input gear"),
    Field("required_ratios", "list", required=False, default=(),
          help="whole-number ratios, encoder to output, that the controller accepts (the build checks one is met)"),
]


def kind_fields(kind: str) -> list[Field]:
    """The [layout] fields a drive ``kind`` reads: the common ones and its own."""
    return COMMON_FIELDS + list(KEYS[kind].LAYOUT_FIELDS)


def layout_fields() -> list[Field]:
    """Every [layout] field of every kind, each name once (the reference docs list them)."""
    out: dict[str, Field] = {f.name: f for f in COMMON_FIELDS}
    for keys in KEYS.values():
        for f in keys.LAYOUT_FIELDS:
            out.setdefault(f.name, f)
    return list(out.values())


def _refuse_other_kinds_keys(table: dict, kind: str) -> None:
    """A key another layout kind reads, given for ``kind``: refused naming it (it would change nothing)."""
    mine = {f.name for f in kind_fields(kind)}
    every = {f.name for f in layout_fields()}
    for key in table:
        base = key if key in every else next((key[:-len(u) - 1] for u in LENGTH_SUFFIXES
                                             if key.endswith("_" + u) and key[:-len(u) - 1] in every), None)
        if base is not None and base not in mine:
            owners = [k.LAYOUT_KIND for k in KEYS.values() if any(f.name == base for f in k.LAYOUT_FIELDS)]
            raise DesignError(f"layout.{key}", f"does not apply to layout.kind = {kind!r} (a key of "
                              f"{' and '.join(map(repr, dict.fromkeys(owners)))})",
                              "leave it out; the keys of this kind: " + ", ".join(sorted(mine - {"kind"})))


#: keys [layout] no longer has -> (what they gave, the key that gives it now: its one home); a file
#: that still has one is told where it went rather than offered the nearest spelling of another key
MOVED_KEYS = {"disengaged_clearance": ("the retracted pinions' axial gap", "[engagement] clearance_<unit>"),
              "model_backlash": ("the model's tooth thickness (a point of each gear's allowance)",
                                 "[layout] model_tooth_thickness = \"mid_tolerance\" (was \"mid\"), \"min_material\" "
                                 "(was \"max\"), \"max_material\" (was \"min\") or \"as_designed\"")}


def layout_settings(design) -> dict[str, Any]:
    """``[layout]`` read and checked on its own (internal units); see :func:`check_layout`.

    A design without ``[layout]`` (or without its ``kind``) that has a ``[synthesis]`` is a
    dual-pinion drive; ``model_tooth_thickness`` left out follows the gear tables: "as_designed" when
    a gear states its thinning, else "mid_tolerance" (the thinning is then derived, and said so). ``"drive"``
    is the drive kind (:func:`geargen.drives.kind_of`)."""
    table = design.section("layout") or {}
    for key in table:
        for name, (what, home) in MOVED_KEYS.items():
            if key == name or (key.startswith(name + "_") and key[len(name) + 1:] in LENGTH_SUFFIXES):
                raise DesignError(f"layout.{key}", f"no longer a key of [layout]: {what} has one home, {home}",
                                  f"leave it out; give {home}")
    head = read_table({k: v for k, v in table.items() if k == "kind"}, COMMON_FIELDS, "layout")
    if head["kind"] is None and not design.section("synthesis"):
        raise DesignError("layout.kind", "missing", " | ".join(map(repr, LAYOUT_KINDS))
                          + " (or a [synthesis] section: a dual-pinion drive)")
    drive = kind_of(design)
    _refuse_other_kinds_keys(table, drive)
    v = read_table(table, kind_fields(drive), "layout")
    v["kind"] = KEYS[drive].LAYOUT_KIND
    v["drive"] = drive
    if v["model_tooth_thickness"] is None:
        v["model_tooth_thickness"] = ("as_designed" if any(g.thinning > 0 for g in design.gears.values())
                                      else "mid_tolerance")
    for i, stage in enumerate(v["upstream_stages"]):
        if not (isinstance(stage, list) and len(stage) == 2
                and all(isinstance(t, int) and not isinstance(t, bool) and 0 < t <= MAX_TEETH for t in stage)):
            raise DesignError(f"layout.upstream_stages[{i}]", f"{shown(stage)} is not [driver_teeth, driven_teeth]",
                              f"two whole numbers in [1, {MAX_TEETH}] (a worm's starts, a gear's teeth)")
    for i, ratio in enumerate(v["required_ratios"]):
        if isinstance(ratio, bool) or not isinstance(ratio, int) or not 0 < ratio <= MAX_RATIO:
            raise DesignError(f"layout.required_ratios[{i}]", f"{shown(ratio)} is not a whole-number ratio",
                              f"whole numbers in [1, {MAX_RATIO}], e.g. 180 or 360")
    fields = {f.name: f for f in kind_fields(drive)}
    for name in KEYS[drive].REQUIRED:
        if v[name] is None:
            allowed = " or ".join(fields[name].keys())
            raise DesignError(f"layout.{name}", f"missing for layout.kind = {v['kind']!r}", allowed)
    for lo_key, hi_key in KEYS[drive].ORDERED:
        if v[lo_key] > v[hi_key]:
            unit = v["_units"][lo_key]
            scale = LENGTH_SUFFIXES[unit]
            raise DesignError(f"layout.{lo_key}_{unit}", f"{v[lo_key] / scale:.6g} {unit} is larger than the "
                              f"maximum {v[hi_key] / scale:.6g} {unit}", f"[0, {v[hi_key] / scale:.6g}] {unit}")
    return v


def check_layout(design, v: dict[str, Any]) -> None:
    """The ``[layout]`` rules that involve other sections of ``design``: the drive kind's own
    (``check_layout`` of its keys module, where it has one) and the common ones."""
    own = getattr(KEYS[v["drive"]], "check_layout", None)
    if own is not None:
        own(design, v)
    if v.get("position") == "disengaged" and not design.section("engagement"):
        raise DesignError("layout.position", "'disengaged' needs an [engagement] section", "'engaged'")
    if v["model_tooth_thickness"] != "as_designed":
        # a gear's own tooth thinning is never replaced quietly
        thinned = [name for name, g in design.gears.items() if g.thinning > 0]
        if thinned:
            raise DesignError("layout.model_tooth_thickness", f"{v['model_tooth_thickness']!r} would replace the "
                              f"tooth thinning given for gears.{thinned[0]}",
                              "'as_designed' when a gear table gives thinning_*")


__all__ = ["LAYOUT_KINDS", "MODEL_POINTS", "MODEL_TOOTH_THICKNESS", "POSITIONS", "COMMON_FIELDS", "MOVED_KEYS", "kind_fields",
           "layout_fields", "layout_settings", "check_layout"]
