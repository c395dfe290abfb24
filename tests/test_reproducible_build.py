"""Two builds of one design give the same bytes, file for file, so that bench/diff_builds.py proves
"numbers do not move" exactly and a shop's revision control sees no false change (issue 26).

Nothing of the moment goes into a file: the STEP header's time_stamp and the DXF's dates are
geargen.outputs.EXPORT_DATE, the DXF's GUIDs are UUID 5s of the gear's name and of the geometry
drawn, the assembly's colour entities (listed by OCCT in the order of its shapes' memory addresses)
are put in the order of the geometry they colour, and the DXF's CLASSES (an ezdxf set, ordered by
the hash seed) are sorted. The one exception is manifest.json's ``timings_s``, the build's measured
seconds.
"""

import importlib.util
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from geargen.outputs import EXPORT_DATE

ROOT = Path(__file__).resolve().parents[1]
SPLIT = ROOT / "assemblies" / "split_pinion.toml"  # the fastest assembly to build (~5 s)
#: every kind of file a build writes: the comparison below must have met each of them
KINDS = {".step", ".stl", ".dxf", ".svg", ".pdf", ".png", ".json", ".html", ".md", ".glb", ".js", ".css", ".txt"}


def _diff_builds():
    spec = importlib.util.spec_from_file_location("diff_builds", ROOT / "bench" / "diff_builds.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _build(out: Path, seed: str, parallel: bool = True) -> subprocess.Popen:
    """``geargen build`` of the split pinion as a user runs it, or (``parallel=False``) every step in
    order in one process (pipeline.build(parallel=False): no checks, STEP or figures in processes of
    their own)."""
    env = dict(os.environ, PYTHONHASHSEED=seed)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in [env.get("PYTHONPATH")] if p])
    command = ["-m", "geargen.cli", "build", str(SPLIT), "--out", str(out), "--quiet"] if parallel else \
        ["-c", "import sys; from geargen.pipeline import build; build(sys.argv[1], sys.argv[2], quiet=True, "
               "parallel=False)", str(SPLIT), str(out)]
    return subprocess.Popen([sys.executable, *command], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def _without_timings(manifest: bytes) -> bytes:
    # the build's measured seconds, the one thing meant to change; the rest of the text compared byte for byte
    text, n = re.subn(rb'"timings_s": \{[^}]*\}', b'"timings_s": {}', manifest)
    assert n == 1
    return text


def _product_colours(path: Path) -> dict[str, list[tuple]]:
    """Product name -> the surface colours (sRGB, alpha) OCCT reads back on it or its sub-shapes."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Quantity import Quantity_ColorRGBA, Quantity_TOC_sRGB
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDF import TDF_ChildIterator, TDF_LabelSequence
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_ColorTool, XCAFDoc_ColorType, XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    reader = STEPCAFControl_Reader()
    reader.SetColorMode(True)
    reader.SetNameMode(True)
    assert reader.ReadFile(str(path)) == IFSelect_RetDone and reader.Transfer(doc)
    labels = TDF_LabelSequence()
    XCAFDoc_DocumentTool.ShapeTool_s(doc.Main()).GetShapes(labels)
    out = {}
    for i in range(labels.Length()):
        label, name, colour = labels.Value(i + 1), TDataStd_Name(), Quantity_ColorRGBA()
        if not label.FindAttribute(TDataStd_Name.GetID_s(), name):
            continue
        under, it = [label], TDF_ChildIterator(label, True)
        while it.More():
            under.append(it.Value())
            it.Next()
        out[name.Get().ToExtString()] = [
            (*colour.GetRGB().Values(Quantity_TOC_sRGB), colour.Alpha()) for lab in under
            if XCAFDoc_ColorTool.GetColor_s(lab, XCAFDoc_ColorType.XCAFDoc_ColorSurf, colour)]
    return out


@pytest.fixture(scope="module")
def two_builds(tmp_path_factory) -> tuple[Path, Path]:
    root = tmp_path_factory.mktemp("twice")
    folders = root / "first", root / "second"
    # other hash seeds, other addresses; the second in one process, in order (the first writes its STEP files,
    # checks and figures in processes of their own: the same bytes either way)
    runs = [_build(folder, seed, parallel) for folder, seed, parallel in zip(folders, ("1", "2"), (True, False))]
    for run in runs:
        _, err = run.communicate(timeout=600)
        assert run.returncode == 0, err
    return folders


def test_two_builds_are_byte_identical_file_for_file(two_builds):
    first, second = two_builds
    names = sorted(p.relative_to(first).as_posix() for p in first.rglob("*") if p.is_file())
    assert names == sorted(p.relative_to(second).as_posix() for p in second.rglob("*") if p.is_file())
    assert {Path(n).suffix for n in names} == KINDS  # every kind of file a build writes was compared
    differ = []
    for name in names:
        x, y = (first / name).read_bytes(), (second / name).read_bytes()
        if name == "manifest.json":
            x, y = _without_timings(x), _without_timings(y)
        if x != y:
            differ.append(name)
    assert differ == []
    found, close = _diff_builds().diff_build(first, second)
    assert found == [] and close == []


def test_headers_carry_the_fixed_date_not_the_clock(two_builds):
    import ezdxf
    from ezdxf.tools.juliandate import calendardate
    first, _ = two_builds
    for step in sorted(first.glob("*.step")):
        head = step.read_bytes()[:400].decode()
        assert f"FILE_NAME('Open CASCADE Shape Model','{EXPORT_DATE}'" in head, step.name
    dxfs = sorted(first.glob("drawings/*.dxf"))
    assert len(dxfs) == 3  # the output gear and the two pinions
    fingerprints = set()
    for path in dxfs:
        text = path.read_text()
        doc = ezdxf.readfile(path)
        for name in ("$TDUPDATE", "$TDUCREATE", "$TDUUPDATE"):
            assert calendardate(doc.header[name]).isoformat() == EXPORT_DATE, (path.name, name)
        assert re.search(r"\$TDCREATE\n 40\n2440588\.0\n", text)  # the Julian day of 1970-01-01 00:00
        assert f"@ {EXPORT_DATE}+00:00" in text and "@ 20" not in text  # ezdxf's marker, without the clock
        fingerprints.add(doc.header["$FINGERPRINTGUID"])
    assert len(fingerprints) == 3  # one identity per gear


def test_the_assemblys_colours_survive_the_reordering(two_builds):
    """Each product of assembly.step reads back with the colour its parts have in the manifest:
    renumbering the colour entities kept which colour is on which solid."""
    first, _ = two_builds
    parts = json.loads((first / "manifest.json").read_text())["parts"]
    colours = _product_colours(first / "assembly.step")
    products = [name for name in parts if name in colours]
    assert len(products) >= 10  # parts alike share one product: 12 of split_pinion's 14 parts are products
    for name in products:
        assert colours[name], name
        # float32 in the file (~6e-8) and the sRGB round trip inside OCCT: 1e-6
        assert colours[name][0] == pytest.approx(tuple(parts[name]["colour_rgba"]), abs=1e-6), name


HEAD = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('x'),'2;1');
ENDSEC;
DATA;
#1 = CARTESIAN_POINT('',(0.,0.,0.));
#2 = CARTESIAN_POINT('',(1.,0.,0.));
#3 = GEOMETRIC_REPRESENTATION_CONTEXT(3);
"""
END = "ENDSEC;\nEND-ISO-10303-21;\n"
# the colours of points #1 and #2 (sharing one COLOUR_RGB), in the order of the geometry
CANONICAL = HEAD + """#4 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(#5),#3);
#5 = STYLED_ITEM('#9 stays',(#6),#1);
#6 = FILL_AREA_STYLE_COLOUR('',#7);
#7 = COLOUR_RGB('',0.5,0.25,0.125);
#8 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(#9),#3);
#9 = STYLED_ITEM('color',(#10),#2);
#10 = FILL_AREA_STYLE_COLOUR('',#7);
""" + END
# the same, as the kernel may write it when #2's representation comes first in its map (a record wrapped)
SWAPPED = HEAD + """#4 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(
    #5),#3);
#5 = STYLED_ITEM('color',(#6),#2);
#6 = FILL_AREA_STYLE_COLOUR('',#7);
#7 = COLOUR_RGB('',0.5,0.25,0.125);
#8 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(#9),#3);
#9 = STYLED_ITEM('#9 stays',(#10),#1);
#10 = FILL_AREA_STYLE_COLOUR('',#7);
""" + END


def test_colour_entities_in_either_order_come_out_the_same():
    from geargen.cad.export import canonical_styles
    assert canonical_styles(CANONICAL.encode()) == CANONICAL.encode()
    assert canonical_styles(SWAPPED.encode()) == CANONICAL.encode()  # a string's '#9' is text, not renumbered
    plain = (HEAD + END).encode()
    assert canonical_styles(plain) == plain  # no colours: as it is
    # two colours on one solid (parts sharing a shape, coloured apart): ordered by their content
    one = HEAD + """#4 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(#5),#3);
#5 = STYLED_ITEM('color',(#6),#1);
#6 = COLOUR_RGB('',{},0.5,0.5);
#7 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(#8),#3);
#8 = STYLED_ITEM('color',(#9),#1);
#9 = COLOUR_RGB('',{},0.5,0.5);
""" + END
    light_first, dark_first = one.format(0.75, 0.25).encode(), one.format(0.25, 0.75).encode()
    assert canonical_styles(light_first) == canonical_styles(dark_first) == dark_first
    # an earlier entity referring into the colours is no file the kernel writes: left alone, not reordered wrongly
    odd = SWAPPED.replace("#3 = GEOMETRIC_REPRESENTATION_CONTEXT(3);", "#3 = GEOMETRIC_REPRESENTATION_CONTEXT(#9);")
    assert canonical_styles(odd.encode()) == odd.encode()
    # an earlier string naming '#9' is text (the fast search finds it, the exact scan sets it aside): reordered
    quoted = "#1 = CARTESIAN_POINT('see #9',(0.,0.,0.));"
    assert canonical_styles(SWAPPED.replace("#1 = CARTESIAN_POINT('',(0.,0.,0.));", quoted).encode()) == \
        CANONICAL.replace("#1 = CARTESIAN_POINT('',(0.,0.,0.));", quoted).encode()


def test_dxf_version_guid_follows_the_geometry_and_the_fingerprint_the_name(tmp_path):
    import math

    import ezdxf

    from geargen.design.gear import GearSpec, Hub
    from geargen.profile.tooth import tooth_profile
    from geargen.report.dxf import write_profile_dxf

    def guids(teeth, name):
        spec = GearSpec(teeth=teeth, module=1.0, pressure_angle=math.radians(20), face_width=5.0,
                        hub=Hub(bore_diameter=4.0), name=name)
        path = write_profile_dxf(tooth_profile(spec), tmp_path / f"{name}-{teeth}.dxf").path
        header = ezdxf.readfile(path).header
        return header["$FINGERPRINTGUID"], header["$VERSIONGUID"], path.read_bytes()

    a = guids(20, "pinion")
    assert guids(20, "pinion") == a  # written again: the same bytes
    b = guids(21, "pinion")
    assert b[0] == a[0] and b[1] != a[1]  # another outline: the same drawing, a new revision
    c = guids(20, "wheel")
    assert c[0] != a[0] and c[1] == a[1]  # the same outline under another name: another drawing
