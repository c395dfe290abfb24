"""The manufacturing drawing of one gear: an A3 landscape sheet as SVG and PDF (:mod:`geargen.report.vector`).

What the sheet shows (420 x 297 mm, ISO 5457 frame: 20 mm filing margin on the left, 10 mm
elsewhere; every length on it in the gear's length unit):

- the transverse section (z = 0, tooth 0 on +x) of the whole gear at a preferred scale of
  ISO 5455 (:data:`PREFERRED_SCALES`), with the reference circle as a chain line and the bore;
- an enlarged detail of two teeth (turned so a tooth points up) with the tip, reference, base
  and root circles named (labels placed clear of each other by :mod:`geargen.report.labels`);
- the axial section with the tip, root and bore diameters and the face width dimensioned;
- the gear data block in the order of ISO 1340:1976 (what the purchaser states on a cylindrical
  gear drawing: teeth, module or diametral pitch - the design's own first -, basic rack,
  pressure angle, helix angle and hand, profile shift, diameters, accuracy grade, tooth
  thickness with its allowances, span and over-balls dimensions with limits, mating gear and
  centre distance), then the drawing's unit, scale, generator and source;
- a title block with the gear's name, the design file and the length unit.

Every value comes from the gear data dict (:func:`geargen.model.gear_data.gear_data`, with the
keys of ``../shared/contracts/gear-data.md``) through :func:`data_rows`; a key the gear lacks
(no accuracy grade, no allowance, no mating gear) reads "not specified", never a made-up value.
The block is laid out deterministically: every text is measured with the font's advance widths and wrapped
to its column, and rows stack downwards from their measured heights, so long values cannot
run into each other. Fonts are at least :data:`MIN_FONT_PT` (3.5 mm body, 2.5 mm capitals, the
smallest lettering of ISO 3098 for A3). Two builds give the same bytes (no dates, fixed salt).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from geargen.units import LENGTH_SUFFIXES, from_mm

SHEET = "A3"
SHEET_MM = (420.0, 297.0)
FRAME_MM = (20.0, 10.0, 410.0, 287.0)  # left, bottom, right, top
MM_PER_PT = 25.4 / 72.0
#: the smallest font on the sheet (pt): 10 pt = 3.5 mm em, DejaVu Sans capitals 2.5 mm high
MIN_FONT_PT = 10.0
TITLE_FONT_PT = 14.0
FONT = "DejaVu Sans"
#: ISO 5455 scales (enlargement > 1), tried largest first
PREFERRED_SCALES = (50.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02)
#: decimals a length is given to, per unit (0.1 um and 0.25 um)
DECIMALS = {"mm": 4, "in": 5}
NOT_SPECIFIED = "not specified"
PAD_MM = 1.2  # clearance between a text and its cell's side
WRAP_FILL = 0.95  # the share of a cell's width a wrapped line may fill (as the font's advance widths measure it)
ROW_PAD_MM = 0.6  # and its cell's top and bottom
#: the row padding of a data block that does not fit with :data:`ROW_PAD_MM` (a gear with three or more
#: mates): a line's 1.2 em still holds the font's ascent and descent (1.164 em), so text stays in its cell
TIGHT_ROW_PAD_MM = 0.1
#: the longest chord (sheet mm) of a drawn tooth outline: its sagitta on a 0.5 mm radius of the sheet is
#: under 3 um, a hundredth of the outline's 0.5 mm line
OUTLINE_STEP_MM = 0.1
HATCH_PITCH_MM = 25.4 / 24  # section hatching's spacing along x (matplotlib's "////" the sheets had)
ARROW_MM = (2.0, 0.4)  # a filled arrowhead's length and half width (ISO 129-1: closed, filled, about 23°)

# the sheet's areas (mm): data block and title block on the right, views on the left
DATA_BLOCK = (230.0, 52.0, 410.0, 287.0)
TITLE_BLOCK = (230.0, 10.0, 410.0, 50.0)
COLUMNS_MM = (74.0, 24.0, 82.0)  # name | symbol | value
FULL_VIEW = (25.0, 120.0, 135.0, 270.0)  # drawing box of the whole gear (without its title)
SECTION_VIEW = (140.0, 120.0, 225.0, 270.0)
DETAIL_VIEW = (30.0, 18.0, 100.0, 102.0)
#: the blank's table (datums, blank tolerances, material, finish) beside the detail
BLANK_BLOCK = (106.0, 12.0, 226.0, 116.0)  # up to below the axial section's lowest dimension
BLANK_COLUMNS_MM = (34.0, 12.0, 74.0)  # name | symbol | value
#: the lines a text of the designer's own takes at most in its cell (the blank table's value column,
#: the title block's part-number and revision cells); the design keys' length limits
#: (geargen.design.gear.DRAWN_TEXT_MAX) are these lines of the widest letter the drawing font draws
DRAWN_TEXT_LINES = {"material": 4, "heat_treatment": 2, "part_number": 2, "revision": 1}
#: room (mm) kept right of the axial section for datum B's indicator
DATUM_ROOM_MM = 9.0
#: side (mm) of a datum letter's frame (ISO 5459), the letter at the sheet's lettering size
DATUM_FRAME_MM = 5.0
#: ISO 1101 circular runout (radial of the toothed surface, axial of face B)
RUNOUT_SYMBOL = "↗"
#: a tolerance frame's height (mm) and the gap (mm) kept between it and the nearest line or text
TOLERANCE_FRAME_MM = 6.0
TOLERANCE_GAP_MM = 1.0
#: below the transverse section (its gear fits within FULL_VIEW's 100 mm square about its centre,
#: so the view's bottom 20 mm are empty): where the frames stand when the axial section leaves no room
FRAME_PLACE_MM = (FULL_VIEW[2], FULL_VIEW[1] + 1.0)  # right end of the row of frames, their bottom


def scale_text(scale: float) -> str:
    """``5:1``, ``1:1``, ``1:2``."""
    return f"{scale:g}:1" if scale >= 1 else f"1:{1 / scale:g}"


def preferred_scale(size_mm: float, room_mm: float) -> float:
    """The largest :data:`PREFERRED_SCALES` scale at which ``size_mm`` fits in ``room_mm``."""
    for s in PREFERRED_SCALES:
        if size_mm * s <= room_mm:
            return s
    return PREFERRED_SCALES[-1]


def format_number(value, unit: str) -> str:
    """A length in the gear's unit to the sheet's decimals, without the unit (``12.3456``): the
    dimensions of the views (the title block states the unit)."""
    return f"{value:.{DECIMALS[unit]}f}"


def format_length(value, unit: str) -> str:
    """A length in the gear's unit as the data block writes it (``12.3456 mm``); None: not specified."""
    if value is None:
        return NOT_SPECIFIED
    return f"{format_number(value, unit)} {unit}"


def format_um(value_um, unit: str, signed: bool = False) -> str:
    """A deviation or tolerance given in um, in the gear's unit (on a metric sheet with the um value beside it)."""
    if value_um is None:
        return NOT_SPECIFIED
    v = from_mm(value_um * 1e-3, unit)
    sign = "+" if signed else ""
    if unit != "mm":  # an inch sheet speaks inches only
        return f"{v:{sign}.{DECIMALS[unit] + 1}f} {unit}"
    return f"{v:{sign}.{DECIMALS[unit]}f} {unit} ({value_um:{sign}.1f} µm)"


def format_tolerance(value_um, unit: str) -> str:
    """A geometric tolerance's value as its frame states it (ISO 1101): in the gear's unit, without
    the unit, to the decimals of :func:`format_um` (an inch sheet one more)."""
    v = from_mm(value_um * 1e-3, unit)
    return f"{v:.{DECIMALS[unit] + (0 if unit == 'mm' else 1)}f}"


def format_limits(limits, unit: str) -> str:
    """``[smallest, largest]`` measurement as ``max / min`` (the order a shop reads it)."""
    if not limits:
        return NOT_SPECIFIED
    lo, hi = limits
    return f"{hi:.{DECIMALS[unit]}f} / {lo:.{DECIMALS[unit]}f} {unit} (max / min)"


def _diameter(data: dict, key: str):
    r = data.get(key)
    return None if r is None else 2.0 * r


@dataclass(frozen=True)
class Mate:
    """A gear this one meshes with: its name and teeth, the working centre distance (gear's unit)
    and its tolerance ``(lower, upper)`` deviation when the design gives one."""

    name: str
    teeth: int
    centre_distance: float | None
    centre_distance_tolerance: tuple[float, float] | None = None

    def to_dict(self) -> dict:
        return {"name": self.name, "teeth": self.teeth, "centre_distance": self.centre_distance,
                "centre_distance_tolerance": None if self.centre_distance_tolerance is None
                else list(self.centre_distance_tolerance)}


def mates_from_layout(layout, gear_name: str, unit: str) -> list[Mate]:
    """The gears ``gear_name`` meshes with in the resolved drive (engaged meshes), each with the
    centre distance of the placed centres (where the mesh runs) and the design's centre-distance
    tolerance (``[checks] centre_distance_tolerance_*``, when given), in ``unit``."""

    f_a = layout.resolved.checks.centre_distance_tolerance  # [checks], 0 when the design gives none
    tolerance = (float(from_mm(-f_a, unit)), float(from_mm(f_a, unit))) if f_a > 0 else None
    out = []
    for m in layout.meshes:
        if not m.engaged:
            continue
        for me, other in ((m.gear1, m.gear2), (m.gear2, m.gear1)):
            if me.name == gear_name and all(o.name != other.name for o in out):
                a = m.centre_distance
                out.append(Mate(other.name, other.teeth, None if not math.isfinite(a) else float(from_mm(a, unit)),
                                tolerance))
    return out


def mates_from_declared(design, settings, gear_name: str, unit: str) -> list[Mate]:
    """The gears ``gear_name`` meshes with among the pairs ``[checks] meshes`` declares (a design that
    places no drive), each at its declared centre distance with the design's centre-distance tolerance
    (``[checks] centre_distance_tolerance_*``, when given), in ``unit``."""
    f_a = settings.centre_distance_tolerance
    tolerance = (float(from_mm(-f_a, unit)), float(from_mm(f_a, unit))) if f_a > 0 else None
    out = []
    for m in settings.meshes:
        for me, other in ((m.gear1, m.gear2), (m.gear2, m.gear1)):
            teeth = getattr(design.gear(other), "teeth", None)
            if me == gear_name and teeth is not None and all(o.name != other for o in out):
                out.append(Mate(other, int(teeth), float(from_mm(m.centre_distance, unit)), tolerance))
    return out


def mates_of(data: dict) -> list[Mate]:
    """The :class:`Mate` s a gear data dict records (``"mating_gears"``; none when absent)."""
    out = []
    for m in data.get("mating_gears") or []:
        tol = m.get("centre_distance_tolerance")
        out.append(Mate(m["name"], m["teeth"], m.get("centre_distance"), None if tol is None else tuple(tol)))
    return out


def _method_text(method: str | None) -> str:
    """The allowance's method as the sheet states it: its name and centre-distance tolerance (the
    JSON keeps the whole rule)."""
    if not method:
        return NOT_SPECIFIED
    name = method.split(": ")[0]
    return name + (f"; {method[method.index('f_a ='):]}" if "f_a =" in method else "")


def _rack_text(data: dict) -> str:
    rack = data.get("basic_rack")
    if not rack:
        return NOT_SPECIFIED
    ha, hf, rho = rack["addendum_coefficient"], rack["dedendum_coefficient"], rack["tip_radius_coefficient"]
    text = f"h_aP {ha:.3g} m_n, h_fP {hf:.3g} m_n, ρ_fP {rho:.3g} m_n"
    # ISO 53:1998 profile A: 1, 1.25, 0.38
    if (round(ha, 9), round(hf, 9), round(rho, 9)) == (1.0, 1.25, 0.38):
        text = "ISO 53 profile A: " + text
    return text


def pitch_row(module_mm: float, unit: str, kind: str = "Normal", symbol: str = "n") -> tuple[str, str, str]:
    """The pitch as one sheet row in the design's system: the module on a metric sheet, the
    diametral pitch on an inch one (no mm on it); ``kind`` "" names it plainly."""
    if unit == "in":
        return f"{kind} diametral pitch".strip(), f"P_{symbol}", f"{LENGTH_SUFFIXES['in'] / module_mm:.6g} 1/in"
    return f"{kind} module".strip(), f"m_{symbol}", f"{module_mm:.6g} mm"


def pitch_rows(module_mm: float, unit: str, kind: str = "Normal", symbol: str = "n") -> list[tuple[str, str, str]]:
    """The gear's pitch rows: a metric sheet gives the module and the diametral pitch it equals (for
    inch tooling), an inch sheet the diametral pitch only."""
    own = pitch_row(module_mm, unit, kind, symbol)
    return [own] if unit == "in" else [own, pitch_row(module_mm, "in", kind, symbol)]


def data_rows(data: dict, scale: str, version: str, source: str) -> list[tuple[str, str, str]]:
    """The gear data block as ``(name, symbol, value)`` rows, in the order of ISO 1340.

    ``data``: the gear data dict (lengths in ``data["length_unit"]``), with ``mating_gears``
    when the gear meshes with others; ``scale``, ``version``, ``source``: the drawing's."""
    u = data["length_unit"]
    L = lambda v: format_length(v, u)  # noqa: E731 - one formatter for every length on the sheet
    rows = [("Number of teeth", "z", f"{data['teeth']}")] + pitch_rows(data["normal_module_mm"], u)
    helical = data.get("hand") is not None
    rows += [
        ("Basic rack tooth proportions", "", _rack_text(data)),
        ("Normal pressure angle", "α_n", f"{data['normal_pressure_angle_deg']:.4f}°"),
        ("Helix angle and hand", "β", f"{data['helix_angle_deg']:.4f}° {data['hand']} hand" if helical
         else "0° (spur)"),
        ("Profile shift coefficient", "x_n", f"{data['profile_shift_normal']:+.4f}"),
        ("Reference diameter", "d", L(_diameter(data, "reference_radius"))),
        ("Tip diameter", "d_a", L(_diameter(data, "tip_radius"))),
        ("Root diameter", "d_f", L(_diameter(data, "root_radius"))),
        ("Base diameter", "d_b", L(_diameter(data, "base_radius"))),
        ("Face width", "b", L(data.get("face_width"))),
        ("Lead", "p_z", L(data.get("lead")) if helical else "- (spur)"),
    ]
    acc = data.get("accuracy")
    if acc:
        held = " (coarsest within the error budget)" if "budget" in acc.get("grade_source", "") else ""
        rows.append(("Accuracy grade", "", f"{acc['standard']} grade {acc['grade']}{held}"))
    else:
        rows.append(("Accuracy grade", "", NOT_SPECIFIED))
    for name, symbol, key in (("Single pitch tolerance", "f_pT", "single_pitch_um"),
                              ("Cumulative pitch tolerance", "F_pT", "cumulative_pitch_um"),
                              ("Total profile tolerance", "F_αT", "profile_total_um"),
                              ("Total helix tolerance", "F_βT", "helix_total_um"),
                              ("Runout tolerance", "F_rT", "runout_um")):
        value = format_um(acc.get(key), u) if acc else "-"
        if acc and key in ("helix_total_um", "runout_um") and acc.get(key) is not None:
            value += ", to datum A"  # the bore axis the gear is cut and inspected on
        rows.append((name, symbol, value))
    allowance = data.get("thickness_allowance")
    rows += [
        ("Tooth thickness allowance, upper", "A_sne",
         format_um(allowance["upper_um"], u, signed=True) if allowance else NOT_SPECIFIED),
        ("Tooth thickness allowance, lower", "A_sni",
         format_um(allowance["lower_um"], u, signed=True) if allowance else NOT_SPECIFIED),
        ("Allowance method", "", _method_text(allowance.get("method")) if allowance else "-"),
        ("Thinning in the model (circumferential)", "", L(data.get("thinning_circumferential"))),
    ]
    span = data.get("span")
    rows += [
        (f"Span over k = {span['teeth_spanned']} teeth" if span else "Span over k teeth", "W_k",
         L(span["span_normal"]) if span else NOT_SPECIFIED),
        ("Span limits", "W_k", format_limits(span.get("limits"), u) if span else "-"),
    ]
    pins = data.get("over_pins")
    kind = (pins or {}).get("kind", "balls")
    rows += [
        (f"{kind[:-1].capitalize()} diameter", "D_M", L(pins["diameter"]) if pins else NOT_SPECIFIED),
        (f"Dimension over {kind}", "M_dK", L(pins["dimension"]) if pins else NOT_SPECIFIED),
        (f"Over-{kind} limits", "M_dK", format_limits(pins.get("limits"), u) if pins else "-"),
    ]
    chord = data.get("chordal_tooth")
    if chord:  # a gear-tooth caliper's reading: normal chord at the virtual gear's reference circle, height from the tip
        rows += [("Chordal tooth thickness / height", "s_c / h_c",
                  f"{format_number(chord['thickness_normal'], u)} / {format_number(chord['height'], u)} {u}"),
                 ("Chordal thickness limits", "s_c", format_limits(chord.get("limits"), u))]
    mates = mates_of(data)
    if not mates:
        rows += [("Mating gear", "", NOT_SPECIFIED), ("Centre distance", "a", NOT_SPECIFIED)]
    for m in mates:
        rows.append(("Mating gear", "z_2", f"{m.name} ({m.teeth} teeth)"))
        a = L(m.centre_distance)
        if m.centre_distance is not None:
            if m.centre_distance_tolerance is None:
                a += ", tolerance not specified"
            else:
                lo, hi = m.centre_distance_tolerance
                a += f" {hi:+.{DECIMALS[u]}f} / {lo:+.{DECIMALS[u]}f}"
        rows.append((f"Centre distance to {m.name}", "a", a))
    rows += [
        ("Drawing units", "", f"{u} (angles in degrees)"),
        ("Drawing scale", "", scale),
        ("Generator", "", f"geargen {version}"),
        ("Source", "", source),
    ]
    return rows


def _tolerance_text(tol: dict | None, unit: str) -> str:
    """A size's tolerance as the blank table states it: ``h11: 19.6435 / 19.5135 mm (max / min)``."""
    if not tol or not tol.get("limits"):
        return NOT_SPECIFIED
    head = f"{tol['code']} (ISO 286-1)" if tol.get("code") else "by deviation"
    return f"{head}: {format_limits(tol['limits'], unit)}"


def blank_rows(data: dict) -> list[tuple]:
    """The blank table as ``(name, symbol, value)`` rows: datums A (bore axis) and B (reference
    face), the bore with its ISO 286 fit and limits, the tip diameter's and face width's tolerances,
    the axial runout of face B referred to A (with the rule it is computed by), material, heat
    treatment, hardness and flank finish. A key the gear data lacks reads "not specified". The
    designer's own texts (material, heat treatment) carry a fourth item, the most lines they may
    take (:data:`DRAWN_TEXT_LINES`)."""
    u = data["length_unit"]
    datums = data.get("datums") or {}
    rows = [("Datum A", "A", datums.get("A", NOT_SPECIFIED)), ("Datum B", "B", datums.get("B", NOT_SPECIFIED))]
    bore = data.get("bore")
    if bore:
        fit = f" {bore['code']}" if bore.get("code") else ", fit not specified"
        limits = f": {format_limits(bore['limits'], u)}" if bore.get("limits") else ""
        rows.append(("Bore", "d_B", format_length(bore["nominal"], u) + fit + limits))
    else:
        rows.append(("Bore", "d_B", "- (no bore)"))
    rows += [("Tip diameter", "d_a", _tolerance_text(data.get("tip_diameter_tolerance"), u)),
             ("Face width", "b", _tolerance_text(data.get("face_width_tolerance"), u))]
    geo = data.get("datum_tolerances") or {}
    face = geo.get("face_axial_runout_um")
    rows.append(("Axial runout of B", "t_B", f"{format_um(face, u)} to A; geargen's rule {geo['face_axial_runout_formula']}"
                 if face is not None else NOT_SPECIFIED))
    pins = data.get("over_pins")
    if pins:  # the over-pins rows of the data block measure with a pin of this series
        rows.append((f"{pins['kind'][:-1].capitalize()} series", "D_M", pins.get("series") or NOT_SPECIFIED))
    mat = data.get("material") or {}
    hard = mat.get("hardness")
    ra = data.get("flank_roughness_Ra_um")
    rows += [("Material", "", mat.get("material") or NOT_SPECIFIED, DRAWN_TEXT_LINES["material"]),
             ("Heat treatment", "", mat.get("heat_treatment") or NOT_SPECIFIED, DRAWN_TEXT_LINES["heat_treatment"]),
             ("Surface hardness", "", f"{hard['value']:g} {hard['unit']}" if hard else NOT_SPECIFIED),
             ("Flank roughness", "Ra", NOT_SPECIFIED if ra is None else
              f"{ra:g} µm" + (f" ({ra / 0.0254:.3g} µin)" if u == "in" else ""))]
    return rows


# ---------------------------------------------------------------- measuring and wrapping text


def cell_gid(n: int, cell) -> str:
    """The SVG id of the ``n``-th text that must stay inside ``cell`` (sheet mm, y up, 3 decimals):
    ``cell-<n>-<x0>_<y0>_<x1>_<y1>``; :func:`parse_cell_gid` reads it back."""
    return f"cell-{n}-" + "_".join(f"{c:.3f}" for c in cell)


def parse_cell_gid(gid: str) -> tuple[float, float, float, float] | None:
    """The cell (sheet mm, y up) of a :func:`cell_gid`, or None for another id."""
    if not gid or not gid.startswith("cell-"):
        return None
    return tuple(float(v) for v in gid.split("-", 2)[2].split("_"))


class Sheet:
    """The A3 sheet being drawn: primitives recorded in sheet mm (y up) by :mod:`geargen.report.vector`,
    written as SVG and PDF from the one record (:meth:`write`). Text is measured with the drawing
    font's own advance widths (DejaVu Sans, what the SVG names and a browser renders)."""

    def __init__(self):
        from geargen.report.vector import Drawing

        self.drawing = Drawing(SHEET_MM)
        self.cells: list[tuple[object, tuple[float, float, float, float]]] = []

    @property
    def texts(self) -> list:
        """Every recorded text (:class:`geargen.report.vector.Text`: its string, box and group id)."""
        from geargen.report.vector import Text
        return [item for item in self.drawing.items if isinstance(item, Text)]

    def width_mm(self, text: str, size: float, weight: str = "normal") -> float:
        from geargen.report.vector import face
        return face(weight).width_em(text) * size * MM_PER_PT

    def in_cell(self, text, cell) -> None:
        """Record that ``text`` (a recorded text) must lie inside ``cell`` (x0, y0, x1, y1 sheet mm, y up):
        its SVG group id carries the cell (:func:`cell_gid`), and :attr:`cells` keeps the pair."""
        self.cells.append((text, tuple(float(c) for c in cell)))
        text.gid = cell_gid(len(self.cells), cell)

    def text(self, x, y, s, size=MIN_FONT_PT, ha="left", va="baseline", weight="normal", color="black",
             rotation=0.0):
        """A one-line text at ``(x, y)`` aligned by ``ha`` (left, center, right) and ``va`` (top, bottom,
        center, center_baseline: the box of ascent and descent centred, baseline), turned ``rotation``
        degrees about that point; returns the recorded text."""
        from geargen.report.vector import Text, face, grey

        f = face(weight)
        em = size * MM_PER_PT
        width = f.width_em(s) * em
        ascent, descent = f.ascent * em, f.descent * em
        lift = {"top": -ascent, "bottom": descent, "baseline": 0.0}.get(va, (descent - ascent) / 2)
        share = {"left": 0.0, "center": 0.5, "right": 1.0}[ha]
        c, sn = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
        bx, by = x - sn * lift, y + c * lift  # the baseline's point under the anchor
        corners = [(u, v) for u in (-share * width, (1 - share) * width) for v in (-descent, ascent)]
        xs = [bx + c * u - sn * v for u, v in corners]
        ys = [by + sn * u + c * v for u, v in corners]
        t = Text(s, bx, by, size, weight, grey(color), {0.0: "start", 0.5: "middle", 1.0: "end"}[share], rotation,
                 (min(xs), min(ys), max(xs), max(ys)))
        if s:  # an empty cell (a row without a symbol) draws nothing
            self.drawing.items.append(t)
        return t

    def line(self, xs, ys, lw=0.35, color="black", linestyle=None, clip=None, closed=False):
        """A polyline through ``xs``, ``ys`` (sheet mm), ``lw`` mm wide (ISO 128: 0.35 thick, 0.18 thin);
        ``linestyle`` ``(0, (on, off, ...))`` in line widths (as matplotlib's dashes); ``clip`` a box."""
        from geargen.report.vector import Path_, grey

        pts = np.column_stack([np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)])
        dash = tuple(v * lw for v in linestyle[1]) if linestyle else None
        path = Path_(pts, lw, grey(color), None, closed, dash, clip)
        self.drawing.items.append(path)
        return path

    def polygon(self, points, fill="black", lw=0.18, edge="black") -> None:
        """A filled polygon (sheet mm), outlined ``lw`` mm in ``edge`` (None: no outline)."""
        from geargen.report.vector import Path_, grey

        self.drawing.items.append(Path_(np.asarray(points, dtype=float), lw, None if edge is None else grey(edge),
                                        grey(fill), True))

    def hatch(self, points, pitch: float = HATCH_PITCH_MM, lw: float = 0.18, color: str = "0.35") -> None:
        """Section hatching (ISO 128-50: thin lines at 45°, ``pitch`` mm apart along x) across the
        convex polygon ``points`` (sheet mm)."""
        pts = np.asarray(points, dtype=float)
        d = pts[:, 0] - pts[:, 1]  # constant along a 45° line
        for c in np.arange(math.ceil(d.min() / pitch) * pitch, d.max(), pitch):
            hits = []
            for a, b in zip(pts, np.roll(pts, -1, axis=0)):
                da, db = a[0] - a[1] - c, b[0] - b[1] - c
                if (da <= 0 < db) or (db <= 0 < da):
                    t = da / (da - db)
                    hits.append(a + t * (b - a))
            if len(hits) >= 2:
                hits.sort(key=lambda p: p[0])
                self.line([hits[0][0], hits[-1][0]], [hits[0][1], hits[-1][1]], lw=lw, color=color)

    def arrow(self, tail, head, lw: float = 0.18, both: bool = False) -> None:
        """A line from ``tail`` to ``head`` with a filled arrowhead (:data:`ARROW_MM`) at ``head``
        (and at ``tail`` with ``both``: a dimension line)."""
        tail, head = np.asarray(tail, dtype=float), np.asarray(head, dtype=float)
        self.line([tail[0], head[0]], [tail[1], head[1]], lw=lw)
        length, half = ARROW_MM
        ends = [(tail, head), (head, tail)] if both else [(tail, head)]
        for a, b in ends:
            u = b - a
            n = float(np.hypot(*u))
            if n == 0:
                continue
            u /= n
            v = np.array([-u[1], u[0]])
            base = b - u * min(length, n / 2 if both else n)
            self.polygon([b, base + v * half, base - v * half], lw=lw)

    def text_boxes(self) -> list[tuple[str, tuple[float, float, float, float], str | None]]:
        """Every recorded text with its box (sheet mm) and group id: what a test measures."""
        return [(t.text, t.box, t.gid) for t in self.texts]

    def svg(self) -> bytes:
        from geargen.report.vector import svg_bytes
        return svg_bytes(self.drawing)

    def pdf(self) -> bytes:
        from geargen.report.vector import pdf_bytes
        return pdf_bytes(self.drawing)

    def wrap(self, text: str, width_mm: float, size: float, most: int | None = None) -> list[str]:
        """``text`` broken into lines no wider than ``width_mm`` (at spaces, else after ``/``,
        else anywhere), measured with :data:`WRAP_FILL` of the width: a browser lays the SVG's text
        out with its own shaping and rounding, which may differ a little from the advance widths summed
        here (headless Chromium checks it, tests/report/test_drawing_cells.py). With ``most``, a text that needs
        more lines broken at words is broken anywhere instead, each line filled: then ``most`` lines
        hold ``most`` times the letters of the widest that fit one line, whatever the spaces."""
        width_mm *= WRAP_FILL
        if self.width_mm(text, size) <= width_mm:
            return [text]
        lines = self._wrap_words(text, width_mm, size)
        if most is not None and len(lines) > most:
            lines = self._fill(text, width_mm, size)
        return lines

    def _fill(self, text: str, width_mm: float, size: float) -> list[str]:
        """``text`` cut into lines as full as ``width_mm`` allows, at any character."""
        lines, start = [], 0
        while start < len(text):
            n = len(text) - start
            while n > 1 and self.width_mm(text[start:start + n], size) > width_mm:
                n -= 1
            lines.append(text[start:start + n])
            start += n
        return lines

    def _wrap_words(self, text: str, width_mm: float, size: float) -> list[str]:
        tokens = []
        for word in text.split(" "):
            parts = word.split("/")
            tokens += [p + "/" for p in parts[:-1]] + [parts[-1]]
            tokens[-1] += " "
        tokens[-1] = tokens[-1].rstrip(" ")
        lines, current = [], ""
        for tok in tokens:
            trial = current + tok
            if current and self.width_mm(trial.rstrip(" "), size) > width_mm:
                lines.append(current.rstrip(" "))
                current = tok
            else:
                current = trial
            while self.width_mm(current.rstrip(" "), size) > width_mm and len(current) > 1:
                # a token wider than the column: cut it where it fits
                n = len(current)
                while n > 1 and self.width_mm(current[:n], size) > width_mm:
                    n -= 1
                lines.append(current[:n])
                current = current[n:]
        if current.strip():
            lines.append(current.rstrip(" "))
        return lines


# ---------------------------------------------------------------- the sheet


def draw_frame(sheet: Sheet) -> None:
    w, h = SHEET_MM
    sheet.line([0, w, w, 0, 0], [0, 0, h, h, 0], lw=0.18, color="0.6")  # trimmed sheet edge
    x0, y0, x1, y1 = FRAME_MM
    sheet.line([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], lw=0.7)


def _box(sheet, box, lw=0.35):
    x0, y0, x1, y1 = box
    sheet.line([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], lw=lw)


def draw_data_block(sheet: Sheet, rows, box=DATA_BLOCK, size: float = MIN_FONT_PT, columns=COLUMNS_MM,
                header=("Gear data (ISO 1340)", "Symbol", "Value"), row_pad: float = ROW_PAD_MM) -> list[float]:
    """Draw ``rows`` as a table in ``box`` (from its top) with ``columns`` widths (mm) under
    ``header``, ``row_pad`` mm above and below each row's lines; returns the bottom of each row (mm).
    Raises ValueError when the rows do not fit the box. Each text carries its cell (:func:`cell_gid`)
    so a test can find it outside."""
    x0, y0, x1, y1 = box
    line_h = size * 1.2 * MM_PER_PT
    cols = np.cumsum((x0,) + tuple(columns))
    assert abs(cols[-1] - x1) < 1e-9
    header = [tuple(header)]
    wrapped = []  # every row wrapped and measured before anything is drawn: a block that does not fit draws nothing
    for row in header + list(rows):
        most = row[3] if len(row) > 3 else None  # a designer's text: the lines its length limit allows
        cells = [sheet.wrap(text, columns[j] - 2 * PAD_MM, size, most if j == 2 else None)
                 for j, text in enumerate(row[:3])]
        if most is not None and len(cells[2]) > most:
            raise ValueError(f"{row[0]!r} needs {len(cells[2])} lines, more than its {most}")
        wrapped.append(cells)
    heights = [max(len(c) for c in cells) * line_h + 2 * row_pad for cells in wrapped]
    if sum(heights) > y1 - y0:
        raise ValueError(f"the gear data block needs more than {y1 - y0:g} mm")
    y = y1
    bottoms = []
    for i, (cells, height) in enumerate(zip(wrapped, heights)):
        weight = "bold" if i == 0 else "normal"
        for j, lines in enumerate(cells):
            for k, text in enumerate(lines):
                t = sheet.text(cols[j] + PAD_MM, y - row_pad - (k + 0.5) * line_h, text, size,
                               va="center_baseline", weight=weight)
                sheet.in_cell(t, (cols[j], y - height, cols[j + 1], y))
        y -= height
        sheet.line([x0, x1], [y, y], lw=0.35 if i == 0 else 0.18)
        bottoms.append(y)
    for c in cols[1:-1]:
        sheet.line([c, c], [y, y1], lw=0.18)
    _box(sheet, (x0, y, x1, y1))
    return bottoms


def fit_data_block(sheet: Sheet, rows) -> list[float]:
    """The gear data block of ``rows`` (:func:`draw_data_block`), its rows closer together
    (:data:`TIGHT_ROW_PAD_MM`) when they do not fit otherwise: a gear with three or more mates, long
    texts and a helix keeps every row, the chordal tooth's too (tests/report/test_drawing_cells.py).
    Raises ValueError when even that does not fit."""
    try:
        return draw_data_block(sheet, rows)
    except ValueError:
        return draw_data_block(sheet, rows, row_pad=TIGHT_ROW_PAD_MM)


def title_cells() -> dict[str, tuple[float, float, float, float]]:
    """The title block's cells (sheet mm, y up): ``name`` (top left), ``design_file``,
    ``part_number`` (top right), ``revision``, ``length_unit`` and ``scale``."""
    x0, y0, x1, y1 = TITLE_BLOCK
    ym, xm = y0 + 0.55 * (y1 - y0), x0 + 110
    xr = xm + 34  # revision | length unit
    return {"name": (x0, ym, xm, y1), "design_file": (x0, y0, xm, ym), "part_number": (xm, ym, x1, y1),
            "revision": (xm, ym - 11, xr, ym), "length_unit": (xr, ym - 11, x1, ym), "scale": (xm, y0, x1, ym - 11)}


def title_cell_width(cell) -> float:
    """The width (mm) a title-block cell's text wraps to: 2 mm clear of each side."""
    return cell[2] - cell[0] - 4


def draw_title_block(sheet: Sheet, name: str, design_file: str, unit: str, scale: str, version: str,
                 part_number: str | None = None, revision: str | None = None, kind: str = "Gear") -> None:
    """The title block: the part's name (``kind`` above it) and its part number; the design file,
    the revision and the length unit; the scale and sheet. A part number or revision the design
    does not give reads "not specified"."""
    x0, y0, x1, y1 = TITLE_BLOCK
    c = title_cells()
    _box(sheet, TITLE_BLOCK, lw=0.7)
    xm, ym, xr = c["part_number"][0], c["part_number"][1], c["revision"][2]
    sheet.line([x0, x1], [ym, ym], lw=0.35)
    sheet.line([xm, xm], [y0, y1], lw=0.35)
    sheet.line([xr, xr], [ym, ym - 11], lw=0.18)
    sheet.line([xm, x1], [ym - 11, ym - 11], lw=0.18)
    top = c["name"]
    sheet.in_cell(sheet.text(x0 + 3, y1 - 3, kind, MIN_FONT_PT, va="top", color="0.3"), top)
    for k, line in enumerate(sheet.wrap(name, xm - x0 - 6, TITLE_FONT_PT)[:2]):
        sheet.in_cell(sheet.text(x0 + 3, y1 - 8.5 - k * 6, line, TITLE_FONT_PT, va="top", weight="bold"), top)
    cells = [(c["design_file"], "Design file", design_file, 3, False),
             (c["part_number"], "Part number", part_number or NOT_SPECIFIED, DRAWN_TEXT_LINES["part_number"], True),
             (c["revision"], "Revision", revision or NOT_SPECIFIED, DRAWN_TEXT_LINES["revision"], True),
             (c["length_unit"], "Length unit", unit, 1, False)]
    for cell, label, value, most, designers in cells:
        x, y = cell[0] + 2, cell[3] - 1.2
        sheet.in_cell(sheet.text(x, y, label, MIN_FONT_PT, va="top", color="0.3"), cell)
        lines = sheet.wrap(value, title_cell_width(cell), MIN_FONT_PT, most if designers else None)
        if designers and len(lines) > most:  # the design reader's length limit keeps this from happening
            raise ValueError(f"the {label.lower()} needs {len(lines)} lines, more than its {most}")
        for k, line in enumerate(lines[:most]):
            sheet.in_cell(sheet.text(x, y - 4.6 - k * 4.4, line, MIN_FONT_PT, va="top"), cell)
    for k, line in enumerate(sheet.wrap(f"Scale {scale}, sheet {SHEET}", x1 - xm - 4, MIN_FONT_PT)[:2][::-1]):
        sheet.in_cell(sheet.text(xm + 2, y0 + 1.2 + k * 4.4, line, MIN_FONT_PT, va="bottom"), c["scale"])


def outline_points(profile, step_mm: float) -> np.ndarray:
    from geargen.profile.segments import sample_outline
    pts = sample_outline(profile.outline(), step_mm)
    return np.vstack([pts, pts[:1]])


def bore_points(hub, n: int = 361) -> np.ndarray | None:
    if hub.bore_diameter <= 0:
        return None
    rb = hub.bore_diameter / 2
    if hub.keyway_width <= 0:
        t = np.linspace(0, 2 * np.pi, n)
        return rb * np.column_stack([np.cos(t), np.sin(t)])
    w2 = hub.keyway_width / 2
    a = math.asin(w2 / rb)
    xk, xf = math.sqrt(rb * rb - w2 * w2), rb + hub.keyway_depth
    t = np.linspace(a, 2 * np.pi - a, n)
    arc = rb * np.column_stack([np.cos(t), np.sin(t)])
    return np.vstack([arc, [(xk, -w2), (xf, -w2), (xf, w2), (xk, w2)]])


def centre_cross(sheet, cx, cy, half):
    dash = dict(lw=0.18, linestyle=(0, (12, 2, 1.5, 2)), color="0.25")
    sheet.line([cx - half, cx + half], [cy, cy], **dash)
    sheet.line([cx, cx], [cy - half, cy + half], **dash)


def view_title(sheet, box, text):
    sheet.text((box[0] + box[2]) / 2, box[3] + 2.5, text, MIN_FONT_PT, ha="center", va="bottom", weight="bold")


def _full_view(sheet, profile, scale: float) -> None:
    box = FULL_VIEW
    cx, cy = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
    k = scale  # sheet mm per gear mm
    to = lambda p: (cx + p[:, 0] * k, cy + p[:, 1] * k)  # noqa: E731
    pts = outline_points(profile, OUTLINE_STEP_MM / k)
    sheet.line(*to(pts), lw=0.5)
    bore = bore_points(profile.spec.hub)
    if bore is not None:
        sheet.line(*to(np.vstack([bore, bore[:1]])), lw=0.5)
    r = profile.reference_radius * k
    t = np.linspace(0, 2 * np.pi, 721)
    sheet.line(cx + r * np.cos(t), cy + r * np.sin(t), lw=0.18, linestyle=(0, (12, 2, 1.5, 2)), color="0.25")
    centre_cross(sheet, cx, cy, profile.tip_radius * k + 4)
    view_title(sheet, box, f"Transverse section ({scale_text(scale)})")


def _section_view(sheet, profile, unit: str, scale: float, datum_tolerances: dict | None = None) -> None:
    """Axial section: the face width, tip, root and bore diameters dimensioned (gear's unit), datums
    A and B, and the runout frames of ``datum_tolerances`` (the gear data's block) with their leaders."""
    spec = profile.spec
    box = SECTION_VIEW
    k = scale
    b = spec.face_width * k
    ra, rf = profile.tip_radius * k, profile.root_radius * k
    hub = spec.hub
    rbore = hub.bore_diameter / 2 * k
    hub_len, rhub = hub.hub_length * k, hub.hub_diameter / 2 * k
    width = b + hub_len
    cx = box[0] + 34 + hub_len + (box[2] - box[0] - 34 - DATUM_ROOM_MM - width) / 2
    cy = (box[1] + box[3]) / 2
    x0, x1 = cx, cx + b
    thick, thin = 0.5, 0.18
    # body between bore and root circle hatched (teeth are drawn unsectioned, ISO 2203)
    for sign in (1, -1):
        sheet.hatch([(x0, cy + sign * rbore), (x1, cy + sign * rbore), (x1, cy + sign * rf), (x0, cy + sign * rf)])
        sheet.line([x0, x1, x1, x0, x0], [cy + sign * rbore, cy + sign * rbore, cy + sign * ra, cy + sign * ra,
                                          cy + sign * rbore], lw=thick)
        sheet.line([x0, x1], [cy + sign * rf, cy + sign * rf], lw=thin)
        rr = profile.reference_radius * k
        sheet.line([x0 - 2, x1 + 2], [cy + sign * rr, cy + sign * rr], lw=thin, linestyle=(0, (12, 2, 1.5, 2)))
        if hub_len > 0:
            sheet.line([x0, x0 - hub_len, x0 - hub_len, x0], [cy + sign * rhub, cy + sign * rhub,
                                                              cy + sign * rbore, cy + sign * rbore], lw=thick)
            sheet.hatch([(x0 - hub_len, cy + sign * rbore), (x0, cy + sign * rbore), (x0, cy + sign * rhub),
                         (x0 - hub_len, cy + sign * rhub)])
    sheet.line([x0 - hub_len - 4, x1 + 4], [cy, cy], lw=thin, linestyle=(0, (12, 2, 1.5, 2)))
    N = lambda v: format_number(from_mm(v, unit), unit)  # noqa: E731
    left = x0 - hub_len
    dims = [(2 * profile.tip_radius, ra), (2 * profile.root_radius, rf)]
    if rbore > 0:
        dims.append((hub.bore_diameter, rbore))
    # the smallest diameter nearest the section, so no extension line crosses a smaller one's text
    datum_a = rbore if rbore > 0 else ra  # A: the bore's axis, else the tip cylinder's
    for i, (value_mm, half) in enumerate(sorted(dims, key=lambda d: d[1])):
        x = left - 8 - 9 * i
        if half == datum_a:
            # in line with the diameter's dimension line: the datum is the feature's axis (ISO 5459)
            _datum(sheet, "A", (x, cy + half), (x, cy + ra + 4 + DATUM_FRAME_MM / 2))
        dimension(sheet, (x, cy - half), (x, cy + half), f"⌀{N(value_mm)}", vertical=True)
        for sign in (1, -1):  # extension lines
            sheet.line([x - 1.5, left - 1 if half > (rhub if hub_len else 0) or not hub_len else x0 - hub_len - 1],
                       [cy + sign * half, cy + sign * half], lw=thin)
    # B: the face at z = b, on its extension line above the tip, clear of the face width's dimension
    sheet.line([x1, x1], [cy + ra + 1, cy + ra + 4 + DATUM_FRAME_MM], lw=thin)
    yb = cy + ra + 4 + DATUM_FRAME_MM / 2
    _datum(sheet, "B", (x1, yb), (x1 + DATUM_ROOM_MM - 0.5 - DATUM_FRAME_MM / 2, yb))
    y = cy - ra - 6
    dimension(sheet, (x0, y), (x1, y), N(spec.face_width), vertical=False)
    for x in (x0, x1):
        sheet.line([x, x], [y - 1.5, cy - ra - 1], lw=thin)
    # the face width's text reaches 1 mm + a capital's height + descent (~4.5 mm) below its line
    lowest = y - 1.0 - 4.5 - TOLERANCE_GAP_MM
    # radial runout: on the tip cylinder's extension line, between the section and the nearest
    # diameter's dimension line (clear of it, so it means the toothed surface, not the axis)
    tip_target = (left - 4.0, cy - ra)
    # axial runout: on face B below the axis, halfway between bore and root, from the right
    face_target = (x1, cy - (rbore + rf) / 2)
    _runout_frames(sheet, datum_tolerances or {}, unit, tip_target, face_target, lowest, x1)
    view_title(sheet, box, f"Axial section ({scale_text(scale)})")


def _runout_frames(sheet, geo: dict, unit: str, tip_target, face_target, lowest: float, face_x: float) -> None:
    """The two ISO 1101 frames of the axial section: circular runout of the toothed surface (radial,
    F_rT) and of face B (axial, t_B), both to datum A, each with a leader ending in an arrow on its
    feature. They stand at the section view's bottom (radial left, axial right, its leader reaching
    face B from the right) when that lies below ``lowest`` (the lowest text of the section), else side
    by side at :data:`FRAME_PLACE_MM` below the transverse section (radial right), their leaders routed
    round the section's dimensions: the radial one level to below the tip's extension line, then up
    onto it; the axial one down under the section's lowest text, along to the right of face B, up and
    onto the face. A tolerance the data lacks has no frame."""
    frames = [(geo.get("radial_runout_um"), tip_target), (geo.get("face_axial_runout_um"), face_target)]
    frames = [(v, t) for v, t in frames if v is not None]
    if not frames:
        return
    widths = [_frame_widths(sheet, format_tolerance(v, unit)) for v, _ in frames]
    box = SECTION_VIEW
    bottom = box[1] + TOLERANCE_GAP_MM
    room = bottom + TOLERANCE_FRAME_MM <= lowest and sum(map(sum, widths)) + 4 * TOLERANCE_GAP_MM <= box[2] - box[0]
    right_end = FRAME_PLACE_MM[0]
    for (value, target), w in zip(frames, widths):
        on_face = target is face_target
        if room:
            x_left, y_bottom = (box[2] - sum(w) if on_face else box[0] + TOLERANCE_GAP_MM), bottom
        else:
            x_left, y_bottom = right_end - sum(w), FRAME_PLACE_MM[1]
            right_end = x_left - 2 * TOLERANCE_GAP_MM
        cells = _tolerance_frame(sheet, (RUNOUT_SYMBOL, format_tolerance(value, unit), "A"), w, x_left, y_bottom)
        top, x_right = y_bottom + TOLERANCE_FRAME_MM, cells[-1][2]
        if room and on_face:
            # up from the frame's right end (right of face B, so it crosses no dimension), then onto the face
            path = [(max(x_right - 2.0, face_x + 2.0), top)]
        elif room:
            path = [(min(max(target[0], cells[0][0] + 2.0), x_right - 2.0), top)]
        elif on_face:
            # below the section view, above the blank table (BLANK_BLOCK's top is 4 mm under the view)
            under, beside = (box[1] + BLANK_BLOCK[3]) / 2, face_x + 4.0
            path = [(x_right - 2.0, y_bottom), (x_right - 2.0, under), (beside, under), (beside, target[1])]
        else:
            mid = y_bottom + TOLERANCE_FRAME_MM / 2
            path = [(x_right, mid), (target[0], mid)]
        if len(path) > 1:
            sheet.line([p[0] for p in path], [p[1] for p in path], lw=0.18)
        sheet.arrow(path[-1], target)


def _frame_widths(sheet, value: str) -> tuple[float, float, float]:
    """The widths (mm) of a tolerance frame's compartments: symbol, value (its text with the cells'
    padding, measured as the tables wrap), datum letter."""
    return (TOLERANCE_FRAME_MM, sheet.width_mm(value, MIN_FONT_PT) / WRAP_FILL + 2 * PAD_MM + 1.0, TOLERANCE_FRAME_MM)


def _tolerance_frame(sheet, texts, widths, x_left: float, y_bottom: float) -> list[tuple]:
    """A feature control frame (ISO 1101): compartments of ``widths`` from ``x_left`` holding
    ``texts`` (symbol, value, datum), each text in its cell (:func:`cell_gid`); returns the cells."""
    cells, x = [], x_left
    for text, w in zip(texts, widths):
        cell = (x, y_bottom, x + w, y_bottom + TOLERANCE_FRAME_MM)
        _box(sheet, cell, lw=0.35)
        sheet.in_cell(sheet.text((cell[0] + cell[2]) / 2, (cell[1] + cell[3]) / 2, text, MIN_FONT_PT, ha="center",
                                 va="center_baseline"), cell)
        cells.append(cell)
        x += w
    return cells


def _datum(sheet, letter: str, foot, frame_centre) -> None:
    """A datum feature indicator (ISO 5459): a filled triangle standing on ``foot``, a leader to a
    square frame around ``letter`` centred at ``frame_centre``. The triangle points along the leader;
    the letter's SVG id carries its frame (:func:`cell_gid`), so a reader finds the datum there."""
    (fx, fy), (cx, cy) = foot, frame_centre
    length = math.hypot(cx - fx, cy - fy)
    ux, uy = (cx - fx) / length, (cy - fy) / length  # along the leader
    side = 3.0  # mm: the triangle's base on the feature; its height sqrt(3)/2 of it
    tip = (fx + ux * side * 0.866, fy + uy * side * 0.866)
    base = [(fx - uy * side / 2, fy + ux * side / 2), (fx + uy * side / 2, fy - ux * side / 2)]
    sheet.polygon([base[0], base[1], tip])
    half = DATUM_FRAME_MM / 2
    # the leader ends where it meets the frame's side
    reach = half / max(abs(ux), abs(uy))
    sheet.line([tip[0], cx - ux * reach], [tip[1], cy - uy * reach], lw=0.18)
    cell = (cx - half, cy - half, cx + half, cy + half)
    _box(sheet, cell, lw=0.35)
    sheet.in_cell(sheet.text(cx, cy, letter, MIN_FONT_PT, ha="center", va="center_baseline"), cell)


def dimension(sheet, p, q, text, vertical: bool) -> None:
    """A dimension line from ``p`` to ``q`` with arrows at both ends and its text beside it."""
    sheet.arrow(q, p, both=True)
    mx, my = (p[0] + q[0]) / 2, (p[1] + q[1]) / 2
    if vertical:
        sheet.text(mx - 1.0, my, text, MIN_FONT_PT, rotation=90, ha="center", va="bottom")
    else:
        sheet.text(mx, my - 1.0, text, MIN_FONT_PT, ha="center", va="top")


def _detail_view(sheet, profile, unit: str, scale: float) -> None:
    """Two teeth around the +y axis, enlarged, with the four circles named."""
    from geargen.report.labels import Obstacles, place_sheet_labels

    box = DETAIL_VIEW
    k = scale
    cx = (box[0] + box[2]) / 2
    cy = box[3] - 12.0 - profile.tip_radius * k  # the gear centre, below the window
    turn = math.pi / 2 - profile.pitch_angle / 2  # the gap between two teeth on +y
    _box(sheet, box)
    half = (box[2] - box[0]) / 2 / k  # gear mm across half the window
    n = int(math.ceil(2 * math.asin(min(1.0, half / profile.root_radius)) / profile.pitch_angle)) + 2
    from geargen.profile.segments import sample_outline
    segs = [s.rotated(turn + j * profile.pitch_angle) for j in range(-n // 2 - 1, n // 2 + 2)
            for s in profile.pitch_segments()]
    pts = sample_outline(segs, OUTLINE_STEP_MM / k)
    sheet.line(cx + pts[:, 0] * k, cy + pts[:, 1] * k, lw=0.5, clip=box)
    circles = [("d_a", profile.tip_radius, dict(lw=0.18)),
               ("d", profile.reference_radius, dict(lw=0.18, linestyle=(0, (12, 2, 1.5, 2)))),
               ("d_b", profile.base_radius, dict(lw=0.18, linestyle=(0, (3, 1.5)))),
               ("d_f", profile.root_radius, dict(lw=0.18, linestyle=(0, (1, 1))))]
    width_angle = (box[2] - box[0]) / (profile.root_radius * k)
    t = np.linspace(math.pi / 2 - width_angle, math.pi / 2 + width_angle, 721)
    labels, obstacles = [], Obstacles(boxes=[])
    for sym, r, style in circles:
        sheet.line(cx + r * k * np.cos(t), cy + r * k * np.sin(t), color="0.25", clip=box, **style)
        # anchor: the circle's point farthest right that is well inside the window
        for frac in (0.7, 0.55, 0.4, 0.25, 0.1):
            x_label = cx + frac * (box[2] - box[0]) / 2
            y = cy + math.sqrt(max((r * k) ** 2 - (x_label - cx) ** 2, 0.0))
            if box[1] + 4 < y < box[3] - 4:
                labels.append((f"{sym} ⌀{format_number(from_mm(2 * r, unit), unit)}", (x_label, y),
                               dict(size=MIN_FONT_PT, color="0.15")))
                break
        obstacles.circles.append((cx, cy, r * k))
    # the outline as an obstacle: 2 mm chords on the sheet, those inside the window
    coarse = sample_outline(segs, 2.0 / k) * k + np.array([cx, cy])
    inside = (coarse[:, 0] > box[0]) & (coarse[:, 0] < box[2]) & (coarse[:, 1] > box[1]) & (coarse[:, 1] < box[3])
    keep = inside[:-1] | inside[1:]
    obstacles.segments += [(tuple(a), tuple(b)) for a, b, ok in zip(coarse[:-1], coarse[1:], keep) if ok]
    # the labels go into the window's right part, clear of each other (hard) and of the outline (soft)
    place_sheet_labels(sheet, box, labels, obstacles, leader_from_ring=1)
    view_title(sheet, box, f"Detail: tooth form ({scale_text(scale)})")


def drawing_scales(profile) -> tuple[float, float, float]:
    """The scales of the whole gear, the axial section and the detail: the ISO 5455 scales at
    which the gear fits its views (a scale is paper length over true length, whatever the unit)."""
    spec = profile.spec
    d_a = 2 * profile.tip_radius
    length = spec.face_width + spec.hub.hub_length
    full = preferred_scale(d_a, min(FULL_VIEW[2] - FULL_VIEW[0], FULL_VIEW[3] - FULL_VIEW[1]) - 10)
    section = min(preferred_scale(d_a, SECTION_VIEW[3] - SECTION_VIEW[1] - 20),
                  preferred_scale(length, SECTION_VIEW[2] - SECTION_VIEW[0] - 34 - 6 - DATUM_ROOM_MM))
    tooth = max(2.6 * 2 * math.pi * profile.reference_radius / spec.teeth,
                1.5 * (profile.tip_radius - profile.root_radius))
    detail = preferred_scale(tooth, min(DETAIL_VIEW[2] - DETAIL_VIEW[0], 1.4 * (DETAIL_VIEW[3] - DETAIL_VIEW[1])))
    return full, section, max(detail, full)


def draw_gear(data: dict, profile, source: str, design_file: str, version: str):
    """The drawing (a :class:`Sheet`) of the gear of ``profile`` with the data ``data``."""
    unit = data["length_unit"]
    full, section, detail = drawing_scales(profile)
    scale = f"{scale_text(full)} (section {scale_text(section)}, detail {scale_text(detail)})"
    sheet = Sheet()
    draw_frame(sheet)
    _full_view(sheet, profile, full)
    _section_view(sheet, profile, unit, section, data.get("datum_tolerances"))
    _detail_view(sheet, profile, unit, detail)
    fit_data_block(sheet, data_rows(data, scale, version, source))
    draw_data_block(sheet, blank_rows(data), BLANK_BLOCK, columns=BLANK_COLUMNS_MM,
                    header=("Blank", "", "Value"))
    draw_title_block(sheet, data["name"], design_file, unit, scale, version, data.get("part_number"),
                     data.get("revision"))
    return sheet


def write_drawing(data: dict, profile, folder, name: str, source: str, design_file: str,
                  version: str | None = None) -> dict[str, Path]:
    """Draw the gear and write ``folder/name-drawing.svg`` and ``.pdf`` (:func:`write_figure`)."""
    from geargen import __version__

    return write_figure(draw_gear(data, profile, source, design_file, version or __version__), folder, name)


def write_figure(sheet: Sheet, folder, name: str) -> dict[str, Path]:
    """``folder/name-drawing.svg`` and ``.pdf`` from the one recorded ``sheet`` (atomically, folder
    created; no dates: same bytes twice); returns ``{"svg": path, "pdf": path}``."""
    from geargen.outputs import atomic_path

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    out = {}
    for fmt, encode in (("svg", sheet.svg), ("pdf", sheet.pdf)):
        path = folder / f"{name}-drawing.{fmt}"
        with atomic_path(path) as tmp:
            Path(tmp).write_bytes(encode())
        out[fmt] = path
    return out


__all__ = ["mates_from_declared", "BLANK_BLOCK", "BLANK_COLUMNS_MM", "DRAWN_TEXT_LINES", "WRAP_FILL", "title_cells", "title_cell_width",
           "blank_rows", "RUNOUT_SYMBOL", "cell_gid", "parse_cell_gid", "SHEET", "SHEET_MM", "MIN_FONT_PT", "PREFERRED_SCALES", "NOT_SPECIFIED", "Mate", "mates_from_layout",
           "mates_of", "data_rows", "format_length", "format_um", "format_tolerance", "format_limits", "preferred_scale", "scale_text",
           "drawing_scales", "pitch_row", "pitch_rows", "draw_gear", "write_drawing", "write_figure", "gear_drawings", "Sheet", "draw_frame", "draw_data_block", "fit_data_block",
           "draw_title_block", "view_title", "dimension", "outline_points", "bore_points", "centre_cross"]


def gear_drawings(data: dict, profile, folder, name: str, source: str, design_file: str) -> dict[str, Path]:
    """Every drawing file of one gear into ``folder``: ``name-drawing.svg``/``.pdf`` and the
    profile DXF ``name.dxf``; records their names in ``data["drawing"]`` (the gear data contract's
    key) before drawing, so the sheet and the JSON agree. Returns ``{"svg"|"pdf"|"dxf": path}``."""
    from geargen.report.dxf import write_profile_dxf

    folder = Path(folder)
    data["drawing"] = {"svg": f"{name}-drawing.svg", "pdf": f"{name}-drawing.pdf", "dxf": f"{name}.dxf"}
    out = write_drawing(data, profile, folder, name, source, design_file)
    out["dxf"] = write_profile_dxf(profile, folder / data["drawing"]["dxf"]).path
    return out
