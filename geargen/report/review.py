"""The design-review report of a build: ``report.md`` and ``report.html``, each figure beside
them as its own PNG and SVG file (``figures/<name>.png|svg``), linked by relative paths.

The report is a list of blocks (heading, paragraph, list, table, preformatted text, figure)
written once and rendered twice, to Markdown and to an HTML page. It opens with the key numbers
(:func:`key_numbers`, also recorded in the manifest): read from the same stiffness summary and
check results as the rest of the report, never recomputed. It takes plain data
(:class:`Review`), put together by the pipeline; this module imports neither the CAD kernel nor
the checker. Files are written plainly: the build writes into a temporary folder that replaces
the export folder at the end.
"""

from __future__ import annotations

import html
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from geargen.units import TextUnits, diametral_pitch_from_module


#: the model frame of a drive whose kind says nothing else (geargen.drives.kind.DriveKind.frame)
FRAME = "the output gear's centre at the origin, +x along the symmetry line towards the input"

@dataclass
class Review:
    """What the report shows. ``blocks`` are ``(kind, payload)``: ``("h2", text)``, ``("h3", text)``,
    ``("p", text)``, ``("list", [text])``, ``("table", (header, rows))``, ``("pre", text)``,
    ``("figure", (caption, relative file name))``."""

    title: str
    status: str  # "PASS" or "FAILING"
    blocks: list[tuple[str, Any]] = field(default_factory=list)

    def h(self, text: str) -> "Review":
        self.blocks.append(("h2", text))
        return self

    def h3(self, text: str) -> "Review":
        self.blocks.append(("h3", text))
        return self

    def p(self, text: str) -> "Review":
        self.blocks.append(("p", text))
        return self

    def items(self, items: list[str]) -> "Review":
        self.blocks.append(("list", list(items)))
        return self

    def table(self, header: list[str], rows: list[list[Any]]) -> "Review":
        self.blocks.append(("table", (list(header), [list(r) for r in rows])))
        return self

    def pre(self, text: str) -> "Review":
        self.blocks.append(("pre", text))
        return self

    def figure(self, caption: str, file_name: str) -> "Review":
        """A figure kept as its own file beside the page (linked, not embedded)."""
        self.blocks.append(("figure", (caption, file_name)))
        return self


def from_markdown(text: str, status: str) -> Review:
    """A :class:`Review` from Markdown of the subset the reports write: ``#``/``##``/``###``
    headings, pipe tables, ``- `` lists, fenced blocks, ``![caption](file)`` figures (linked
    files) and paragraphs (inline ``**``, ``*`` and backticks dropped)."""
    lines = text.splitlines()
    title = lines[0][2:].strip() if lines and lines[0].startswith("# ") else "report"
    review = Review(title=title, status=status)

    def plain(t: str) -> str:
        return t.replace("**", "").replace("`", "").strip("*").replace("\\|", "|")
    i = 1 if lines and lines[0].startswith("# ") else 0
    while i < len(lines):
        line = lines[i]
        if not line.strip():
            i += 1
        elif line.startswith("#"):
            review.h(plain(line.lstrip("#").strip()))
            i += 1
        elif line.startswith("```"):
            j = next((k for k in range(i + 1, len(lines)) if lines[k].startswith("```")), len(lines))
            review.pre("\n".join(lines[i + 1:j]))
            i = j + 1
        elif line.startswith("|") and i + 1 < len(lines) and lines[i + 1].startswith("|--"):
            def cells(row):
                parts, cell, k = [], "", 1
                while k < len(row.rstrip()) - 1:
                    if row[k] == "\\" and row[k + 1] == "|":
                        cell, k = cell + "|", k + 2
                        continue
                    if row[k] == "|":
                        parts.append(plain(cell.strip()))
                        cell = ""
                    else:
                        cell += row[k]
                    k += 1
                return parts + [plain(cell.strip())]
            j = i + 2
            while j < len(lines) and lines[j].startswith("|"):
                j += 1
            review.table(cells(line), [cells(r) for r in lines[i + 2:j]])
            i = j
        elif line.startswith("- "):
            j = i
            while j < len(lines) and lines[j].startswith("- "):
                j += 1
            review.items([plain(x[2:]) for x in lines[i:j]])
            i = j
        elif line.startswith("!["):
            caption, _, rest = line[2:].partition("](")
            review.figure(caption, rest.rstrip(")"))
            i += 1
        else:
            review.p(plain(line))
            i += 1
    return review


def table_cell(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def to_markdown(review: Review) -> str:
    out = [f"# {review.title}", "", f"**Status: {review.status}**", ""]
    for kind, payload in review.blocks:
        if kind == "h2":
            out += [f"## {payload}", ""]
        elif kind == "h3":
            out += [f"### {payload}", ""]
        elif kind == "p":
            out += [payload, ""]
        elif kind == "list":
            out += [f"- {item}" for item in payload] + [""] if payload else ["(none)", ""]
        elif kind == "table":
            header, rows = payload
            out.append("| " + " | ".join(header) + " |")
            out.append("|" + "|".join("---" for _ in header) + "|")
            out += ["| " + " | ".join(table_cell(c).replace("|", "\\|") for c in r) + " |" for r in rows]
            out.append("")
        elif kind == "pre":
            out += ["```", payload.rstrip("\n"), "```", ""]
        elif kind == "figure":
            caption, name = payload
            out += [f"![{caption}]({name})", ""]
    return "\n".join(out)


_CSS = """body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}
table{border-collapse:collapse;margin:0.5em 0 1.2em}td,th{border:1px solid #bbb;padding:3px 7px;font-size:0.9em}
th{background:#eee}pre{background:#f6f6f6;padding:0.6em;overflow-x:auto;font-size:0.82em}
img{max-width:100%}.PASS{color:#1a7f37}.FAILING{color:#c62828}figcaption{font-style:italic;font-size:0.9em}"""


_LINK = re.compile(r"^\[([^\]]+)\]\(([^)\s]+)\)$")


def _html_cell(value: Any) -> str:
    """A table cell as HTML: a cell that is one Markdown link ``[text](href)`` becomes a link."""
    text = table_cell(value)
    link = _LINK.match(text)
    if link:
        return f"<a href='{html.escape(link.group(2))}'>{html.escape(link.group(1))}</a>"
    return html.escape(text)


def to_html(review: Review) -> str:
    e = html.escape
    out = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'>", f"<title>{e(review.title)}</title>",
           f"<style>{_CSS}</style></head><body>", f"<h1>{e(review.title)}</h1>",
           f"<p><strong class='{e(review.status)}'>Status: {e(review.status)}</strong></p>"]
    for kind, payload in review.blocks:
        if kind == "h2":
            out.append(f"<h2>{e(payload)}</h2>")
        elif kind == "h3":
            out.append(f"<h3>{e(payload)}</h3>")
        elif kind == "p":
            out.append(f"<p>{e(payload)}</p>")
        elif kind == "list":
            out.append("<ul>" + "".join(f"<li>{e(i)}</li>" for i in payload) + "</ul>" if payload else "<p>(none)</p>")
        elif kind == "table":
            header, rows = payload
            out.append("<table><tr>" + "".join(f"<th>{e(h)}</th>" for h in header) + "</tr>")
            out += ["<tr>" + "".join(f"<td>{_html_cell(c)}</td>" for c in r) + "</tr>" for r in rows]
            out.append("</table>")
        elif kind == "pre":
            out.append(f"<pre>{e(payload)}</pre>")
        elif kind == "figure":
            caption, name = payload
            out.append(f"<figure><a href='{e(name)}'><img alt='{e(caption)}' src='{e(name)}'></a>"
                       f"<figcaption>{e(caption)}</figcaption></figure>")
    out.append("</body></html>")
    return "\n".join(out)


def write_review(review: Review, folder: str | Path) -> dict[str, Path]:
    """Write ``report.md`` and ``report.html`` into ``folder``."""
    folder = Path(folder)
    md = folder / "report.md"
    page = folder / "report.html"
    from geargen.outputs import write_file
    write_file(md, to_markdown(review))
    write_file(page, to_html(review))
    return {"report_md": md, "report_html": page}


__all__ = ["Review", "to_markdown", "to_html", "write_review", "compose", "key_numbers", "key_numbers_table",
           "write_figures", "figure_link", "FIGURE_FOLDER"]

FIGURE_FOLDER = "figures"


# ---------------------------------------------------------------- the review of a build


def _len(v_mm: float | None, scale: float, digits: int = 5) -> str:
    if v_mm is None:
        return "-"
    return f"{v_mm / scale:.{digits}g}"


def key_numbers(result: Any) -> dict[str, Any]:
    """The numbers a reviewer reads first, for the report's opening block and the manifest:
    the ratio, the drive and loop stiffness, the preload and its variation (the headline budget),
    the minimum backlash of each mesh (worst case over the error budget where the design has one,
    else as built), the warnings and failures counted. Lengths in the design's unit.

    Read from the objects the rest of the report uses: the stiffness summary's own
    :meth:`to_dict` (what ``geargen stiffness --json`` prints), the check results' ``to_dict``
    (what ``geargen check --json`` prints) and the build's warnings."""
    from geargen.units import LENGTH_SUFFIXES

    unit = result.design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    ratio = result.layout.ratio
    out: dict[str, Any] = {"length_unit": unit, "torque_unit": result.design.text_units.torque,
                           "ratio": ratio["text"] if ratio else None,
                           "ratio_ok": ratio["ok"] if ratio else None,
                           "drive_stiffness_Nm_per_rad": None, "drive_stiffness_with_common_Nm_per_rad": None,
                           "loop_stiffness_Nm_per_rad": None, "preload_Nm": None,
                           "preload_variation": None,
                           "warnings": len(result.warnings), "failures": len(result.checks.failures)}
    if result.stiffness is not None:
        st = result.stiffness.to_dict()
        # k_D is the paper's (the two paths); with the common parts (shafts, bearings) is what the servo sees
        out.update(drive_stiffness_Nm_per_rad=st["drive"]["stiffness_Nm_per_rad"],
                   drive_stiffness_with_common_Nm_per_rad=st["drive"]["stiffness_with_common_Nm_per_rad"],
                   loop_stiffness_Nm_per_rad=st["loop"]["stiffness_Nm_per_rad"], preload_Nm=st["preload_Nm"])
        head = next((v for v in st["preload_variation"] if v["label"] == st["headline_budget"]), None)
        if head is not None:
            out["preload_variation"] = {"budget": head["label"], "range_Nm": head["range_Nm"],
                                        "relative": head["relative"]}
    dc = getattr(result.checks, "design_check", None)
    tolerances = {t.mesh: t.to_dict(unit) for t in (dc.tolerances if dc is not None else [])}
    meshes = []
    for m in result.checks.meshes:
        if m.get("status") == "disengaged":
            continue
        t = tolerances.get(m["mesh"])
        meshes.append({"mesh": m["mesh"], "min_backlash": m["backlash_min"] / scale,
                       "worst_case_min_backlash": None if t is None else t["worst_case_min_backlash"]})
    out["meshes"] = meshes
    rating = getattr(dc, "load_capacity", None) if dc is not None else None
    weakest = {}
    if rating is not None and rating.rated:
        for what in ("S_H", "S_F"):
            values = [(v, m.name) for m in rating.meshes for f in m.flanks for v in getattr(f, what)]
            if values:
                weakest[what] = min(values)
    out["load_capacity"] = None if not weakest else {
        "stated_duty": rating.duty_stated, "ok": rating.ok,
        **{f"min_{k}": v for k, (v, _) in weakest.items()}, **{f"min_{k}_mesh": n for k, (_, n) in weakest.items()}}
    return out


def plain_number(value: float | None, digits: int = 5) -> str:
    """One format for the numbers a reviewer reads first: positional (no exponent), at most
    ``digits`` significant digits, whole numbers whole, no trailing zeros (a stiffness of 1305030
    N·m/rad, a backlash of 0.0012345 or 0.00005)."""
    from geargen.report.synthesis import fixed
    if value is None:
        return "-"
    if value == 0 or not math.isfinite(value):
        return f"{value:g}"
    text = fixed(value, max(0, digits - 1 - math.floor(math.log10(abs(value)))))
    return text.rstrip("0").rstrip(".") if "." in text else text


def key_numbers_table(numbers: dict[str, Any]) -> tuple[list[str], list[list[str]]]:
    """:func:`key_numbers` as a two-column table (quantity, value), every number in one format
    (:func:`plain_number`)."""
    unit = numbers["length_unit"]
    units = TextUnits(length=unit, torque=numbers.get("torque_unit", "Nm"))  # the numbers' N·m in the file's unit
    tq, ks = units.unit("torque"), units.unit("torsional_stiffness")

    def torque_number(value_nm, digits: int = 5):
        return plain_number(None if value_nm is None else units.value("torque", value_nm * 1e3), digits)

    rows = [["ratio", "-" if numbers["ratio"] is None else
             f"{numbers['ratio']}" + ("" if numbers["ratio_ok"] else " (NOT an allowed ratio)")],
            [f"drive stiffness k_D ({ks})", torque_number(numbers["drive_stiffness_Nm_per_rad"])],
            [f"drive stiffness with common parts ({ks})", torque_number(numbers["drive_stiffness_with_common_Nm_per_rad"])],
            [f"loop stiffness k_L ({ks})", torque_number(numbers["loop_stiffness_Nm_per_rad"])],
            [f"preload ({tq})", torque_number(numbers["preload_Nm"])]]
    g = plain_number
    v = numbers["preload_variation"]
    rows.append([f"preload variation, p-p ({tq})", "-" if v is None else
                 f"{torque_number(v['range_Nm'], 4)} ({100 * v['relative']:.2f} %, {v['budget']} budget)"])
    for m in numbers["meshes"]:
        worst = m["worst_case_min_backlash"]
        rows.append([f"backlash {m['mesh']}, minimum ({unit})",
                     f"{g(m['min_backlash'])} as built" + ("" if worst is None else f"; {g(worst)} worst case")])
    lc = numbers.get("load_capacity")
    if lc is not None:
        basis = "the stated duty" if lc["stated_duty"] else "geargen's default duty and materials"
        for what, name in (("S_H", "pitting"), ("S_F", "bending")):
            if f"min_{what}" in lc:
                rows.append([f"least {what} ({name}, {basis})", f"{lc[f'min_{what}']:.3g} ({lc[f'min_{what}_mesh']})"])
    rows.append(["warnings", str(numbers["warnings"])])
    rows.append(["failures", str(numbers["failures"])])
    return ["quantity", "value"], rows


def _with_vector(caption: str, png: str) -> str:
    """A figure's caption naming its SVG beside the PNG (what a reviewer reuses in a document)."""
    return f"{caption} (vector: {png.removesuffix('.png')}.svg)"


def compose(result: Any, figures: dict[str, str] | None = None, notes: list[str] = ()) -> Review:
    """The review of a build result (``geargen.pipeline.BuildResult``, read by attribute);
    ``figures``: figure key (``"render"``, ``"layout"``, ``"preload_diagram"``) -> the PNG's
    path relative to the report (:func:`write_figures`); ``notes`` on figures not drawn."""
    figures = figures or {}
    from geargen.units import LENGTH_SUFFIXES

    design = result.design
    layout = result.layout
    unit = design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    status = "PASS" if result.ok else "FAILING"
    r = Review(f"{design.name}: design review", status)
    r.h("Key numbers")
    r.table(*key_numbers_table(key_numbers(result)))
    r.p(design.description or design.name)
    frame = layout.drive.frame if layout.drive is not None else FRAME
    r.p(f"Design file {design.path.name if design.path else '-'}, sha256 {design.sha256}. Lengths in {unit} "
        f"unless marked; the model frame has {frame}, +z along the gear axes. Position modelled: {layout.position}.")
    if not result.ok:
        r.h("Failures" + (" (written anyway with --force)" if result.forced else ""))
        r.items(list(result.checks.failures))
    r.h("Warnings")
    r.items(result.warnings)
    if design.defaulted:
        r.h("Default hardware")
        r.p("The design file gives none of these: geargen sized them by its default rules "
            "(geargen/drives/<kind>/defaults.py). Copy a line into the file to change it.")
        r.table(["key", "value", "why"], [[d.key, d.value, d.why] for d in design.defaulted])

    r.h("Assembly")
    if "render" in figures:
        r.figure(_with_vector("Rendered view of the assembly (reference bodies translucent)", figures["render"]),
                 figures["render"])
    if "layout" in figures:
        r.figure(_with_vector("Layout: gear circles, centres, lines of action, symmetry line, carriage travel",
                              figures["layout"]), figures["layout"])
    if layout.ratio:
        ok = "exact and allowed" if layout.ratio["ok"] else "NOT one of the required ratios"
        req = ", ".join(f"{x}:1" for x in layout.ratio["required"]) or "none given"
        r.p(f"Ratio {layout.ratio['what']}: {layout.ratio['text']} ({ok}; required: {req}).")
    for n in list(layout.notes) + list(getattr(result.parts, "notes", [])):
        r.p(n)

    rows = []
    for g in layout.gears:
        for spec in g.gears:
            z0, z1 = g.face_z(spec)
            helix = f"{math.degrees(spec.helix_angle):.4g} {spec.hand}" if spec.is_helical else "spur"
            size = diametral_pitch_from_module(spec.module) if unit == "in" else spec.module
            rows.append([g.name, spec.name, spec.teeth, f"{size:.5g}", f"{math.degrees(spec.pressure_angle):.4g}",
                         helix, _len(spec.face_width, scale), _len(spec.thinning, scale),
                         f"({_len(g.centre[0], scale, 6)}, {_len(g.centre[1], scale, 6)})",
                         f"{_len(z0, scale)} to {_len(z1, scale)}", f"{math.degrees(g.rotation_at(spec, z0)):.5g}"])
    r.h("Gears")
    r.table(["part", "gear", "teeth", "P_n (1/in)" if unit == "in" else "m_n (mm)", "alpha_n (deg)", "helix (deg)", f"face ({unit})",
             f"thinning ({unit}, circ.)", f"centre ({unit})", f"z ({unit})", "tooth 0 at its face (deg)"], rows)

    run = layout.synthesis
    if run is not None:
        from geargen.report.synthesis import appendix_sections
        r.h("Centre synthesis and error budget (Appendix layout)")
        title, tables = appendix_sections(run)
        r.p(title)
        for header, rows in tables:
            r.table(header, rows)

    r.h("Mesh checks")
    from geargen.model import BACKLASH_KIND
    r.p("The verdict of `geargen check` (the same function): path 1 on the exact 2-D outlines at every mesh "
        "position of a tooth cycle, the design ranges, the ratio and the error budget; path 2 on sections of "
        f"the built solids. Backlash: {BACKLASH_KIND}, in {unit}; positive is clearance. The resolved "
        "teeth, centres and phases are in resolved.json.")
    rows = []
    for m in result.checks.meshes:
        if m.get("status") == "disengaged":
            rows.append([m["mesh"], f"{m['gear1']} / {m['gear2']}", "-", f"{_len(m['design_min'], scale)} to "
                         f"{_len(m['design_max'], scale)}", "disengaged", "-", "-", "-",
                         f"axial clearance {_len(m['axial_clearance'], scale)}"])
            continue
        p1 = m["path1"]
        p2 = f"{_len(m['path2_backlash_min'], scale)} to {_len(m['path2_backlash_max'], scale)}" \
            if "path2_backlash_min" in m else "not run"
        rows.append([m["mesh"], f"{m['gear1']} / {m['gear2']}", _len(p1.centre_distance, scale, 7),
                     f"{_len(m['design_min'], scale)} to {_len(m['design_max'], scale)}",
                     f"{_len(m['backlash_min'], scale)} to {_len(m['backlash_max'], scale)}", p2,
                     f"{m['contact_ratio']:.4g}", _len(p1.min_clearance, scale),
                     "ok" if not m["failures"] else "; ".join(m["failures"])])
    r.table(["mesh", "gear 1 / gear 2", f"centre distance ({unit})", "design backlash", "backlash (path 1)",
             "backlash (path 2)", "contact ratio", f"min tip clearance ({unit})", "result"], rows)

    dc = getattr(result.checks, "design_check", None)
    if dc is not None and dc.bevel:
        r.h("Bevel pair")
        r.p("The bevel pair: backlash circumferential at the heel pitch circle, measured on the exact "
            f"spherical-involute outlines on the heel sphere of the placed gears (lengths in {unit}).")
        r.table(["mesh", "gear 1 / gear 2", "design backlash", "measured backlash", "difference", "free play each side",
                 f"min tip clearance ({unit})", "result"],
                [[b["mesh"], f"{b['gear1']} / {b['gear2']}", _len(b["design_backlash"], scale), _len(b["backlash"], scale),
                  f"{(b['backlash'] - b['design_backlash']) / scale:.1e}",
                  f"{_len(b['play_negative'], scale)} / {_len(b['play_positive'], scale)}", _len(b["tip_clearance"], scale),
                  "; ".join(f.message for f in dc.failures if f.mesh == b["mesh"]) or "ok"] for b in dc.bevel])
    if dc is not None and dc.planetary:
        r.h("Planetary stage")
        rings = [b for b in dc.planetary if "gear1" in b]
        r.p("Planet-ring meshes: backlash circumferential at the planet's reference circle, measured on the exact "
            "outlines of the placed planet and ring (the planet turned both ways, the ring held), over one planet "
            "pitch of mesh positions and by the closed form; the result column holds the internal pair's interference "
            f"checks too (involute, tip, trochoid, radial assembly; lengths in {unit}). The sun-planet meshes are in "
            "the mesh table.")
        r.table(["mesh", "gear 1 / gear 2", "design backlash", "measured backlash", "over a planet pitch", "closed form",
                 "free play each side", "contact ratio", "result"],
                [[b["mesh"], f"{b['gear1']} / {b['gear2']}", f"{_len(b['design_min'], scale)} to "
                  f"{_len(b['design_max'], scale)}", _len(b["backlash"], scale),
                  f"{_len(b['sweep_min'], scale)} to {_len(b['sweep_max'], scale)}", _len(b["closed_form_backlash"], scale),
                  f"{_len(b['play_cw'], scale)} / {_len(b['play_ccw'], scale)}", f"{b['contact_ratio']:.4g}",
                  "; ".join(f.message for f in dc.failures if f.mesh == b["mesh"]) or "ok"] for b in rings])
        r.table(["stage", "ratio", f"carrier radius ({unit})", f"coaxiality difference ({unit})",
                 "assembly step error", f"planet tip gap ({unit})", "min tooth difference", "result"],
                [[b["stage"], f"{b['ratio']:.6g}", _len(b["carrier_radius"], scale),
                  f"{b['coaxiality_difference'] / scale:.2e}", f"{b['assembly_step_error']:.1e}",
                  _len(b["neighbour_tip_gap"], scale), str(b["minimum_tooth_difference"]),
                  "; ".join(f.message for f in dc.failures if f.mesh == b["mesh"]) or "ok"]
                 for b in dc.planetary if "gear1" not in b])
    if dc is not None and dc.rack:
        r.h("Rack meshes and preload carriage")
        meshes = [b for b in dc.rack if b["mesh"] != "carriage"]
        r.p("The rack meshes: backlash circumferential along the rack's rolling line, measured on the exact "
            f"outlines of the pinions as placed over the rack (lengths in {unit}).")
        r.table(["mesh", "design backlash", "measured backlash", "working flank gap", f"min tip clearance ({unit})",
                 "contact ratio", "result"],
                [[b["mesh"], f"{_len(b['design_min'], scale)} to {_len(b['design_max'], scale)}",
                  f"{_len(b['backlash_min'], scale)} to {_len(b['backlash_max'], scale)}",
                  _len(b["working_flank_gap"], scale), _len(b["tip_clearance"], scale), f"{b['contact_ratio']:.4g}",
                  "; ".join(f.message for f in dc.failures if f.mesh == b["mesh"]) or "ok"] for b in meshes])
        c = next((b for b in dc.rack if b["mesh"] == "carriage"), None)
        if c is not None:
            k = c["stiffness"]
            r.p(f"Preload carriage (Type 2, radial motion, Fig. 9): the loop closes with the input's centre at y = "
                f"{_len(c['carriage_y'], scale)} {unit}; the carriage needs {_len(c['carriage_needed'], scale)} of "
                f"its {_len(c['carriage_travel'], scale)} {unit} stroke ({c['sensitivity']:.4g} {unit} per {unit} of "
                f"loop error at the rack). Spring {c['spring_force']:.4g} N: {c['mesh_force_at_rest']:.4g} N in "
                f"each input mesh at rest, a path unloads at {c['unloading_rack_force']:.4g} N on the rack. "
                f"Stiffness at the rack: paths {k['k1']:.4g} and {k['k2']:.4g} N/mm, carriage spring k3 "
                f"{k['k3']:.4g} N/mm, drive (Eq. 5) {k['drive']:.4g} N/mm, loop (Eq. 6) {k['loop']:.4g} N/mm.")
    rating = getattr(dc, "load_capacity", None) if dc is not None else None
    if rating is not None:
        r.h("Load capacity")
        r.p("Every mesh rated by ISO 6336-2:2019 (pitting) and ISO 6336-3:2019 (tooth-root bending), method B, for "
            "the preload it carries all its life and its share of the duty (Eqs. 2-6), the spectrum summed by "
            "ISO 6336-6; S_H and S_F of gear 1 / gear 2 per flank. manifest.json holds every factor by its name "
            "in the standard.")
        r.items(rating.preamble())
        header, rows = rating.table(unit)
        if rows:
            r.table(header, rows)
        r.items(rating.remarks(unit))
    if dc is not None and dc.tolerances:
        r.h("Backlash across the error budget")
        from geargen.design.checks import checks_settings
        checks = checks_settings(result.design)
        mc = result.design.section("monte_carlo")
        r.p("Minimum backlash of each mesh with every error of the [errors.*] budget: the worst case and the "
            f"minimum of the backlash Monte Carlo, {checks.monte_carlo_samples} builds per mesh ([checks] "
            f"monte_carlo_samples) (lengths in {unit})."
            + (f" The design's [monte_carlo] samples = {mc['samples']} is another Monte Carlo, the centre "
               "synthesis's carriage travel (geargen synth), not this one." if mc.get("samples") is not None else ""))
        r.table(["mesh", "meant for", "nominal", "worst case", "backlash Monte Carlo min",
                 "builds ([checks] monte_carlo_samples)", "result"],
                [[t.mesh, t.meant_for, _len(t.nominal_min_backlash, scale), _len(t.worst_case_min_backlash, scale),
                  _len(t.monte_carlo_minimum, scale) if t.samples else "-", t.samples,
                  "ok" if t.ok else "; ".join(f.message for f in t.failures)] for t in dc.tolerances])
        r.items(list(dict.fromkeys(n for t in dc.tolerances for n in t.notes)))

    ov = result.checks.overlaps
    if ov is not None:
        r.h("Part overlaps")
        r.p(f"{ov.parts} parts; {ov.pairs_checked} pairs whose bounding boxes meet were intersected "
            f"(tolerance {ov.tolerance / scale ** 3:.4g} {unit}^3); "
            f"{len(ov.intended)} intended contacts; "
            f"{len(ov.delegated)} meshing pairs left to the mesh checker. Unintended overlaps: "
            f"{len(ov.unintended) or 'none'}.")
        r.items([f"{o.part1} / {o.part2}: {o.volume / scale ** 3:.4g} {unit}^3"
                 for o in ov.unintended])
        r.table(["part", "part", "intended contact"], [[a, b, why] for a, b, why in ov.intended])

    s = result.stiffness
    if s is not None:
        from geargen.report.stiffness import summary_tables
        r.h("Stiffness and preload")
        for title, header, rows in summary_tables(s):
            r.h3(title)
            if header:
                r.table(header, rows)
            else:
                r.items([row[0] for row in rows])
        if "preload_diagram" in figures:
            r.figure(_with_vector("Preload diagram (Fig. 6)", figures["preload_diagram"]), figures["preload_diagram"])
    for n in notes:
        r.p(n)

    sheets = getattr(result, "drawings", None) or {}
    if sheets:
        r.h("Drawings")
        r.p("Per gear: the manufacturing drawing with the gear data block of ISO 1340 (SVG, PDF), the exact "
            "transverse profile for wire EDM (DXF, arcs and splines within 0.01 um) and the gear data (JSON).")
        base = Path(next(iter(sheets.values()))).parent.parent
        rows = {}
        for key, path in sheets.items():
            _, gear, kind = key.split(":")
            rel = Path(path).relative_to(base).as_posix()
            rows.setdefault(gear, {})[kind] = f"[{Path(path).name}]({rel})"
        r.table(["gear", "drawing (SVG)", "drawing (PDF)", "profile (DXF)", "gear data (JSON)"],
                [[g, *(k.get(kind, "-") for kind in ("svg", "pdf", "dxf", "json"))] for g, k in rows.items()])
    parts = getattr(result.parts, "parts", [])
    r.h("Parts")
    r.table(["part", "group", "kind", "description"], [[p.name, p.group, p.kind, p.description] for p in parts])
    files = result.files.get("records", {}) if result.files else {}
    r.h("Files")
    r.p(f"{len(files)} files besides this report; see manifest.json for units, tolerances and versions.")
    return r
def figure_link(name: str) -> str:
    """The figure ``name``'s PNG path relative to the build folder, as the report links it."""
    return f"{FIGURE_FOLDER}/{name}.png"


def write_figures(length_unit: str, stiffness: Any, folder: str | Path, view: Any = None, layout_figure: Any = None
                  ) -> tuple[dict[str, Path], dict[str, str], list[str]]:
    """Write the build's figures (the rendered ``view``, a ``geargen.cad.render.RenderedView``; the
    ``layout_figure``; the preload diagram of the ``stiffness`` summary), each that is given, as
    ``figures/<name>.png`` and ``.svg`` into ``folder``. Returns the files written (by role), each
    figure's PNG path relative to ``folder`` (for :func:`compose`) and notes on figures that could
    not be drawn."""
    from geargen.report.figures import save_figure
    folder = Path(folder)
    made = {}
    if view is not None:
        from geargen.report.view import view_figure
        made["render"] = view_figure(view, length_unit)
    if layout_figure is not None:
        made["layout"] = layout_figure
    notes = []
    if stiffness is not None:
        from geargen.report.stiffness import preload_diagram_figure
        try:
            made["preload_diagram"] = preload_diagram_figure(stiffness)
        except Exception as exc:  # the plot is an aid; the numbers are in the tables
            notes.append(f"preload diagram not drawn: {exc}")
    files: dict[str, Path] = {}
    links = {}
    for name, fig in made.items():
        for fmt, path in save_figure(fig, folder / FIGURE_FOLDER, name).items():
            files[f"figure_{name}_{fmt}"] = path
        links[name] = figure_link(name)
    return files, links, notes
