"""``geargen fit ... --update-design OUT.toml``: the design again, with what the bench measured.

A copy of the design file named by the sidecar's ``assembly``, in the file's own units and with
its comments, where

- a gear measured on its own (the output's and the input's once-per-revolution order) gets the
  measured eccentricity TIR: the bearing eccentricity as designed (it cannot be told from the
  pitch-line one: both turn once per revolution), the pitch-line eccentricity the rest;
- gears that share an order (both clusters' large and small gears; the two gears of a mesh for
  the tooth-to-tooth term) are scaled together by measured / budgeted amplitude, where the
  measurement exceeds the budget (inside it, it only bounds them from below: left as designed);
- the effects the fit added, and the ambiguous ones, are recorded as a comment at the top (the
  design-file format has no key for them).

The preload variation the design predicts (its headline loop-error band) is computed for the
design as it was and as updated, so the report shows what the measured errors do to the preload.
"""

from __future__ import annotations

import re
from pathlib import Path

from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

ECCENTRICITY_KEYS = ("bearing_eccentricity_tir", "pitch_line_eccentricity_tir")
FLAG = "--update-design"


def _section(lines: list[str], role: str) -> tuple[int, int]:
    """(first, end) line indices of the ``[errors.ROLE]`` table's body."""
    header = re.compile(rf"^\s*\[\s*errors\.{role}\s*\]")
    start = next((i for i, line in enumerate(lines) if header.match(line)), None)
    if start is None:
        raise DesignError(f"errors.{role}", f"{FLAG} rewrites [errors.{role}] tables; this design gives the budget "
                          "another way", f"an [errors.{role}] table")
    end = next((i for i in range(start + 1, len(lines)) if re.match(r"^\s*\[", lines[i])), len(lines))
    return start + 1, end


def _key_line(lines: list[str], span: tuple[int, int], key: str, role: str) -> tuple[int, str, float]:
    """(line index, unit suffix, value in mm) of ``key_UNIT = value`` in the table."""
    pattern = re.compile(rf"^\s*{key}_(\w+)\s*=\s*([^#\n]+?)\s*(#.*)?$")
    for i in range(*span):
        m = pattern.match(lines[i])
        if m and m.group(1) in LENGTH_SUFFIXES:
            return i, m.group(1), float(m.group(2)) * LENGTH_SUFFIXES[m.group(1)]
    raise DesignError(f"errors.{role}.{key}", "missing", f"{key}_<unit> = value in [errors.{role}]")


def _set(lines: list[str], span, key: str, role: str, value_mm: float, why: str) -> float:
    """Write ``key`` = ``value_mm`` (in the line's own unit, ``why`` as its comment); its old value, mm."""
    i, unit, old = _key_line(lines, span, key, role)
    lines[i] = f"{key}_{unit} = {value_mm / LENGTH_SUFFIXES[unit]:.6g}  # {why}"
    return old


def updated_design(design_path: Path, report: dict, source: str) -> tuple[str, list[dict]]:
    """The updated design's text and the changes made (each ``{"key", "old_mm", "new_mm", "why"}``)."""
    budget = report.get("budget") or {}
    rows = budget.get("terms") or []
    if not rows:
        raise DesignError(FLAG, f"nothing to update: {budget.get('summary') or 'the sidecar names no assembly'}",
                          "a preload trace whose sidecar names assembly = a design with an [errors] budget")
    lines = Path(design_path).read_text().splitlines()
    changes: list[dict] = []

    def record(role, key, old, new, why):
        if abs(new - old) > 1e-12:
            changes.append({"key": f"errors.{role}.{key}", "old_mm": old, "new_mm": new, "why": why})

    for row in rows:
        why = f"measured by geargen fit {source}"
        if row["term"] == "eccentricity" and len(row["gears"]) == 1:
            (role,) = row["gears"]
            span = _section(lines, role)
            measured = row["measured_tir_um"] * 1e-3
            bearing = min(_key_line(lines, span, "bearing_eccentricity_tir", role)[2], measured)
            old = _set(lines, span, "bearing_eccentricity_tir", role, bearing,
                       f"{why} (with the pitch-line one: {measured * 1e3:.4g} um in all)")
            record(role, "bearing_eccentricity_tir", old, bearing, why)
            old = _set(lines, span, "pitch_line_eccentricity_tir", role, measured - bearing,
                       f"{why}: total eccentricity {measured * 1e3:.4g} um, the bearing's as designed")
            record(role, "pitch_line_eccentricity_tir", old, measured - bearing, why)
        elif row["verdict"] == "exceeds":
            scale = row["amplitude_um"] / row["budget_amplitude_um"]
            keys = ECCENTRICITY_KEYS if row["term"] == "eccentricity" else ("tooth_to_tooth_tir",)
            for role in row["gears"]:
                span = _section(lines, role)
                for key in keys:
                    value = _key_line(lines, span, key, role)[2]
                    text = (f"{why}: x {scale:.3g}, the measured over the budgeted amplitude at order "
                            f"{row['order']:.4g} (shared by {', '.join(row['gears'])})")
                    old = _set(lines, span, key, role, value * scale, text)
                    record(role, key, old, value * scale, text)
    found = [f"#   {e['effect']}: " + ", ".join(f"{k} = {v:.5g}" if isinstance(v, float) else f"{k} = {v}"
                                                 for k, v in e.items() if k in ("order", "amplitude", "phase_deg",
                                                                                 "per_kelvin", "per_second",
                                                                                 "half_width", "exponent",
                                                                                 "width_urad"))
             for e in report.get("effects_added", [])]
    found += [f"#   ambiguous: {' or '.join(a['candidates'])}" for a in report.get("ambiguous", [])]
    head = [f"# Updated by geargen fit {source}: the measured errors replace the budgeted ones where the",
            "# bench measured them (the changed lines say so). Effects the fit found beyond the declared model:",
            *(found or ["#   none"]), ""]
    return "\n".join(head + lines) + "\n", changes


def design_from_text(text: str, path: Path):
    """The design ``text`` as if it were the file ``path`` (nothing written)."""
    import hashlib
    import tomllib

    from geargen.design.assembly import design_from_dict
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:  # pragma: no cover - the text is the user's file with numbers changed
        raise DesignError(FLAG, f"the updated design does not parse: {exc}") from None
    return design_from_dict(data, path=Path(path).resolve(), sha256=hashlib.sha256(text.encode()).hexdigest(),
                            validate=True)


def preload_band(design) -> dict | None:
    """The design's headline preload variation (N·m): its loop-error band, or None without one."""
    from geargen.model.analysis import stiffness
    from geargen.drives import resolve
    summary, _ = stiffness(design, resolve(design))
    if summary is None or summary.headline is None:
        return None
    h = summary.headline
    return {"label": h.label, "low_Nm": h.low * 1e-3, "high_Nm": h.high * 1e-3, "range_Nm": h.range * 1e-3,
            "unloads": bool(h.unloads)}


__all__ = ["updated_design", "design_from_text", "preload_band"]
