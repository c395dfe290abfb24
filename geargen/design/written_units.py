"""Lengths written in the other unit: a design in inches may write ``face_width_mm`` (and one in mm
``face_width_in``); the key is read in the unit it names, as always. A warning names it when its
number reads like one in the design's own unit:

the file's typical length is the median of the sizes it wrote in its own unit; a key in the
other unit is implausible when, read in the unit it names, it lies more than a factor
:data:`FACTOR` from that typical length, while read in the design's unit it would lie within it
(a ``pinion_axial_gap_mm = 0.0625`` beside lengths of about 0.3 in: 0.0625 mm is 120 times smaller,
0.0625 in only 5 times). Tolerances, runouts, backlashes and thinnings are small by nature
(:data:`SMALL_BY_NATURE`): an STL tolerance of 0.005 mm in an inch file is not warned about.
"""

from __future__ import annotations

import math
from statistics import median
from typing import Any, Iterator, Mapping

from geargen.units import LENGTH_SUFFIXES, LENGTH_UNITS

#: how far from the file's typical length a value may lie and still read as a length of its kind
FACTOR = 10.0
#: words of keys that are small by nature (a tolerance, a runout, a backlash, a thinning): neither
#: part of the typical length nor compared with it
SMALL_BY_NATURE = ("tolerance", "tir", "backlash", "deviation", "runout", "thinning", "flank_gap", "error")


def _lengths(table: Mapping[str, Any], where: str = "") -> Iterator[tuple[str, str, float]]:
    """``(dotted key, suffix, value)`` of every mm or in size of a nested table (numbers and lists of
    them; not the keys :data:`SMALL_BY_NATURE`)."""
    for key, value in table.items():
        path = f"{where}.{key}" if where else key
        if isinstance(value, Mapping):
            yield from _lengths(value, path)
            continue
        suffix = key.rsplit("_", 1)[-1] if "_" in key else ""
        if suffix not in LENGTH_UNITS or key.endswith(("_per_in", "_per_mm")) or any(w in key for w in SMALL_BY_NATURE):
            continue
        for v in value if isinstance(value, list) else [value]:
            if not isinstance(v, (int, float)) or isinstance(v, bool):
                continue
            try:
                size = abs(float(v))
            except OverflowError:  # an integer beyond any float: the schema refuses it by its key
                continue
            if math.isfinite(size) and size != 0:
                yield path, suffix, size


def other_unit_warnings(sections: Mapping[str, Any], length_unit: str) -> list[str]:
    """A warning for each length key of ``sections`` written in the unit other than ``length_unit``
    whose number reads like one in ``length_unit`` (the module docstring says how)."""
    found = list(_lengths(sections))
    own = [v * LENGTH_SUFFIXES[s] for _, s, v in found if s == length_unit]
    if not own:
        return []
    typical = median(own)
    out = []
    for path, suffix, value in found:
        if suffix == length_unit:
            continue
        as_written = abs(math.log10(value * LENGTH_SUFFIXES[suffix] / typical))
        as_design = abs(math.log10(value * LENGTH_SUFFIXES[length_unit] / typical))
        if as_written > math.log10(FACTOR) >= as_design:
            key = path.rsplit(".", 1)[-1]
            in_design_unit = value * LENGTH_SUFFIXES[suffix] / LENGTH_SUFFIXES[length_unit]
            out.append(f"{path} = {value:g} is read in {suffix} ({in_design_unit:.4g} {length_unit}): more than "
                       f"{FACTOR:g} times from the file's typical size, {typical / LENGTH_SUFFIXES[length_unit]:.4g} "
                       f"{length_unit} (the median of its {length_unit} lengths), which {value:g} {length_unit} is "
                       f"within; if {length_unit} is meant, write {key[:-len(suffix)]}{length_unit}")
    return out
