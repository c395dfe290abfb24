"""Whether two build folders of the same design hold the same results, for a change meant not to change any.

Run by hand: ``.venv/bin/python bench/diff_builds.py BEFORE AFTER`` (two ``geargen build --out`` folders,
or two folders holding such folders by design name). Every file of either folder, in every sub-folder,
is compared, and every difference printed:

- manifest.json as values, without ``timings_s`` and ``versions`` (the build's measured seconds and the
  libraries' versions, the one thing a faster build or another environment must change), then as
  text (the same values in another order or layout are a difference too);
- every other JSON file (resolved.json, drawings/*.json) as values, then byte for byte;
- every other file byte for byte: STEP, STL, DXF, SVG, PDF, PNG, HTML, report.md, the review's files
  (a build writes no date, clock or random value into any of them: two builds of one design are
  identical, tests/test_reproducible_build.py). For a text file the first line that differs is shown.

``--rel TOL``: numbers in the JSON files that differ by at most TOL relative are listed apart (a
change that moves a root by a few ulps), not counted as differences.

Exit status 0 if all are identical (within ``--rel``), 1 otherwise.
"""

import json
import sys
from pathlib import Path

MANIFEST = "manifest.json"
IGNORED_MANIFEST_KEYS = ("timings_s", "versions")
#: files shown by their first differing line when they differ
TEXT_SUFFIXES = {".md", ".html", ".svg", ".step", ".dxf", ".js", ".css", ".txt", ".json"}


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


def _files(folder: Path) -> set[str]:
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()}


def _first_difference(x: bytes, y: bytes, text: bool) -> str:
    """Where two byte strings first differ: the byte, and for text the line on each side."""
    at = next((i for i, (p, q) in enumerate(zip(x, y)) if p != q), min(len(x), len(y)))
    where = f"{len(x)} vs {len(y)} bytes, first difference at byte {at}"
    if not text:
        return where
    line = x.count(b"\n", 0, at)
    before, after = (s.split(b"\n")[line] if line < s.count(b"\n") + 1 else b"" for s in (x, y))
    return f"{where}, line {line + 1}: {before.decode(errors='replace')[:120]!r} vs {after.decode(errors='replace')[:120]!r}"


def _json_differences(name: str, x: bytes, y: bytes, rel: float, out: list, close: list) -> None:
    """Differences of two JSON files: values first (numbers within ``rel`` into ``close``), then, when
    the values agree, the text (less the manifest's ignored keys)."""
    a, b = json.loads(x), json.loads(y)
    if name.rsplit("/", 1)[-1] == MANIFEST:
        for m in (a, b):
            for key in IGNORED_MANIFEST_KEYS:
                m.pop(key, None)
    found = list(_differences(a, b))
    close += [r for _, r in found if r is not None and r <= rel]
    out += [name + text for text, r in found if r is None or r > rel]
    if not found and json.dumps(a, indent=2) != json.dumps(b, indent=2):
        out.append(f"{name}: the same values in another order")


def diff_build(before: Path, after: Path, rel: float = 0.0) -> tuple[list[str], list[float]]:
    """The differences, and the relative differences of the numbers within ``rel``."""
    out, close = [], []
    ours, theirs = _files(before), _files(after)
    for name in sorted(ours ^ theirs):
        out.append(f"{name}: only in {'before' if name in ours else 'after'}")
    for name in sorted(ours & theirs):
        x, y = (before / name).read_bytes(), (after / name).read_bytes()
        if name.endswith(".json"):
            if x != y or name.rsplit("/", 1)[-1] == MANIFEST:
                _json_differences(name, x, y, rel, out, close)
        elif x != y:
            out.append(f"{name}: differs, {_first_difference(x, y, Path(name).suffix.lower() in TEXT_SUFFIXES)}")
    return out, close


def main(argv) -> int:
    rel = 0.0
    if argv[:1] == ["--rel"]:
        rel, argv = float(argv[1]), argv[2:]
    before, after = map(Path, argv)
    pairs = [(before, after)] if (before / MANIFEST).exists() else \
        [(f, after / f.name) for f in sorted(before.iterdir()) if (f / MANIFEST).exists()]
    bad = 0
    for a, b in pairs:
        found, close = diff_build(a, b, rel)
        within = f" ({len(close)} numbers within {rel:g} relative, the largest {max(close):.2g})" if close else ""
        print(f"{a.name}: {'identical' if not found else f'{len(found)} differences'} ({len(_files(a))} files)"
              f"{within}")
        for line in found[:40]:
            print(f"  {line}")
        bad += bool(found)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
