"""Reading a gear drawing's tables back from its SVG: each table text's group id carries its cell
(geargen.report.drawing.cell_gid), so a row is found by its cells whatever its text wraps to."""

import xml.etree.ElementTree as ET

from geargen.report.drawing import parse_cell_gid

SVG = "{http://www.w3.org/2000/svg}"


def cell_texts(svg_path) -> dict[tuple[float, float, float, float], list[str]]:
    """{cell (x0, y0, x1, y1) mm: [its texts, top to bottom]} of the SVG."""
    out = {}
    for g in ET.parse(svg_path).getroot().iter(f"{SVG}g"):
        cell = parse_cell_gid(g.get("id"))
        if cell is not None:
            out.setdefault(cell, []).extend("".join(t.itertext()) for t in g.iter(f"{SVG}text"))
    return out


def table_rows(cells, box, join: str = " ") -> dict[str, str]:
    """{name: value} of a table in ``box``: the cells in it grouped by row, first column the name,
    last the value, wrapped lines joined with ``join`` (a value broken inside a word: "")."""
    rows = {}
    inside = {c: t for c, t in cells.items() if box[0] - 1e-3 <= c[0] and c[2] <= box[2] + 1e-3
              and box[1] - 1e-3 <= c[1] and c[3] <= box[3] + 1e-3}
    for c, texts in inside.items():
        if abs(c[0] - box[0]) < 1e-3:
            value = next((join.join(t) for cc, t in inside.items() if abs(cc[2] - box[2]) < 1e-3 and cc[1] == c[1]
                          and cc[3] == c[3]), "")
            rows[" ".join(texts)] = value
    return rows


def tolerance_frames(cells, symbol: str) -> list[tuple[tuple, str, str]]:
    """The feature control frames of the sheet whose first compartment holds ``symbol``: each as
    (its symbol cell, its value text, its datum letter), from the compartments in line to its right."""
    out = []
    for c, texts in cells.items():
        if texts == [symbol]:
            row = sorted((cc for cc in cells if cc[1] == c[1] and cc[3] == c[3] and cc[0] >= c[2] - 1e-3
                          and cc[0] - c[2] < 60), key=lambda cc: cc[0])
            value, datum = row[0], row[1]
            assert abs(value[0] - c[2]) < 1e-3 and abs(datum[0] - value[2]) < 1e-3  # adjoining compartments
            out.append((c, " ".join(cells[value]), " ".join(cells[datum])))
    return out
