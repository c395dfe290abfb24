"""Whether two build folders of the same design hold the same results, for a change meant not to change any.

Run by hand: ``.venv/bin/python bench/diff_builds.py BEFORE AFTER`` (two ``geargen build --out`` folders,
or two folders holding such folders by design name). Compares, and prints every difference:

- manifest.json without ``timings_s`` and ``versions`` (checks, parts, volumes, placements, files
  and their sizes: a STEP file's timestamp has a fixed length);
- resolved.json;
- report.md, with its timings lines left out, its text exactly, and its figures' PNG files
  (``figures/*.png``) byte for byte;
- every STL file byte for byte (STEP files carry a timestamp: their size is compared in the manifest).

``--rel TOL``: numbers in the JSON files that differ by at most TOL relative are listed apart (a
change that moves a root by a few ulps), not counted as differences.

Exit status 0 if all are identical (within ``--rel``), 1 otherwise.
"""

import json
import sys
from pathlib import Path

IGNORED_MANIFEST_KEYS = ("timings_s", "versions")


def _relative(a, b) -> float:
    return abs(a - b) / max(abs(a), abs(b))


def _differences(a, b, where: str = ""):
    """(path, relative difference or None) where two JSON values differ (floats compared exactly)."""
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                yield f"{where}/{key}: only in {'after' if key in b else 'before'}", None
            else:
                yield from _differences(a[key], b[key], f"{where}/{key}")
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            yield from _differences(x, y, f"{where}[{i}]")
    elif a != b:
        numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b))
        yield f"{where}: {a!r} != {b!r}", _relative(a, b) if numbers else None


def _report_lines(folder: Path) -> list[str]:
    # the report's own timing table is the one thing a faster build must change
    return [line for line in (folder / "report.md").read_text().splitlines() if "timing" not in line.lower()
            and " s |" not in line]


def diff_build(before: Path, after: Path, rel: float = 0.0) -> tuple[list[str], list[float]]:
    """The differences, and the relative differences of the numbers within ``rel``."""
    out, close = [], []
    m1, m2 = (json.loads((f / "manifest.json").read_text()) for f in (before, after))
    for m in (m1, m2):
        for key in IGNORED_MANIFEST_KEYS:
            m.pop(key, None)
    # the report's size follows its timing lines
    for m in (m1, m2):
        for name in ("report.md", "report.html"):
            m["files"].get(name, {}).pop("bytes", None)
    r1, r2 = (json.loads((f / "resolved.json").read_text()) for f in (before, after))
    for name, x, y in (("manifest.json", m1, m2), ("resolved.json", r1, r2)):
        for text, r in _differences(x, y):
            if r is not None and r <= rel:
                close.append(r)
            else:
                out.append(name + text)
    l1, l2 = _report_lines(before), _report_lines(after)
    if l1 != l2:
        changed = [i for i, (x, y) in enumerate(zip(l1, l2)) if x != y]
        out.append(f"report.md: {len(l1)} vs {len(l2)} lines, {len(changed)} differ, the first: "
                   f"{l1[changed[0]] if changed else 'beyond the shorter'!r}")
    for png in sorted(before.glob("figures/*.png")):
        other = after / "figures" / png.name
        if not other.exists() or png.read_bytes() != other.read_bytes():
            out.append(f"figures/{png.name}: differs")
    for stl in sorted(before.glob("*.stl")):
        other = after / stl.name
        if not other.exists() or stl.read_bytes() != other.read_bytes():
            out.append(f"{stl.name}: differs")
    return out, close


def main(argv) -> int:
    rel = 0.0
    if argv[:1] == ["--rel"]:
        rel, argv = float(argv[1]), argv[2:]
    before, after = map(Path, argv)
    pairs = [(before, after)] if (before / "manifest.json").exists() else \
        [(f, after / f.name) for f in sorted(before.iterdir()) if (f / "manifest.json").exists()]
    bad = 0
    for a, b in pairs:
        found, close = diff_build(a, b, rel)
        within = f" ({len(close)} numbers within {rel:g} relative, the largest {max(close):.2g})" if close else ""
        print(f"{a.name}: {'identical' if not found else f'{len(found)} differences'}{within}")
        for line in found[:40]:
            print(f"  {line}")
        bad += bool(found)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
