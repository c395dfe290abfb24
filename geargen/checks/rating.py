"""Load capacity of every mesh of a resolved drive: ISO 6336-2/-3:2019 method B over the duty's
spectrum, summed by ISO 6336-6 (Palmgren-Miner).

:func:`rate_drive` is the entry point: ``rate_drive(layout, summary=None) -> DriveRating``. It
takes the loads every flank carries from :func:`geargen.model.mesh_loads.mesh_loads` (the preload,
each path's share of the drive torque by Eqs. 2-6, the unloaded path, the upstream stages), the
duty and materials from ``[duty]`` and ``[materials.GEAR]`` (:mod:`geargen.design.duty`), the
minimum safety factors from ``[checks]`` (``min_S_H``, ``min_S_F``), and rates every mesh with
:func:`geargen.core.load_capacity.rate_mesh`:

* every load case alone over the whole life (the preload alone; each level of the spectrum), all
  factors by their names in the standard, and the face width at which it reaches the minimum;
* per mesh and flank, the safety factors S_H and S_F of each gear: the ISO 6336-6 spectrum's (the
  factor on every level's stress that makes the Palmgren-Miner sum 1), or, for a flank no level
  loads, its preload case's; a mesh fails when one is below the minimum;
* the face width at which the spectrum reaches the minimum safety factors: what the narrower
  compliant path of a type 1 drive needs (the paper: "accordingly the gear face widths differ"),
  at the loads of the drive as designed (a narrower gear's mesh is a little softer, which moves the
  paths' shares a little: rate the drive again at the width chosen).

Bevel and worm meshes are named as not rated by ISO 6336 (ISO 10300 / ISO/TS 14521), an upstream
stage without gear tables (a bought gearhead) as rated by its maker.

Units: the result keeps N, N·mm, mm, rpm, h internally; :meth:`DriveRating.to_dict` gives the
contract's N, N/mm^2, m/s with lengths in mm and torques in N·m; :meth:`DriveRating.lines` the
design's length unit and the torque unit the file wrote its loads in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from geargen.core.iso6336_materials import Material
from geargen.core.load_capacity import STANDARD, LoadCase, MeshRating, RatingConditions, rate_mesh
from geargen.design.duty import DutySpec, GearMaterial
from geargen.design.stiffness import QUANTITY_SUFFIXES
from geargen.errors import DesignError
from geargen.model.mesh_loads import MeshLoads, mesh_loads
from geargen.units import from_mm

SPECTRUM = "ISO 6336-6 (Palmgren-Miner)"

#: what a failing mesh is rated again with, in this order, the first that meets the minimum safety
#: factors offered as its fix: each ISO 6336-5 material at quality MQ (a sloped line at the top of its
#: hardness range), alone and then with ground flanks (ISO 1328 class 5, R_a 0.4 um: what grinding
#: after hardening holds)
FIX_MATERIALS = (("through_hardened", "MQ"), ("induction_hardened", "MQ"), ("nitrided", "MQ"),
                 ("case_carburised", "MQ"), ("case_carburised", "ME"))
GROUND_FINISH = {"accuracy_grade": 5, "roughness": 0.4e-3}
LBF = 4.4482216152605  # N per pound-force
#: how the torque suffixes of a design file are written in a report
_TORQUE_TEXT = {"Nm": "N·m", "Nmm": "N·mm", "in_lbf": "in·lbf", "ft_lbf": "ft·lbf"}


@dataclass(frozen=True)
class FlankRating:
    """One flank of a mesh (gear 1's "ccw"/"cw", :mod:`geargen.model.mesh_loads`): the safety
    factors of gear 1 and gear 2 against pitting (``S_H``) and bending (``S_F``), what they are
    (``basis``: the spectrum's, or the preload case's), the Palmgren-Miner sums (None without a
    spectrum) and the largest load on the flank (N)."""

    flank: str
    S_H: tuple[float, float]
    S_F: tuple[float, float]
    basis: str
    D_H: tuple[float, float] | None
    D_F: tuple[float, float] | None
    peak_load: float


@dataclass(frozen=True)
class RatedMesh:
    """One mesh: its loads, the rating (None when not rated: ``scope`` says why), the materials,
    accuracy grade, speed and conditions it was rated with, its flanks and what fails."""

    loads: MeshLoads
    rating: MeshRating | None = None
    materials: tuple[GearMaterial, GearMaterial] | None = None
    accuracy_grade: int | None = None
    speed: float | None = None  # gear 1, rpm
    conditions: RatingConditions | None = None
    flanks: tuple[FlankRating, ...] = ()
    failures: tuple[str, ...] = ()
    scope: str | None = None

    @property
    def name(self) -> str:
        return self.loads.name

    @property
    def rated(self) -> bool:
        return self.rating is not None

    @property
    def ok(self) -> bool:
        return not self.failures

    @property
    def face_width(self) -> float | None:
        """The carrying face width rated (mm)."""
        return self.rating.cases[0][1].geometry.face_width if self.rated and self.rating.cases else None

    @property
    def face_width_needed(self) -> float | None:
        """The face width at which the spectrum reaches the minimum safety factors (mm)."""
        fw = self.rating.spectrum_face_width if self.rated else None
        return None if fw is None else fw.required


@dataclass(frozen=True)
class DriveRating:
    """The load capacity of every mesh of a drive (see the module docstring). ``reason``: why the
    drive is not rated at all (None when it is); ``duty_stated``: the file has a [duty] or
    [materials] section (else every number rests on the defaults of :mod:`geargen.design.duty`)."""

    design: str
    kind: str
    drive_type: str | None
    length_unit: str
    duty: DutySpec | None
    minimum_safety: tuple[float, float]
    meshes: tuple[RatedMesh, ...] = ()
    preload: float | None = None  # N·mm at the output
    reason: str | None = None
    warnings: tuple[str, ...] = ()
    duty_stated: bool = False
    # when a mesh fails: ({gear table: (material, quality, hardness HV or None)}, ground flanks) with
    # which every mesh passes, checked (:func:`_drive_fix`); None when no material of FIX_MATERIALS does
    fix: tuple[dict, bool] | None = None

    @property
    def rated(self) -> bool:
        return self.reason is None

    @property
    def failures(self) -> tuple[str, ...]:
        return tuple(f for m in self.meshes for f in m.failures)

    @property
    def ok(self) -> bool:
        return not self.failures

    @property
    def compliant_path(self) -> tuple[RatedMesh, ...]:
        """The meshes of a type 1's compliant path (path 2), rated."""
        if self.drive_type != "type1":
            return ()
        return tuple(m for m in self.meshes if m.loads.role == "path 2" and m.rated)

    # ------------------------------------------------------------------ JSON
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: per mesh the contract's ``load_capacity`` block per load case, with the load
        it was rated at and its source; per flank the governing S_H, S_F; non-finite numbers None."""
        out: dict[str, Any] = {"standard": f"{STANDARD}; spectrum by {SPECTRUM}", "rated": self.rated,
                               "reason": self.reason, "ok": self.ok, "failures": list(self.failures),
                               "warnings": list(self.warnings), "S_Hmin": self.minimum_safety[0],
                               "S_Fmin": self.minimum_safety[1], "duty_stated": self.duty_stated,
                               "drive_type": self.drive_type, "kind": self.kind,
                               "preload_Nm": None if self.preload is None else self.preload / 1e3}
        if self.duty is not None:
            d = self.duty
            out["duty"] = {"levels": [{"output_torque_Nm": t / 1e3, "share": s} for t, s in d.levels],
                           "direction": d.direction, "levels_source": d.levels_source,
                           "output_speed_rpm": d.output_speed, "life_h": d.life, "K_A": d.application_factor,
                           "nu_40": d.viscosity, "R_a_um": d.roughness * 1e3, "accuracy_grade": d.accuracy_grade,
                           "K_Hbeta_given": d.face_load_factor, "C_a_um": d.tip_relief * 1e3,
                           "defaulted": list(d.defaulted)}
        out["fix"] = None if self.fix is None else {
            "materials": {g: {"material": n, "quality": q, "hardness_HV": h} for g, (n, q, h) in self.fix[0].items()},
            "ground_flanks": self.fix[1], "toml": fix_lines(self.fix)}
        out["meshes"] = [_mesh_dict(m) for m in self.meshes]
        out["gears"] = _weakest_per_gear(self.meshes)
        compliant = self.compliant_path
        out["type1_compliant_path"] = [{"mesh": m.name, "face_width_mm": m.face_width,
                                        "face_width_for_minimum_mm": m.face_width_needed} for m in compliant] or None
        return _finite(out)

    # ------------------------------------------------------------------ text
    def table(self, unit: str | None = None) -> tuple[list[str], list[list[str]]]:
        """(header, rows): one row per rated mesh and flank, S_H and S_F of gear 1/gear 2; forces in N
        (lbf for an inch design), face widths in ``unit`` (default the design's)."""
        unit = unit or self.length_unit
        inch = unit == "in"

        def force(newtons: float | None) -> str:
            return "-" if newtons is None else f"{newtons / LBF if inch else newtons:.4g}"

        def length(mm: float | None) -> str:
            return "none" if mm is None else f"{from_mm(mm, unit):.{4 if inch else 2}f}"

        header = ["mesh", "role", "flank", "preload", "peak F_t", "b", "b needed", "S_H gear 1/2", "S_F gear 1/2"]
        rows = []
        for m in self.meshes:
            if not m.rated:
                continue
            for i, fl in enumerate(m.flanks):
                first = i == 0
                rows.append([m.name if first else "", m.loads.role if first else "", fl.flank,
                             force(m.loads.preload) if first else "", force(fl.peak_load),
                             length(m.face_width) if first else "", length(m.face_width_needed) if first else "",
                             _pair(fl.S_H), _pair(fl.S_F)])
        return header, rows

    def _torque(self) -> tuple[str, float]:
        """(text, N·mm per unit) of the torque unit the file wrote its loads in."""
        torque_unit = self.duty.torque_unit if self.duty is not None else "Nm"
        return _TORQUE_TEXT.get(torque_unit, torque_unit), QUANTITY_SUFFIXES["torque"].get(torque_unit, 1e3)

    def preamble(self) -> list[str]:
        """What the meshes are rated for: the duty, the preload, the minimum safety factors, the materials."""
        if not self.rated:
            return [f"not rated: {self.reason}"]
        t_text, t_scale = self._torque()
        d = self.duty
        levels = ", ".join(f"{t / t_scale:.4g}" for t, _ in d.levels)
        shares = ", ".join(f"{s:.3g}" for _, s in d.levels)
        way = "each level both ways, half its share each" if d.direction == "both" else "signed levels"
        out = [f"duty: {levels} {t_text} at the output ({way}; shares {shares}), from {d.levels_source}; "
               f"output {d.output_speed:g} rpm, life {d.life:g} h, K_A {d.application_factor:g}, nu_40 "
               f"{d.viscosity:g} mm^2/s, R_a {d.roughness * 1e3:g} um"
               + ("" if d.face_load_factor is None else f", K_Hbeta {d.face_load_factor:g} given")]
        if not self.duty_stated:
            out.append("the file states no [duty] or [materials]: rated for geargen's defaults (docs/design-files.md "
                       "says why each)")
        elif d.defaulted:
            out.append("[duty] keys at their defaults (docs/design-files.md says why): " + ", ".join(d.defaulted))
        if self.preload is not None:
            out.append(f"loop preload {self.preload / t_scale:.4g} {t_text} at the output (each path at zero drive "
                       "torque)")
        out.append(f"minimum safety factors ([checks]): S_H {self.minimum_safety[0]:g}, S_F {self.minimum_safety[1]:g}")
        by_material: dict[str, list[str]] = {}
        for m in self.meshes:
            for gear, mat in zip((m.loads.gear1, m.loads.gear2), m.materials or ()):
                text = f"{mat.name} {mat.quality}" + ("" if mat.hardness is None else f" {mat.hardness:g} HV") \
                       + f" ({mat.source})"
                names = by_material.setdefault(text, [])
                if gear.name not in names:
                    names.append(gear.name)
        out += [f"materials: {', '.join(names)}: {text}" for text, names in by_material.items()]
        return out

    def remarks(self, unit: str | None = None) -> list[str]:
        """Below the table: the meshes not rated and why, the type 1 compliant path's face width, the
        warnings, what is below the minimum and the fix."""
        if not self.rated:
            return []
        unit = unit or self.length_unit
        t_text, t_scale = self._torque()

        def length(mm: float | None) -> str:
            return "none" if mm is None else f"{from_mm(mm, unit):.{4 if unit == 'in' else 2}f}"

        out = []
        for m in self.meshes:
            if not m.rated:
                peak = max((abs(t) for t, _ in self.duty.levels), default=0.0) * m.loads.torque_per_output
                carried = "" if not math.isfinite(peak) else f"; at the peak it carries {peak / t_scale:.4g} {t_text} " \
                                                               "at its first gear"
                out.append(f"{m.name}: {m.scope}{carried}")
        for m in self.compliant_path:
            stiff = [s for s in self.meshes if s.loads.role == "path 1" and s.rated]
            also = "; the stiff path: " + ", ".join(f"{s.name} {length(s.face_width_needed)} {unit} (has "
                                                     f"{length(s.face_width)})" for s in stiff) if stiff else ""
            out.append(f"type 1, compliant path {m.name}: {length(m.face_width_needed)} {unit} of face reaches S_Hmin "
                       f"and S_Fmin (has {length(m.face_width)} {unit}){also}")
        out += [f"warning: {w}" for w in self.warnings]
        out += [("FAILED: " if self.duty_stated else "below the minimum (a check once the file states [duty] or "
                 "[materials]): ") + f for f in self.failures]
        if self.failures:
            out.append("fix (every mesh rated again with it passes): " + fix_text(self.fix) if self.fix is not None
                       else "no ISO 6336-5 material meets the minimum at these loads: a wider face (b needed above) "
                            "or a lighter [duty]")
        return out

    def lines(self, unit: str | None = None) -> list[str]:
        """The text a reader sees (``geargen check``): lengths in ``unit`` (default the design's), torques
        in the unit the file wrote its loads in, forces in N (lbf for an inch design)."""
        unit = unit or self.length_unit
        out = ["", f"Load capacity of every mesh: {STANDARD}; spectrum by {SPECTRUM}"] + \
            [f"  {t}" for t in self.preamble()]
        if not self.rated:
            return out
        header, rows = self.table(unit)
        out.append(f"(forces {'lbf' if unit == 'in' else 'N'}, face widths {unit}; b needed: the face width at which "
                   "the spectrum reaches the minimum safety factors)")
        if rows:
            widths = [max(len(h), *(len(r[i]) for r in rows)) + 2 for i, h in enumerate(header)]
            for row in [header] + rows:
                out.append("".join(f"{c:<{w}}" if i < 2 else f"{c:>{w}}" for i, (c, w) in enumerate(zip(row, widths))))
        return out + self.remarks(unit)


def _pair(values) -> str:
    return "/".join("inf" if math.isinf(v) else f"{v:#.3g}" for v in values)


def _finite(value):
    """``value`` with every non-finite float None (JSON has none), tuples as lists."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def _width_dict(fw) -> dict | None:
    if fw is None:
        return None
    return {"pitting": fw.pitting, "bending": fw.bending, "required": fw.required, "message": fw.message}


def _mesh_dict(m: RatedMesh) -> dict[str, Any]:
    ml = m.loads
    out = {"name": m.name, "role": ml.role, "part1": ml.part1, "part2": ml.part2,
           "gear1": getattr(ml.gear1, "name", None), "gear2": getattr(ml.gear2, "name", None),
           "rated": m.rated, "scope": m.scope, "ok": m.ok, "failures": list(m.failures),
           "speed_over_output": ml.speed, "torque_per_output_torque": ml.torque_per_output}
    if not m.rated:
        return out
    out.update({"n_1_rpm": m.speed, "centre_distance_mm": ml.centre_distance, "face_width_mm": m.face_width,
                "accuracy_grade": m.accuracy_grade, "working_flank": ml.working_flank, "preload_N": ml.preload,
                "load_cycles_per_turn": list(ml.load_cycles_per_turn), "reversed_bending": list(ml.reversed_bending),
                "materials": [{"name": g.name, "quality": g.quality, "hardness_HV": g.hardness, "source": g.source}
                              for g in m.materials],
                "flanks": [{"flank": f.flank, "S_H": list(f.S_H), "S_F": list(f.S_F), "basis": f.basis,
                            "D_H": None if f.D_H is None else list(f.D_H),
                            "D_F": None if f.D_F is None else list(f.D_F), "peak_F_t_N": f.peak_load}
                           for f in m.flanks],
                "face_width_for_minimum_mm": _width_dict(m.rating.spectrum_face_width),
                "cases": [{"flank": load.flank, "source": load.source, "level": load.level,
                           "output_torque_Nm": load.output_torque / 1e3, "path_torque_Nm": load.path_torque / 1e3,
                           "share": load.share, "F_t_N": load.tangential_load,
                           "face_width_for_minimum_mm": _width_dict(width), "load_capacity": rating.to_dict()}
                          for load, (_, rating), width in zip(ml.loads, m.rating.cases, m.rating.face_widths)]})
    return out


def _weakest_per_gear(meshes) -> dict[str, Any]:
    """Per gear (part) its smallest S_H and S_F over its meshes and flanks, and where."""
    out: dict[str, Any] = {}
    for m in meshes:
        for f in m.flanks:
            for i, part in enumerate((m.loads.part1, m.loads.part2)):
                entry = out.setdefault(part, {"S_H": math.inf, "S_H_at": None, "S_F": math.inf, "S_F_at": None})
                for key, values in (("S_H", f.S_H), ("S_F", f.S_F)):
                    if values[i] < entry[key]:
                        entry[key], entry[f"{key}_at"] = values[i], f"{m.name} flank {f.flank}"
    return out


# ---------------------------------------------------------------------------------------------

def rate_drive(layout, summary=None) -> DriveRating:
    """The load capacity of every mesh of the resolved drive ``layout``
    (:func:`geargen.drives.resolver.resolve`), with its stiffness ``summary``
    (:func:`geargen.model.analysis.stiffness`'s first value; computed when None). A drive without
    ``[stiffness]`` and ``[preload]`` is returned not rated, saying why."""
    identity, resolved = layout.identity, layout.resolved
    checks = resolved.checks
    minimum = (checks.min_S_H, checks.min_S_F)
    base = dict(design=identity.name, kind=layout.kind, drive_type=identity.drive_type,
                length_unit=identity.length_unit, minimum_safety=minimum,
                duty_stated=resolved.has("duty") or resolved.has("materials"))
    if summary is None:
        from geargen.model.analysis import drive_stiffness
        summary = drive_stiffness(layout)[0]
    if summary is None:
        return DriveRating(duty=None, reason="the drive has no [stiffness] and [preload] sections: the loads of its "
                           "preloaded meshes come from the stiffness model", **base)
    duty = resolved.duty
    if not duty.levels:
        return DriveRating(duty=duty, reason="no load: give [duty] output_torque_levels_* or [preload] "
                           "max_output_torque_*", **base)
    materials = resolved.materials
    warnings = []
    peak = max(abs(t) for t, _ in duty.levels)
    if peak > summary.max_output_torque * (1 + 1e-9):
        warnings.append(f"a [duty] level ({peak / 1e3:.4g} N·m) is above [preload] max_output_torque "
                        f"({summary.max_output_torque / 1e3:.4g} N·m), for which the preload was chosen")
    rated = tuple(_rate(ml, duty, materials, minimum) for ml in mesh_loads(layout, summary, duty))
    one_piece = {tuple(gear.name for gear in g.gears) for g in layout.gears if len(g.gears) > 1}
    fix = None if all(m.ok for m in rated) else _drive_fix(rated, duty, materials, minimum, one_piece)
    return DriveRating(fix=fix, duty=duty, meshes=rated, preload=summary.drive.preload, warnings=tuple(warnings), **base)


def _rate(ml: MeshLoads, duty: DutySpec, materials: dict[str, GearMaterial], minimum) -> RatedMesh:
    """Rate one mesh over its loads; a mesh ISO 6336 does not rate comes back with its reason."""
    if ml.scope is not None:
        return RatedMesh(ml, scope=ml.scope)
    if not ml.loads:
        return RatedMesh(ml, scope="not rated: no level of the duty loads it")
    mats = (materials[ml.gear1.name], materials[ml.gear2.name])
    grade = max(g.accuracy_grade or duty.accuracy_grade for g in (ml.gear1, ml.gear2))
    speed = duty.output_speed * ml.speed
    drive_flank = ml.working_flank or next((l.flank for l in ml.loads if l.output_torque > 0), ml.loads[0].flank)
    # phase 1 names a mesh's two flanks "drive" and "coast": here the working (or positive) flank is "drive"
    cases = [LoadCase(l.tangential_load, f"{l.source}" + ("" if l.level is None else f", duty level {l.level}"),
                      "drive" if l.flank == drive_flank else "coast", l.share) for l in ml.loads]
    try:
        conditions = RatingConditions(
            speed=speed, life=duty.life, accuracy_grade=grade, roughness=duty.roughness * 1e3,
            viscosity=duty.viscosity, application_factor=duty.application_factor,
            face_load_factor=duty.face_load_factor, tip_relief=duty.tip_relief * 1e3, minimum_safety=minimum,
            load_cycles_per_turn=ml.load_cycles_per_turn)
        rating = rate_mesh(ml.gear1, ml.gear2, ml.centre_distance, cases, conditions,
                           tuple(Material(m.name, m.quality, m.hardness) for m in mats),
                           reversed_bending=ml.reversed_bending)
    except DesignError as exc:
        return RatedMesh(ml, materials=mats, accuracy_grade=grade, speed=speed,
                         scope=f"not rated: ISO 6336 cannot rate it as given: {exc}")
    flanks, failures = [], []
    for flank in dict.fromkeys(l.flank for l in ml.loads):
        phase1 = "drive" if flank == drive_flank else "coast"
        spectrum = next((s for s in rating.spectra if s.flank == phase1), None)
        on_flank = [(load, r) for load, (_, r) in zip(ml.loads, rating.cases) if load.flank == flank]
        peak = max(load.tangential_load for load, _ in on_flank)
        if spectrum is not None:
            s_h, s_f = spectrum.safety("pitting"), spectrum.safety("bending")
            fr = FlankRating(flank, s_h, s_f, f"spectrum, {SPECTRUM}", spectrum.pitting, spectrum.bending, peak)
        else:  # no level loads this flank: its preload alone, as if for the whole life
            r = on_flank[0][1]
            fr = FlankRating(flank, tuple(r.S_H), tuple(r.S_F), f"{on_flank[0][0].source} alone, the whole life",
                             None, None, peak)
        flanks.append(fr)
        for i, gear in enumerate((ml.part1, ml.part2)):
            for what, values, least in (("S_H", fr.S_H, minimum[0]), ("S_F", fr.S_F, minimum[1])):
                if values[i] < least:
                    failures.append(f"{ml.name}: {what} {values[i]:.3g} of {gear} (flank {flank} of {ml.part1}) is "
                                    f"below {least:g}")
    return RatedMesh(ml, rating, mats, grade, speed, conditions, tuple(flanks), tuple(failures))


def _mesh_fix(rated: RatedMesh, duty: DutySpec, materials: dict[str, GearMaterial], minimum):
    """``({gear table: (material, quality, hardness)}, ground)``: the first of :data:`FIX_MATERIALS`
    (on the mesh's failing gears; with :data:`GROUND_FINISH` when the material alone is not enough)
    with which the mesh rated again meets the minimum; None when none does."""
    from dataclasses import replace

    from geargen.design.iso6336_5 import hardness_needed, hardness_range
    ml = rated.loads
    failing = [gear.name for i, gear in enumerate((ml.gear1, ml.gear2))
               if any(f.S_H[i] < minimum[0] or f.S_F[i] < minimum[1] for f in rated.flanks)]
    for finish in (False, True):
        for name, quality in FIX_MATERIALS:
            hardness = hardness_range(name, quality)[1] if hardness_needed(name, quality) else None
            trial = dict(materials)
            for gear in failing:
                trial[gear] = GearMaterial(name, quality, hardness, "fix")
            tried = _rate(ml, replace(duty, **GROUND_FINISH) if finish else duty, trial, minimum)
            if tried.rated and tried.ok:
                return {gear: (name, quality, hardness) for gear in failing}, finish
    return None


def _drive_fix(meshes, duty: DutySpec, materials: dict[str, GearMaterial], minimum,
               one_piece=()) -> tuple[dict, bool] | None:
    """The fix of every failing mesh together (each gear the strongest any of its meshes needs, the
    gear tables of one piece, ``one_piece``, one material), checked by rating every mesh again with
    it; None when a mesh has no fix or the whole does not pass."""
    from dataclasses import replace
    choice: dict[str, tuple] = {}
    ground = False
    rank = {m: i for i, m in enumerate(FIX_MATERIALS)}
    for m in meshes:
        if m.ok or not m.rated:
            continue
        found = _mesh_fix(m, duty, materials, minimum)
        if found is None:
            return None
        for gear, pick in found[0].items():
            if gear not in choice or rank[pick[:2]] > rank[choice[gear][:2]]:
                choice[gear] = pick
        ground |= found[1]
    for piece in one_piece:
        picks = [choice[g] for g in piece if g in choice]
        if picks:
            strongest = max(picks, key=lambda pick: rank[pick[:2]])
            choice.update({g: strongest for g in piece})
    trial = dict(materials)
    trial.update({g: GearMaterial(*pick, "fix") for g, pick in choice.items()})
    trial_duty = replace(duty, **GROUND_FINISH) if ground else duty
    if all(_rate(m.loads, trial_duty, trial, minimum).ok for m in meshes if m.rated):
        return choice, ground
    return None


def fix_tables(fix: tuple[dict, bool]) -> dict[str, dict]:
    """A drive fix (:func:`_drive_fix`) as the design file's tables: ``{"materials": {gear: keys},
    "duty": keys}`` (``duty`` only with ground flanks)."""
    choice, ground = fix
    out: dict[str, dict] = {"materials": {}}
    for gear, (name, quality, hardness) in choice.items():
        out["materials"][gear] = {"material": name, "quality": quality}
        if hardness is not None:
            out["materials"][gear]["hardness_HV"] = hardness
    if ground:
        out["duty"] = {"accuracy_grade": GROUND_FINISH["accuracy_grade"],
                       "roughness_Ra_um": round(GROUND_FINISH["roughness"] * 1e3, 12)}
    return out


def _toml_value(v) -> str:
    return f'"{v}"' if isinstance(v, str) else f"{v:g}"


def fix_text(fix: tuple[dict, bool]) -> str:
    """A drive fix on one line: each table's keys after its name."""
    tables = fix_tables(fix)
    named = [(f"materials.{gear}", keys) for gear, keys in tables["materials"].items()]
    named += [("duty", tables["duty"])] if "duty" in tables else []
    return "; ".join(f"[{name}] " + ", ".join(f"{k} = {_toml_value(v)}" for k, v in keys.items())
                     for name, keys in named)


def fix_lines(fix: tuple[dict, bool]) -> list[str]:
    """A drive fix as the TOML a designer pastes into the file (a [duty] table merged with the file's own)."""
    tables = fix_tables(fix)
    named = [(f"materials.{gear}", keys) for gear, keys in tables["materials"].items()]
    named += [("duty", tables["duty"])] if "duty" in tables else []
    out = []
    for name, keys in named:
        out += [f"[{name}]"] + [f"{k} = {_toml_value(v)}" for k, v in keys.items()]
    return out


__all__ = ["SPECTRUM", "FIX_MATERIALS", "GROUND_FINISH", "fix_tables", "fix_text", "fix_lines", "FlankRating", "RatedMesh", "DriveRating", "rate_drive"]
