"""``geargen gear``: build one gear and write STEP, STL and a JSON of its derived quantities.

From a design file (a ``[gear]`` table, or ``--gear NAME`` of an assembly file's ``[gears.NAME]``)
or from options::

    geargen gear --teeth 112 --diametral-pitch 32 --pressure-angle 20 --face-width 0.25 --bore 0.3937
    geargen gear --teeth 21 --module 0.79375 --helix-angle 20 --hand left --face-width 12.7 --out out/

Writes ``DIR/NAME.step`` (in the design's length unit), ``DIR/NAME.stl`` (mm, chordal tolerance
``--stl-tolerance`` mm), ``DIR/NAME.json`` (radii, thicknesses, tip land, undercut, span and
over-pins/balls, in the design's length unit; angles in degrees; with a thickness allowance,
``--thickness-allowance`` or the design's, its span and over-pins limits), the manufacturing drawing
``DIR/NAME-drawing.svg`` and ``.pdf`` (:mod:`geargen.report.drawing`) and the exact transverse
profile ``DIR/NAME.dxf`` for wire EDM (:mod:`geargen.report.dxf`), unless ``--no-drawing``, and
``DIR/manifest.json``. A gear of an assembly's drive (``--gear``) is drawn with its mating gears
and working centre distances from the resolved drive.

DIR (default ``exports/NAME``) follows the folder policy of :mod:`geargen.outputs`: it must not
exist, be empty, or hold an earlier ``geargen gear`` output of the same gear (same name, from the
same design file and table, or from options), which is replaced whole; ``--overwrite`` also
replaces an earlier gear output of another source. An assembly's build folder is never written.

A design file and gear options are alternatives: an option given with a design file is refused
(naming it), never ignored. Errors name the option (``--teeth``), not the design-file key.
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

from geargen.design.gear import DRAWN_TEXT_MAX, GEAR_FIELDS, GearSpec
from geargen.design.schema import GEAR_NAME_MAX, check_name, shown
from geargen.errors import DesignError, clipped
from geargen.families.registry import FAMILIES, family_of, read_gear
from geargen.units import from_mm, to_mm


#: the kinds read from the cylindrical gear's table (its teeth, face width and pitch options required)
CYLINDRICAL_KINDS = tuple(kind for kind, family in FAMILIES.items() if family.FIELDS is GEAR_FIELDS)


def add_arguments(p) -> None:
    p.add_argument("design", nargs="?", help="design file (TOML) with a [gear] table, or an assembly file with --gear")
    p.add_argument("--gear", metavar="NAME", help="build [gears.NAME] of an assembly design file")
    g = p.add_argument_group("gear options (instead of a design file)")
    g.add_argument("--kind", choices=tuple(FAMILIES), default=None,
                   help="the gear's kind (default external: spur or helical); a kind's own options are listed "
                        "under it below")
    g.add_argument("--teeth", type=int, help="number of teeth")
    pitch = g.add_mutually_exclusive_group()
    pitch.add_argument("--module", type=float, metavar="MM", help="module in mm (metric design: lengths in mm)")
    pitch.add_argument("--diametral-pitch", type=float, metavar="PER_IN",
                       help="diametral pitch, teeth per inch (inch design: lengths in inches)")
    g.add_argument("--pitch-system", choices=("normal", "transverse"), default=None,
                   help="helical gears: module/pitch and pressure angle given in the normal (default) or transverse section")
    g.add_argument("--pressure-angle", type=float, default=None, metavar="DEG", help="pressure angle, degrees (default 20)")
    g.add_argument("--helix-angle", type=float, default=None, metavar="DEG", help="helix angle, degrees (default 0: spur)")
    g.add_argument("--hand", choices=("right", "left"), default=None, help="helix hand (default right)")
    g.add_argument("--profile-shift", type=float, default=None, metavar="X", help="profile shift coefficient x (default 0)")
    g.add_argument("--face-width", type=float, metavar="LEN",
                   help="face width in the unit of the pitch system: mm with --module, inches with --diametral-pitch")
    g.add_argument("--face-width-mm", type=float, metavar="MM", help="face width in mm")
    g.add_argument("--face-width-in", type=float, metavar="IN", help="face width in inches")
    g.add_argument("--bore", type=float, metavar="LEN", help="bore diameter in the unit of the pitch system (default: none)")
    g.add_argument("--bore-mm", type=float, metavar="MM", help="bore diameter in mm")
    g.add_argument("--bore-in", type=float, metavar="IN", help="bore diameter in inches")
    g.add_argument("--centre-gap", type=float, metavar="LEN", default=None,
                   help="--kind double_helical: axial gap between the two helical halves, a relief groove at the root "
                        "diameter, in the unit of the pitch system (default 0: a herringbone)")
    g.add_argument("--thinning", type=float, metavar="LEN", default=None,
                   help="tooth thinning for backlash: circumferential (transverse arc at the reference circle), "
                        "in the unit of the pitch system (default 0)")
    g.add_argument("--accuracy-grade", type=int, default=None, metavar="A",
                   help="ISO 1328-1:2013 flank tolerance class 1..11: the gear data gains its tolerances "
                        "(--kind bevel: ISO 17485 grade 2..11, recorded)")
    shop = p.add_argument_group("drawing data (cylindrical gears; the gear table's keys of the same names)")
    for flag, metavar, help_ in SHOP_OPTIONS.values():
        shop.add_argument(flag, default=None, type=float if metavar in ("HV", "HRC", "UM") else str, metavar=metavar,
                          help=help_)
    g.add_argument("--name", default=None,
                   help=f"part name, the files' names (default: the [gear] file's, or gear_<teeth>): at most {GEAR_NAME_MAX} "
                        "of A-Z a-z 0-9 _ - .")
    for kinds, module in _kind_modules().items():
        module.add_arguments(p.add_argument_group(f"--kind {' / '.join(kinds)} options"))
    p.add_argument("--thickness-allowance", type=float, nargs=2, metavar=("UPPER", "LOWER"), default=None,
                   help="tooth-thickness allowance in um: upper and lower deviation of the normal tooth thickness "
                        "from the zero-backlash tooth (both <= 0, UPPER >= LOWER); the JSON gains the span and "
                        "over-pins limits. Default: the gear table's thickness_*_deviation_*, or for a gear of a "
                        "drive (--gear) the allowance chosen from its meshes' backlash ranges")
    p.add_argument("--thickness-series", metavar="DESIGNATION", default=None,
                   help="DIN 3967 tooth-thickness allowance (upper series a..h, tolerance series 21..30, e.g. cd25) "
                        "of a gear made alone; default: the gear table's thickness_allowance_series, else cd25")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="output folder (default: exports/<name>); must not exist, be empty, or hold an earlier "
                        "geargen gear output of the same gear, which is replaced")
    p.add_argument("--overwrite", action="store_true",
                   help="also replace an earlier geargen gear output of another source (never a folder holding "
                        "other files, nor an assembly's build)")
    p.add_argument("--stl-tolerance", type=float, default=1e-3, metavar="MM",
                   help="STL chordal tolerance in mm (default 0.001 = 1 um)")
    p.add_argument("--no-stl", action="store_true", help="skip the STL")
    p.add_argument("--no-drawing", action="store_true",
                   help="skip the manufacturing drawing (NAME-drawing.svg/.pdf) and the profile DXF (NAME.dxf)")
    p.add_argument("--measure", action="store_true",
                   help="also section the solid and report the measured flank deviation, span and over-pins size")


#: the drawing-data options: argparse dest -> (flag, metavar, help); each sets the gear-table key of
#: :data:`SHOP_KEYS`
SHOP_OPTIONS = {
    "part_number": ("--part-number", "TEXT", "part (identification) number in the title block (at most "
                    f"{DRAWN_TEXT_MAX['part_number']} characters)"),
    "revision": ("--revision", "TEXT", f"drawing revision index (at most {DRAWN_TEXT_MAX['revision']} characters)"),
    "material": ("--material", "TEXT", f"material, e.g. '42CrMo4 (1.7225)' (at most {DRAWN_TEXT_MAX['material']} "
                 "characters)"),
    "heat_treatment": ("--heat-treatment", "TEXT", "heat treatment, e.g. 'quenched and tempered' (at most "
                       f"{DRAWN_TEXT_MAX['heat_treatment']} characters)"),
    "hardness_hv": ("--hardness-hv", "HV", "surface hardness, Vickers"),
    "hardness_hrc": ("--hardness-hrc", "HRC", "surface hardness, Rockwell C"),
    "flank_roughness_ra": ("--flank-roughness-ra", "UM", "flank roughness Ra in um"),
    "bore_fit": ("--bore-fit", "CLASS", "ISO 286-1 class of the bore, e.g. H7 (limits computed)"),
    "tip_diameter_tolerance": ("--tip-diameter-tolerance", "CLASS", "ISO 286-1 class of the tip diameter (default h11)"),
    "face_width_tolerance": ("--face-width-tolerance", "CLASS", "ISO 286-1 class of the face width (default h11)"),
}
#: drawing-data option dest -> the gear-table key it sets
SHOP_KEYS = {"part_number": "part_number", "revision": "revision", "material": "material",
             "heat_treatment": "heat_treatment", "hardness_hv": "hardness_HV", "hardness_hrc": "hardness_HRC",
             "flank_roughness_ra": "flank_roughness_Ra_um", "bore_fit": "bore_fit",
             "tip_diameter_tolerance": "tip_diameter_tolerance", "face_width_tolerance": "face_width_tolerance"}

#: the gear options (argparse dest -> flag) and the value each stands for when not given
GEAR_OPTIONS = {"teeth": ("--teeth", None), "module": ("--module", None),
                "diametral_pitch": ("--diametral-pitch", None), "pitch_system": ("--pitch-system", "normal"),
                "pressure_angle": ("--pressure-angle", 20.0), "helix_angle": ("--helix-angle", 0.0),
                "hand": ("--hand", "right"), "profile_shift": ("--profile-shift", 0.0),
                "face_width": ("--face-width", None), "face_width_mm": ("--face-width-mm", None),
                "face_width_in": ("--face-width-in", None), "bore": ("--bore", None), "bore_mm": ("--bore-mm", None),
                "bore_in": ("--bore-in", None), "thinning": ("--thinning", None), "centre_gap": ("--centre-gap", None),
                "accuracy_grade": ("--accuracy-grade", None),
                **{dest: (flag, None) for dest, (flag, _, _) in SHOP_OPTIONS.items()}}


def _kind_modules() -> dict[tuple[str, ...], object]:
    """Each family's own options module (:meth:`geargen.families.family.GearFamily.options`: its
    ``add_arguments(group)``, ``OPTIONS`` {argparse dest: (flag, design-table key stem, whether the
    value is a length in the pitch system's unit)} and ``COMMON``, the dests of :data:`GEAR_OPTIONS`
    the kind reads; a common option the kind does not read is refused) once, with the kinds it
    serves. Options map to the kind's design-table keys, so a command line and a ``[gear]`` table
    are read by the same reader."""
    by_module: dict[object, list[str]] = {}
    for kind, family in FAMILIES.items():
        module = family.options()
        if module is not None:
            by_module.setdefault(module, []).append(kind)
    return {tuple(kinds): module for module, kinds in by_module.items()}


def _kind_option_table() -> dict[str, tuple]:
    """argparse dest -> (flag, key stem, is_length, kinds that take it) of every kind's own option."""
    out: dict[str, tuple] = {}
    for kinds, module in _kind_modules().items():
        for dest, (flag, key, is_length) in module.OPTIONS.items():
            out[dest] = (flag, key, is_length, out.get(dest, (None, None, None, ()))[3] + kinds)
    return out


def unset_options() -> dict[str, None]:
    """Every gear option's argparse dest (the common ones, ``kind`` and each kind's own), unset: the
    namespace a caller that is not the command line starts from."""
    return {dest: None for dest in [*GEAR_OPTIONS, "kind", *_kind_option_table()]}


def _given(args) -> list[str]:
    """The flags of the gear options given on the command line (the kind's own ones too)."""
    given = [flag for dest, (flag, _) in GEAR_OPTIONS.items() if getattr(args, dest, None) is not None]
    given += [row[0] for dest, row in _kind_option_table().items() if getattr(args, dest, None) is not None]
    if getattr(args, "kind", None) is not None:
        given.append("--kind")
    return given


def _option(args, dest):
    value = getattr(args, dest)
    return GEAR_OPTIONS[dest][1] if value is None else value


def _flag_of_key(key: str, table: dict, given: list[str]) -> str:
    """The flag that set the gear-table key ``key`` (``face_width_mm`` -> the face-width flag used)."""
    base = {"teeth": "--teeth", "module_mm": "--module", "diametral_pitch_per_in": "--diametral-pitch",
            "pitch_system": "--pitch-system", "pressure_angle_deg": "--pressure-angle",
            "helix_angle_deg": "--helix-angle", "hand": "--hand", "profile_shift": "--profile-shift",
            "accuracy_grade": "--accuracy-grade"}
    if key in base:
        return base[key]
    shop = {k: SHOP_OPTIONS[d][0] for d, k in SHOP_KEYS.items()}
    if key in shop:
        return shop[key]
    if key == "kind":
        return "--kind"
    kind = table.get("kind", "external")
    for dest, (flag, stem, is_length, kinds) in _kind_option_table().items():
        # only the gear's own kind's options (a spur gear's thinning is --thinning, not --bevel-thinning)
        if kind in kinds and (key == stem or (is_length and key.rsplit("_", 1)[0] == stem)):
            return flag
    for stem, flag in (("face_width", "--face-width"), ("bore_diameter", "--bore"), ("centre_gap", "--centre-gap"),
                       ("thinning_circumferential", "--thinning")):
        if key.startswith(stem):
            used = [f for f in given if f.startswith(flag)]
            return used[0] if used else flag
    return f"--{key.replace('_', '-')}"


def spec_from_args(args, layout=None) -> tuple[GearSpec, str | None]:
    """The GearSpec the command line describes (through the design-file validation), and where an
    assembly gear's thinning comes from (None for a gear file or options: as given). ``layout``:
    the drive of ``--gear`` already resolved (:func:`drive_layout`), so it is resolved once.

    A design file and gear options exclude each other: an option given with a design file is
    an error naming it (it would otherwise be ignored). Errors in the options name the option."""
    flags_given = _given(args)
    if args.gear and not args.design:
        raise DesignError("--gear", "needs an assembly design file", "geargen gear FILE.toml --gear NAME")
    if args.name is not None:
        if args.gear:
            raise DesignError("--name", f"the gear of --gear is named by its table [gears.{clipped(args.gear, 40)}]",
                              "--name with gear options or a [gear] file")
        check_name("--name", args.name, GEAR_NAME_MAX)
    if args.design and flags_given:
        raise DesignError(flags_given[0], f"conflicts with the design file {args.design}, which gives the gear",
                          "a design file or gear options, not both")
    if args.design:
        from geargen.design.schema import load_toml
        data = load_toml(args.design)
        if args.gear:
            from geargen.design.assembly import load_design
            return assembly_gear(load_design(args.design), args.gear, layout)
        if "gear" not in data:
            raise DesignError(str(args.design), "no [gear] table (use --gear NAME for an assembly file)")
        unknown = [k for k in data if k != "gear"]
        if unknown:
            raise DesignError(unknown[0], "unknown key or section in a gear design file", "[gear]")
        return read_gear(data["gear"], where="gear", name=_file_gear_name(args, data["gear"])), None
    kind = args.kind or "external"
    table = _kind_table(args, kind, flags_given)
    if args.module is None and args.diametral_pitch is None:
        raise DesignError("--module", "give a design file, or --module or --diametral-pitch (and the gear's options)")
    if kind in CYLINDRICAL_KINDS and args.teeth is None:
        raise DesignError("--teeth", "give a design file, or --teeth and --module or --diametral-pitch")
    unit = "mm" if args.module is not None else "in"
    if kind in CYLINDRICAL_KINDS:
        table.update({"pitch_system": _option(args, "pitch_system"), "pressure_angle_deg": _option(args, "pressure_angle"),
                      "helix_angle_deg": _option(args, "helix_angle"), "hand": _option(args, "hand"),
                      "profile_shift": _option(args, "profile_shift")})
    else:  # another family's reader takes only what was given, with its own defaults
        for dest, key in (("pitch_system", "pitch_system"), ("pressure_angle", "pressure_angle_deg"),
                          ("helix_angle", "helix_angle_deg"), ("hand", "hand"), ("profile_shift", "profile_shift")):
            if getattr(args, dest) is not None:
                table[key] = getattr(args, dest)
    if args.teeth is not None:
        table["teeth"] = args.teeth
    if args.module is not None:
        table["module_mm"] = args.module
    else:
        table["diametral_pitch_per_in"] = args.diametral_pitch
    for dest, (flag, key, is_length, kinds) in _kind_option_table().items():
        value = getattr(args, dest, None)
        if value is not None:
            table[f"{key}_{unit}" if is_length else key] = value
    for key, plain, mm, inch in (("face_width", args.face_width, args.face_width_mm, args.face_width_in),
                                 ("bore_diameter", args.bore, args.bore_mm, args.bore_in)):
        given = [(u, v) for u, v in ((unit, plain), ("mm", mm), ("in", inch)) if v is not None]
        if len(given) > 1:
            raise DesignError(f"--{key.replace('_', '-')}", "given more than once", "one of LEN, -mm, -in")
        if given:
            table[f"{key}_{given[0][0]}"] = given[0][1]
    if kind in CYLINDRICAL_KINDS and "face_width_mm" not in table and "face_width_in" not in table:
        raise DesignError("--face-width", "missing", "--face-width, --face-width-mm or --face-width-in")
    if args.thinning:
        table[f"thinning_circumferential_{unit}"] = args.thinning
    if args.centre_gap is not None:
        table[f"centre_gap_{unit}"] = args.centre_gap
    if args.accuracy_grade is not None:
        table["accuracy_grade"] = args.accuracy_grade
    for dest, key in SHOP_KEYS.items():
        if getattr(args, dest, None) is not None:
            table[key] = getattr(args, dest)
    name = args.name or (f"gear_{args.teeth}" if kind == "external" else f"{kind}_{args.teeth}" if args.teeth else kind)
    try:
        return read_gear(table, where="options", name=name, length_unit=unit), None
    except DesignError as exc:
        if not exc.field.startswith("options."):
            raise
        raise DesignError(_flag_of_key(exc.field.split(".", 1)[1], table, flags_given), exc.problem, exc.allowed) from None


def _file_gear_name(args, table) -> str:
    """The name of a ``[gear]`` file's gear: ``--name``, else the table's ``name``, else the file's
    name, checked like every name that becomes a file name."""
    written = table.get("name") if isinstance(table, dict) else None
    if args.name is not None or written is not None:
        return args.name if args.name is not None else check_name("gear.name", written, GEAR_NAME_MAX)
    stem = Path(args.design).stem
    try:
        return check_name("gear.name", stem, GEAR_NAME_MAX)
    except DesignError as exc:
        raise DesignError("gear.name", f"missing, and the file's name {shown(stem)} is not a valid gear name",
                          f'name = "..." in [gear], or --name; {exc.allowed}') from None


def _kind_table(args, kind: str, flags_given: list[str]) -> dict:
    """The start of the options' design table for ``kind``: its ``kind`` key, after refusing the
    options that do not apply to it (another kind's own option, or a common option it does not read)."""
    for dest, (flag, key, is_length, kinds) in _kind_option_table().items():
        if getattr(args, dest, None) is not None and kind not in kinds:
            raise DesignError(flag, f"does not apply to --kind {kind}", f"--kind {' or '.join(kinds)}")
    if kind not in CYLINDRICAL_KINDS:
        module = dict((k, m) for ks, m in _kind_modules().items() for k in ks).get(kind)
        common = getattr(module, "COMMON", ())
        for dest, (flag, _) in GEAR_OPTIONS.items():
            if getattr(args, dest, None) is not None and dest not in common:
                raise DesignError(flag, f"does not apply to --kind {kind}",
                                  ", ".join(GEAR_OPTIONS[d][0] for d in common) or "the kind's own options")
    return {} if kind == "external" else {"kind": kind}


def assembly_gear(design, name: str, layout=None) -> tuple[GearSpec, str]:
    """``[gears.NAME]`` of an assembly as the assembly builds it, and where its thinning comes from:
    in a drive the resolved one (``layout``, or :func:`geargen.model.resolve`: the thinning the
    design states, or the one at the model's point of its allowance), else the table as written."""
    from geargen.model import is_drive
    from geargen.drives.resolver import resolve

    spec = design.gear(name)  # names the key when there is no such gear
    if not is_drive(design):
        return spec, "design"
    layout = resolve(design) if layout is None else layout
    for placed in layout.gears:
        for g in placed.gears:
            if g.name == name:
                return g, layout.thinning.get(placed.name, {}).get("source", "design")
    return spec, "design"


def drive_layout(args):
    """The resolved drive of ``geargen gear FILE --gear NAME`` (None for a gear file, options, or an
    assembly that is no drive): resolved once for the gear, its allowance and its mates."""
    if not (args.design and args.gear) or _given(args):
        return None  # spec_from_args says what is wrong
    from geargen.design.assembly import load_design
    from geargen.model import is_drive
    from geargen.drives.resolver import resolve
    design = load_design(args.design)
    return resolve(design) if is_drive(design) else None


def gear_source(args, spec: GearSpec) -> str:
    """What a gear output is of, as its manifest records it (``"source"``): the gear's name and the
    design file (and table) or the options it came from."""
    if args.design:
        origin = str(Path(args.design).resolve()) + (f" [gears.{args.gear}]" if args.gear else " [gear]")
    else:
        origin = "command-line options"
    return f"gear {spec.name} from {origin}"


def gear_allowance(args, spec: GearSpec):
    """The allowance ``--thickness-allowance`` or the gear table enters
    (:class:`geargen.core.allowance.ThicknessAllowance`), or None; the option is refused when the
    gear table enters one too. A drive's gear without either takes the drive's (see :func:`run`)."""
    from geargen.core.allowance import ThicknessAllowance
    from geargen.model.allowance import entered_allowance

    given = getattr(args, "thickness_allowance", None)
    if _spec_allowance(spec) is not None:  # its spec carries the allowance (with_entered_allowance)
        return None
    if not isinstance(spec, GearSpec):  # the other families enter their thinning only
        if given is not None:
            raise DesignError("--thickness-allowance", f"applies to cylindrical gears, not --kind {spec.kind}",
                              "a cylindrical gear")
        return None
    if given is not None:
        if getattr(spec, "thickness_deviations", None) is not None:
            raise DesignError("--thickness-allowance", f"conflicts with the thickness deviations the design file gives "
                              f"gear {spec.name}", "the option or the design keys, not both")
        upper, lower = given
        return ThicknessAllowance(upper * 1e-3, lower * 1e-3, "entered (--thickness-allowance)",
                                  "--thickness-allowance")
    if getattr(spec, "thickness_deviations", None) is not None:  # other families have no allowance
        return entered_allowance(spec, f"gears.{spec.name}.thickness_upper_deviation_um")
    return None


def _spec_allowance(spec):
    """``with_allowance(spec, given)`` of the options module of a family whose spec carries an
    entered allowance (the rack's), else None."""
    return getattr(family_of(spec).options(), "with_allowance", None)


def with_entered_allowance(args, spec):
    """A spec that carries its allowance with the one ``--thickness-allowance`` gives it (its
    family's ``with_allowance``); any other spec as it is (:func:`gear_allowance` reads theirs)."""
    given = getattr(args, "thickness_allowance", None)
    enter = _spec_allowance(spec)
    return spec if given is None or enter is None else enter(spec, given)


def _check_shop_keys(args, spec) -> None:
    """The drawing keys' ISO 286 classes and DIN 3967 designation, checked before the gear is built;
    errors name the design key, or the option that set it."""
    from geargen.model.gear_data import check_shop_keys
    if not isinstance(spec, GearSpec):
        return
    if args.design:
        check_shop_keys(spec, f"gears.{args.gear}." if args.gear else "gear.")
        return
    try:
        check_shop_keys(spec, "")
    except DesignError as exc:
        raise DesignError(_flag_of_key(exc.field, {}, _given(args)), exc.problem, exc.allowed) from None


def standalone_allowance(args, spec, layout):
    """A gear made alone (options, a [gear] file, or an assembly gear outside a drive) without an
    allowance of its own is ordered with the DIN 3967 one of ``--thickness-series`` or its table's
    ``thickness_allowance_series`` (default cd25), so its span and over-pins limits are printed."""
    from geargen.core.allowance import series_allowance
    given = getattr(args, "thickness_series", None)
    if layout is not None or not isinstance(spec, GearSpec) or spec.kind != "external":
        if given is not None:
            raise DesignError("--thickness-series", "applies to an external gear made alone, not to a drive's gear "
                              "(whose allowance comes from its meshes' backlash)", "an external gear without --gear")
        return None
    return series_allowance(spec, given, "--thickness-series" if given else "thickness_allowance_series")


def prepared_gear(args, layout=None):
    """The gear ``args`` describe, ready to build: ``(spec, thinning source, allowance)``, every option
    and drawing key checked (``layout``: the resolved drive of an assembly's gear, :func:`drive_layout`)."""
    spec, thinning_source = spec_from_args(args, layout)
    spec = with_entered_allowance(args, spec)
    _check_shop_keys(args, spec)
    allowance = gear_allowance(args, spec)
    if allowance is None and layout is not None:
        from geargen.pipeline import drive_allowances_of
        allowance = drive_allowances_of(layout).get(spec.name)
    elif getattr(args, "thickness_series", None) is not None and allowance is not None:
        raise DesignError("--thickness-series", "conflicts with the allowance entered for the gear",
                          "--thickness-series or --thickness-allowance / the design's deviations, not both")
    if allowance is None:
        allowance = standalone_allowance(args, spec, layout)
        if allowance is not None and spec.thinning == 0:
            # an unthinned model would measure outside the limits it is drawn with: the model is made
            # at the middle of the allowance, as a drive's gears are by default
            from geargen.core.allowance import made_at
            spec, thinning_source = made_at(spec, allowance, 0.5), "mid-tolerance of its DIN 3967 allowance"
    return spec, thinning_source, allowance


def run(args) -> int:
    layout = drive_layout(args)
    spec, thinning_source, allowance = prepared_gear(args, layout)
    from geargen.outputs import OutputFolder
    source = gear_source(args, spec)
    output = OutputFolder(Path(args.out) if args.out else Path("exports") / spec.name, "geargen gear", source,
                          overwrite=args.overwrite, flag="--out" if args.out else "output folder")
    output.prepare()  # refused or unwritable: said before the gear is built
    try:
        target, names = _write_gear(args, spec, thinning_source, output, allowance, layout)
    except BaseException:
        output.discard()
        raise
    for name in names:
        print(target / name)
    return 0


def _drawn(spec) -> bool:
    """Whether the manufacturing drawing and DXF are made for this gear's kind."""
    return isinstance(spec, GearSpec) and spec.kind == "external"


def _write_gear(args, spec, thinning_source: str | None, output, allowance=None,
                layout=None) -> tuple[Path, list[str]]:
    """Build the gear and write its files and manifest into ``output``'s folder; returns the target,
    committed, and the names written."""
    from geargen import __version__
    from geargen.cad.export import update_manifest, write_json

    out = output.work
    records, data_file, drawn = gear_files(args, spec, thinning_source, out, output.source, allowance, layout)
    update_manifest(out, records, extra={"length_unit": spec.length_unit, "generator": "geargen gear",
                                         "source": output.source, "version": __version__})
    # the data file and drawings are listed too, so a later run recognises every file here as its own
    manifest_path = out / "manifest.json"
    manifest = json.loads(manifest_path.read_text())
    for path in [data_file] + list(drawn.values()):
        manifest["files"][path.name] = {"format": path.suffix.lstrip("."), "length_unit": spec.length_unit,
                                        "bytes": path.stat().st_size}
    write_json(manifest_path, manifest)
    return output.commit(), [r.path.name for r in records] + [data_file.name] + [p.name for p in drawn.values()]


def gear_files(args, spec, thinning_source: str | None, out: Path, source: str, allowance=None,
               layout=None) -> tuple[list, Path, dict[str, Path]]:
    """Build the gear and write NAME.step, NAME.stl, NAME.json and its drawings into the folder
    ``out`` (no manifest); returns (the STEP/STL export records, the data file, the drawings). A gear
    of a resolved drive (``layout``) gets the drive's gear data, as the build's drawings."""
    from geargen.cad.export import export_step, export_stl, write_json
    from geargen.cad.families import build_part
    from geargen.profile.tooth import UndercutWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UndercutWarning)
        t0 = time.perf_counter()
        solid = build_part(spec, check=True)
        t_build = time.perf_counter() - t0
    for w in caught:
        print(f"geargen gear: warning: {w.message}", file=sys.stderr)
    records = [export_step(solid, out / f"{spec.name}.step", spec.length_unit)]
    if not args.no_stl:
        records.append(export_stl(solid, out / f"{spec.name}.stl", args.stl_tolerance))
    if layout is not None:
        from geargen.pipeline import drive_gear_data
        data = drive_gear_data(layout, spec, solid.profile, allowance)
    elif isinstance(spec, GearSpec):
        from geargen.model.gear_data import gear_data
        data = gear_data(spec, solid.profile, allowance)
        if thinning_source is not None:
            data["thinning_source"] = thinning_source
        if args.design and args.gear:  # a gear of a file that places no drive: its mates are [checks] meshes'
            from geargen.design.assembly import load_design
            from geargen.design.checks import checks_settings
            from geargen.report.drawing import mates_from_declared
            design = load_design(args.design)
            data["mating_gears"] = [m.to_dict() for m in mates_from_declared(design, checks_settings(design),
                                                                              spec.name, spec.length_unit)]
    else:
        data = family_of(spec).gear_data(spec)
    data["timings_s"] = {"build": t_build, **{r.format: r.seconds for r in records}}
    data["files"] = [r.path.name for r in records]
    if args.measure:
        if not _drawn(spec):
            raise DesignError("--measure", f"measures external gears only, not --kind {getattr(spec, 'kind', '?')}",
                              "an external gear")
        data["measured"] = _measure(solid, data)
    drawn = {}
    design_file = str(Path(args.design).resolve()) if args.design else "command-line options"
    if not args.no_drawing and _drawn(spec):
        from geargen.report.drawing import gear_drawings
        data.setdefault("mating_gears", [])  # a drive's gear has its mates already
        drawn = gear_drawings(data, solid.profile, out, spec.name, source, design_file)
    elif not args.no_drawing:
        drawn = family_of(spec).drawings(data, spec, out, spec.name, source, design_file) or {}
    data_file = out / f"{spec.name}.json"
    write_json(data_file, data)
    return records, data_file, drawn


def _measure(solid, data) -> dict:
    """Flank deviation (um) at three heights, span and over-pins on the mid-face section."""
    from geargen.cad.measure import flank_deviation, over_balls_on_section, section, span_on_section

    spec, profile = solid.spec, solid.profile
    u = spec.length_unit
    heights = [0.05 * spec.face_width, 0.5 * spec.face_width, 0.95 * spec.face_width]
    out = {"flank_deviation_max_um": max(flank_deviation(solid.shape, profile, z).max_abs for z in heights) * 1e3}
    cut = section(solid.shape, heights[1], 128)
    if data.get("span"):
        k = data["span"]["teeth_spanned"]
        out["span_normal"] = float(from_mm(span_on_section(solid.shape, profile, k, heights[1], cut=cut).normal, u))
    if data.get("over_pins"):
        d = to_mm(data["over_pins"]["diameter"], u)
        out["over_pins_dimension"] = float(from_mm(over_balls_on_section(solid.shape, profile, d, heights[1], cut=cut).size, u))
    return out
