"""A part's STEP file (geargen.cad.assembly.part_step_files): the part placed in the assembly frame, every
product in it named after the part (the kernel names a placed shape's unplaced self "Open CASCADE STEP
translator 7.9 <n>.1" unless told, n counting its earlier transfers: a component a CAM station lists)."""

from pathlib import Path

import pytest

from geargen import pipeline as pl
from geargen.cad.assembly import part_step_files
from geargen.cad.export import read_step
from geargen.cad.gear_solid import solid_volume
from geargen.cad.parts import bounding_box

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def split_pinion():
    layout = pl.place(pl.load(ROOT / "assemblies" / "split_pinion.toml"))
    gears = pl.gear_solids(layout)
    return layout, pl.other_parts(layout, gears, pl.stiffness(layout)).parts


def test_a_part_file_names_every_product_after_the_part_in_the_assembly_frame(split_pinion, tmp_path):
    layout, parts = split_pinion
    written = part_step_files(layout, parts, tmp_path)
    placed = 0
    for p in parts:
        text = (tmp_path / written[p.name][0]).read_text()
        products = text.count("PRODUCT(")
        assert products == text.count(f"PRODUCT('{p.name}','{p.name}'") >= 1, p.name
        assert "STEP translator" not in text
        placed += products == 2  # a placed part: itself, and its unplaced self as the one component
        back = read_step(tmp_path / written[p.name][0])
        assert back.names == [p.name]
        # where the assembly has it: the kernel's integration to 1e-9 relative, boxes from the same faces
        # (1e-6 mm for the writer's digits)
        assert solid_volume(back.shape) == pytest.approx(solid_volume(p.shape), rel=1e-8)
        (lo, hi), (lo0, hi0) = bounding_box(back.shape, optimal=False), bounding_box(p.world(), optimal=False)
        assert max(abs(a - b) for a, b in zip((*lo, *hi), (*lo0, *hi0))) < 1e-6
    assert placed > 0  # the case the naming is for occurs in this drive
