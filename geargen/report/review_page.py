"""The browser design review of a build: ``review/index.html``, opening offline from the folder.

The page shows the assembly (a GLB, :mod:`geargen.cad.gltf`) in three.js, a part tree to hide and
isolate parts, a section plane, the mesh-check numbers of a gear or mesh on hover or click and
the report's sections as tables. Chromium loads neither ES modules nor ``fetch()`` from
``file://``, so everything reaches the page as classic scripts beside it: ``model.js`` (the GLB
as base64), ``data.js`` (the numbers), the vendored three.js bundle (``viewer/``, rebuilt by
``tools/viewer-bundle``) and the page's own ``review.js``. ``assembly.glb`` is written too, for
other viewers. The numbers are the build's: the mesh checks as ``manifest.json`` records them
and the report's blocks (:class:`geargen.report.review.Review`), so the page, the manifest and
the report cannot disagree. Files are written plainly: the build writes into a temporary folder
that replaces the export folder at the end.
"""

from __future__ import annotations

import base64
import html
import json
import re
from pathlib import Path
from typing import Any

from geargen.report.review import Review, table_cell
from geargen.units import LENGTH_SUFFIXES

VIEWER = Path(__file__).parent / "viewer"
#: the page's files copied from the package, by manifest role
VIEWER_FILES = {"review_library": "three-bundle.min.js", "review_library_licence": "three-LICENSE.txt",
                "review_script": "review.js", "review_style": "review.css"}
#: the report's key sections, shown first and unfolded, in this order
_KEY = [re.compile(r"key numbers", re.IGNORECASE), re.compile(r"check|backlash", re.IGNORECASE), re.compile(r"stiffness", re.IGNORECASE),
        re.compile(r"synthesis", re.IGNORECASE), re.compile(r"load capacity", re.IGNORECASE)]


def sections(review: Review) -> list[dict[str, Any]]:
    """The report's blocks without its images, grouped under their headings: ``[{"title", "open",
    "blocks": [{"kind": "table", "header", "rows"} | {"kind": "pre"|"p"|"h3", "text"} | {"kind": "list",
    "items"}]}]``; table cells as the report prints them (a sub-heading "h3" shows as a paragraph).
    The report's opening paragraphs come first, then its key numbers, checks, stiffness and
    synthesis (unfolded), then the rest in its order."""
    out: list[dict[str, Any]] = [{"title": "Summary", "open": True, "blocks": []}]
    for kind, payload in review.blocks:
        if kind == "h2":
            out.append({"title": payload, "open": any(k.search(payload) for k in _KEY), "blocks": []})
        elif kind == "table":
            header, rows = payload
            out[-1]["blocks"].append({"kind": "table", "header": [str(h) for h in header],
                                      "rows": [[table_cell(c) for c in r] for r in rows]})
        elif kind == "list":
            out[-1]["blocks"].append({"kind": "list", "items": [str(i) for i in payload]})
        elif kind in ("p", "pre", "h3"):
            out[-1]["blocks"].append({"kind": kind, "text": str(payload)})
    rank = [next((i for i, k in enumerate(_KEY) if k.search(s["title"])), len(_KEY)) for s in out[1:]]
    ordered = [out[0]] + [s for _, s in sorted(zip(rank, out[1:]), key=lambda pair: pair[0])]
    return [s for s in ordered if s["blocks"]]


def page_data(result: Any, checks: dict[str, Any], review: Review) -> dict[str, Any]:
    """What ``data.js`` gives the page: the build's parts (``result.parts.parts``, read by
    attribute), its mesh checks as the manifest records them (``checks``: lengths in mm) and the
    report's sections."""
    design = result.design
    return {"title": review.title, "design": design.name, "status": review.status,
            "length_unit": design.length_unit, "mm_per_unit": LENGTH_SUFFIXES[design.length_unit],
            "backlash_kind": checks["backlash_kind"],
            "parts": [{"name": p.name, "group": p.group, "kind": p.kind, "role": p.role, "description": p.description}
                      for p in result.parts.parts],
            "meshes": checks["meshes"], "tolerances": checks["tolerances"], "sections": sections(review)}


def index_html(title: str, status: str) -> str:
    e = html.escape
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{e(title)}</title>
<link rel="stylesheet" href="review.css">
</head>
<body data-loaded="false" data-parts="0">
<header><h1>{e(title)}</h1><span class="{e(status)}">{e(status)}</span>
<span>drag: orbit, wheel: zoom, right-drag: pan; click a part or a mesh for its numbers</span></header>
<main>
<section id="left">
<h2>Parts <button id="show-all">show all</button> <button id="isolate-selection">isolate selected</button>
<button id="frame">frame</button></h2>
<div id="tree"></div>
<h2>Meshes (backlash, exact outlines)</h2>
<div id="meshes"></div>
<h2>Section</h2>
<div id="section">
<label>plane normal to <select id="section-axis"><option value="none">no section</option>
<option value="x">x</option><option value="y">y</option><option value="z">z</option></select></label>
<input id="section-pos" type="range" min="0" max="1000" value="500" disabled>
<label><input id="section-flip" type="checkbox"> keep the other side</label>
<div id="section-value"></div>
</div>
</section>
<section id="centre"><div id="viewport"></div><div id="info"></div><div id="tooltip" hidden></div></section>
<section id="right"><div id="tables"></div></section>
</main>
<script src="three-bundle.min.js"></script>
<script src="data.js"></script>
<script src="model.js"></script>
<script src="review.js"></script>
</body></html>
"""


def _script(variable: str, value: Any) -> str:
    return f"window.{variable} = {json.dumps(value, allow_nan=False, separators=(',', ':'))};\n"


def write_review_page(folder: str | Path, glb: bytes, data: dict[str, Any]) -> dict[str, Path]:
    """Write the page into ``folder`` (created): index.html, data.js, model.js, assembly.glb and
    the viewer's files; returns them by manifest role."""
    folder = Path(folder)
    folder.mkdir(exist_ok=True)
    files = {"review_page": folder / "index.html", "review_data": folder / "data.js",
             "review_model": folder / "model.js", "review_glb": folder / "assembly.glb"}
    from geargen.outputs import write_file
    write_file(files["review_page"], index_html(data["title"], data["status"]))
    write_file(files["review_data"], _script("GEARGEN_REVIEW", data))
    write_file(files["review_model"], _script("GEARGEN_MODEL", {"name": data["design"], "glb_base64":
                                                                base64.b64encode(glb).decode("ascii")}))
    write_file(files["review_glb"], glb)
    for role, name in VIEWER_FILES.items():
        files[role] = write_file(folder / name, (VIEWER / name).read_bytes())
    return files


def read_script(path: str | Path) -> Any:
    """The value a ``data.js``/``model.js`` of :func:`write_review_page` sets (for tests and tools)."""
    text = Path(path).read_text(encoding="utf-8")
    return json.loads(text[text.index("=") + 1:].strip().rstrip(";"))


__all__ = ["sections", "page_data", "index_html", "write_review_page", "read_script", "VIEWER", "VIEWER_FILES"]
