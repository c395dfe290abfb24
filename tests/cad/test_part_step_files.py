"""A part's STEP file (geargen.cad.assembly.part_step_files) is its solid moved into the assembly frame as
one named product (not an assembly of one component, whose product and usage the kernel names by how
many it made before): the same bytes whatever the process wrote before it, so a CAM station sees the
part alone and the file does not change with the order or the process the build writes it in."""

from pathlib import Path

import pytest

from geargen import pipeline as pl
from geargen.cad.assembly import export_step_files, part_step_files
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


def test_part_files_do_not_depend_on_what_was_written_before(split_pinion, tmp_path):
    layout, parts = split_pinion
    first = part_step_files(layout, parts, tmp_path / "first")
    # the same process, after assembly.step (its usages counted by the kernel) and in the reverse order
    later = export_step_files(layout, parts[::-1], tmp_path / "later")["parts"]
    assert set(first) == set(later) == {p.name for p in parts}
    for name, (file, entry) in first.items():
        assert (tmp_path / "first" / file).read_bytes() == (tmp_path / "later" / file).read_bytes(), name
        assert entry == later[name][1]


def test_a_part_file_is_one_named_product_in_the_assembly_frame(split_pinion, tmp_path):
    layout, parts = split_pinion
    written = part_step_files(layout, parts, tmp_path)
    for p in parts:
        text = (tmp_path / written[p.name][0]).read_text()
        assert text.count("PRODUCT(") == 1 and f"PRODUCT('{p.name}','{p.name}'" in text
        assert "NEXT_ASSEMBLY_USAGE_OCCURRENCE" not in text and "STEP translator" not in text
        back = read_step(tmp_path / written[p.name][0])
        assert back.names == [p.name]
        # the geometry moved, not copied approximately: the same solid where the assembly has it (the
        # kernel's integration to 1e-9 relative; boxes from the same faces, 1e-6 mm for the writer's digits)
        assert solid_volume(back.shape) == pytest.approx(solid_volume(p.shape), rel=1e-8)
        (lo, hi), (lo0, hi0) = bounding_box(back.shape, optimal=False), bounding_box(p.world(), optimal=False)
        assert max(abs(a - b) for a, b in zip((*lo, *hi), (*lo0, *hi0))) < 1e-6
