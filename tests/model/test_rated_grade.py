"""A drive gear is drawn to the accuracy its load capacity was rated at (issue 27: the drawing is
what the shop makes; issue 29: the rating's K_v, K_Hbeta and K_Halpha assume the [duty] grade).

split_pinion_inch states ``[duty] accuracy_grade = 5`` and gives its gears no grade of their own:
before, pinion_stiff's drawing said "Accuracy grade: not specified" while the rating assumed grade 5.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from geargen.core.accuracy import iso1328_tolerances
from geargen.design.assembly import design_from_dict
from geargen.drives.resolver import resolve
from geargen.pipeline import drive_gear_data
from geargen.profile.tooth import tooth_profile

ROOT = Path(__file__).resolve().parents[2]
DESIGN = ROOT / "assemblies" / "split_pinion_inch.toml"


def _gear_data(text: str, gear: str) -> dict:
    design = design_from_dict(tomllib.loads(text))
    layout = resolve(design)
    spec = next(p.spec for p in layout.gears if p.name == gear)  # as placed (thinned to its allowance)
    return drive_gear_data(layout, spec, tooth_profile(spec, warn=False), None)


def test_a_gear_without_a_grade_is_drawn_to_the_rated_grade():
    text = DESIGN.read_text()
    assert "accuracy_grade = 5" in text  # the design's [duty] grade
    data = _gear_data(text, "pinion_stiff")
    acc = data["accuracy"]
    assert acc["grade"] == 5 and "[duty] accuracy_grade" in acc["grade_source"]
    # the tolerances are ISO 1328-1's of grade 5 for this gear (the same table the rating reads)
    spec_d = 2 * data["reference_radius"] * 25.4  # the JSON is in the design's unit (in)
    ref = iso1328_tolerances(5, spec_d, 25.4 / 20, 0.5 * 25.4).to_dict()
    assert {k: acc[k] for k in ref if k != "grade_source"} == {k: ref[k] for k in ref if k != "grade_source"}


def test_without_a_rating_in_force_the_budget_grade_stands():
    # no [duty] and no [materials]: the rating is a note, the drawing keeps what the budget holds
    text = DESIGN.read_text()
    start = text.index("[duty]")
    end = text.find("\n[", start + 1)
    text = text[:start] + (text[end + 1:] if end >= 0 else "")
    data = _gear_data(text, "pinion_stiff")
    assert "[duty]" not in data.get("accuracy", {}).get("grade_source", "")


def test_a_gear_with_its_own_grade_keeps_it():
    text = re.sub(r"(?m)^(\[gears\.pinion_stiff\].*)$", r"\1\naccuracy_grade = 8", DESIGN.read_text(), count=1)
    assert "accuracy_grade = 8" in text
    data = _gear_data(text, "pinion_stiff")
    assert data["accuracy"]["grade"] == 8 and data["accuracy"]["grade_source"] == "the design's accuracy_grade"
