"""One home for every length: the solids and the stiffness read the same placed shafts.

Moving the bearings in the design file ([parts] bearing_clearance) moves the bearing solids and
changes the computed shaft stiffness, and the stiffness is the closed form of the beam measured
on the solids themselves (bearing mid-widths and the gear's mid-face from the bodies' extents).
"""

import math
from pathlib import Path

import pytest

from geargen.design.assembly import load_design
from geargen.drives import resolve
from geargen.model.analysis import stiffness

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
IN = 25.4


def _design(tmp_path, clearance_in: float):
    text = (ROOT / "assemblies/robot_joint.toml").read_text()
    old = "bearing_clearance_in = 0.02 "
    assert old in text
    path = tmp_path / f"robot_joint_{clearance_in}.toml"
    text = text.replace(old, f"bearing_clearance_in = {clearance_in} ")
    # the carriage arm rises with the clearance, and the bevel gear's back must clear it by the
    # clearance: the bevel heel goes up by twice the change (geargen.cad.assembly._bevel_drive)
    bevel = "input_shaft_to_bevel_in = 0.525 "
    assert bevel in text
    text = text.replace(bevel, f"input_shaft_to_bevel_in = {0.525 + 2 * (clearance_in - 0.02):.6g} ")
    path.write_text(text)
    return load_design(path)


def _z_extent(part) -> tuple[float, float]:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    BRepBndLib.Add_s(part.world(), box, False)
    box.SetGap(0.0)
    _, _, z0, _, _, z1 = box.Get()
    return z0, z1


def _placed(design, gears=None, position=None):
    """(layout, stiffness summary, PartSet) of a design: the resolved drive (at ``position``, else
    the file's) and its non-gear parts (with ``gears``, the gear parts too)."""
    from geargen.pipeline import other_parts
    layout = resolve(design, position)
    summary, _ = stiffness(design, layout)
    return layout, summary, other_parts(layout, gears, summary)


def _measured(design):
    """(span, load position from the lower support) of cluster A's shaft measured on the built
    bearing and gear solids (mm), the summary's cluster_support component, the summary, the parts;
    the placed component spec's other load is checked to sit at the large gear's measured mid-face."""
    from geargen.model.analysis import placed_components
    layout, summary, part_set = _placed(design)
    parts = {p.name: p for p in part_set.parts}
    lo = sum(_z_extent(parts["cluster_bearing_lower_a"])) / 2
    hi = sum(_z_extent(parts["cluster_bearing_upper_a"])) / 2
    small, large = (layout.gear(n) if n in {g.name for g in layout.gears} else layout.gear("cluster_a")
                    for n in ("cluster_small_a", "cluster_large_a"))
    z_small = sum(small.face_z(small.gears[-1])) / 2
    z_large = sum(large.face_z(large.gears[0])) / 2
    comp = next(c for c in summary.components if c.name == "cluster_support")
    spec = next(c for c in placed_components(design, layout) if c.name == "cluster_support")
    ((z_other, _, _),) = spec.other_loads
    assert z_other == pytest.approx(z_large - lo, abs=1e-9)
    return hi - lo, z_small - lo, comp, summary, parts, spec


def _support_compliance(influence, spec) -> float:
    """The work of the gear's unit mesh force and the shaft's other mesh force (share and angle as
    placed) through the shaft's displacement ``influence(load, at)``, mm/N."""
    loads = [(spec.load_position, 1.0, 0.0), *spec.other_loads]
    return sum(f * g * math.cos(t - u) * influence(z, y) for z, f, t in loads for y, g, u in loads)


def test_moving_the_bearings_moves_the_solids_and_changes_the_stiffness(tmp_path):
    span0, a0, comp0, s0, parts0, spec0 = _measured(_design(tmp_path, 0.02))
    span1, a1, comp1, s1, parts1, spec1 = _measured(_design(tmp_path, 0.06))
    # the solids moved: each cluster bearing 0.04 in further from the gear faces
    dz_lo = _z_extent(parts1["cluster_bearing_lower_a"])[0] - _z_extent(parts0["cluster_bearing_lower_a"])[0]
    dz_hi = _z_extent(parts1["cluster_bearing_upper_a"])[0] - _z_extent(parts0["cluster_bearing_upper_a"])[0]
    assert dz_lo == pytest.approx(-0.04 * IN, abs=1e-6) and dz_hi == pytest.approx(0.04 * IN, abs=1e-6)
    assert span1 - span0 == pytest.approx(0.08 * IN, abs=1e-6)
    # the stiffness is the simply supported beam of the solids' span and load positions on two
    # 10 N/um bearings (closed form: beam on rigid supports + the bearings through their levers),
    # under the small gear's mesh force and the large gear's
    E, kb = 207e3, 10e3
    ei = E * math.pi * (0.25 * IN) ** 4 / 64
    for span, a, comp, spec in ((span0, a0, comp0, spec0), (span1, a1, comp1, spec1)):
        assert spec.span == pytest.approx(span, abs=1e-9) and spec.load_position == pytest.approx(a, abs=1e-9)

        def influence(load, at, span=span):
            if at > load:  # mirrored: the point on the near side of the load
                load, at = span - load, span - at
            b = span - load
            return b * at * (span ** 2 - b ** 2 - at ** 2) / (6 * ei * span) + ((span - load) * (span - at)
                                                                                 + load * at) / span ** 2 / kb
        b = span - a
        alone = a * a * b * b / (3 * ei * span) + ((b / span) ** 2 + (a / span) ** 2) / kb
        assert influence(a, a) == pytest.approx(alone, rel=1e-12)
        assert comp.local == pytest.approx(1 / _support_compliance(influence, spec), rel=1e-9)
    # and it moved: under one force a longer span is softer, but the two mesh forces nearly oppose
    # (a couple), and a wider bearing base carries a couple with smaller reactions: here the two
    # effects about cancel (+0.04 %); the path follows the component
    assert comp1.local != pytest.approx(comp0.local, rel=1e-4)
    assert (s1.drive.k1 - s0.drive.k1) * (comp1.local - comp0.local) > 0
    # the built geometry the reviewer measured: 0.80 in span, the small gear 0.52 in from a bearing
    assert span0 / IN == pytest.approx(0.7985, abs=1e-9) and a0 / IN == pytest.approx(0.52425, abs=1e-9)


def test_c_axis_pinion_overhung_on_its_quill_bearings():
    """The C-axis dual pinion sits 53.5 mm beyond the upper of two 150 N/um bearings 30 mm apart
    (measured on the solids): about 12 N/um at the pinion under its own force (the reviewer's
    number), not the 300 N/um of two bearings in parallel. The large gear's mesh force on the same
    shaft (18.5 mm out, 0.42 of it, its line of action 136 deg away) holds the shaft back: 16 N/um
    for the path, each path about 3.1e5 N m/rad (was 2.39e6 in the first round), and 68 um of
    misalignment across the 30 mm face at the preload (78 um under the pinion's force alone)."""
    from geargen.core.stiffness import supported_shaft_compliance
    span, load, comp, summary, _, spec = _measured(load_design(ROOT / "assemblies/c_axis.toml"))
    c = load - span  # overhang beyond the upper support
    assert span == pytest.approx(30.0, abs=1e-6) and c == pytest.approx(53.5, abs=1e-6)
    E, kb, d = 207e3, 150e3, 30.0
    ei = E * math.pi * d ** 4 / 64

    def influence(load, at):  # both beyond the upper support: rigid supports, plus the bearings' levers
        near, far = sorted((load - span, at - span))
        beam = near * near * (span + near) / (3 * ei) + near * (2 * span + 3 * near) / (6 * ei) * (far - near)
        u_hi, u_lo = load / span / kb, (span - load) / span / kb
        return beam + u_lo + (u_hi - u_lo) * at / span
    alone = c * c * (span + c) / (3 * ei) + (((span + c) / span) ** 2 + (c / span) ** 2) / kb
    assert influence(load, load) == pytest.approx(alone, rel=1e-12)
    assert 1 / supported_shaft_compliance(E, d, span, load, (kb, kb))[0] / 1e3 == pytest.approx(12.1, abs=0.1)
    assert comp.local == pytest.approx(1 / _support_compliance(influence, spec), rel=1e-9)
    assert comp.local / 1e3 == pytest.approx(16.0, abs=0.1)  # N/um
    assert summary.drive.k1 / 1e3 == pytest.approx(3.11e5, rel=0.01)  # N m/rad
    (sup,) = [x for x in summary.supports if x.component == "cluster_support"]
    # tilt at the overhang's end: rigid-body rotation on the bearings plus the beam's slope, and the
    # same of the large gear's force (nearer: the shaft runs straight beyond it) projected on the pinion's
    ((z_l, share, angle),) = spec.other_loads
    c_l = z_l - span

    def tilt(c):
        return (span + 2 * c) / (span ** 2 * kb) + c * (2 * span + 3 * c) / (6 * ei)
    assert sup.tilt == pytest.approx(sup.force * (tilt(c) + share * math.cos(angle) * tilt(c_l)), rel=1e-9)
    assert sup.misalignment * 1e3 == pytest.approx(67.6, abs=0.1)  # um across the 30 mm face
    assert any("misalignment" in w for w in summary.warnings)


def _box(part) -> tuple[float, ...]:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    BRepBndLib.Add_s(part.world(), box, False)
    box.SetGap(0.0)
    return box.Get()


@pytest.mark.parametrize("thickness_mm", [30, 45])
def test_the_c_axis_drive_column_is_in_the_preload_spring(tmp_path, thickness_mm):
    """The long pinion's bearings sit on the drive column: its solid and k3 read the same column.
    A thicker column is a thicker solid and a stiffer preload spring, each bearing carried by the
    column as a cantilever from the housing block's nearer face (3 E I / h^3, measured on the
    solids), in series with the beam through its reactions."""
    text = (ROOT / "assemblies/c_axis.toml").read_text()
    old = "drive_column_thickness_mm = 30\n"
    assert old in text
    path = tmp_path / f"c_axis_{thickness_mm}.toml"
    path.write_text(text.replace(old, f"drive_column_thickness_mm = {thickness_mm}\n"))
    layout, summary, part_set = _placed(load_design(path))
    parts = {p.name: p for p in part_set.parts}
    col, block = _box(parts["drive_column"]), _box(parts["housing"])
    assert col[3] - col[0] == pytest.approx(thickness_mm, abs=1e-6)
    lo, hi = (sum(_z_extent(parts[f"input_bearing_{w}"])) / 2 for w in ("lower", "upper"))
    i_col = (col[4] - col[1]) * thickness_mm ** 3 / 12
    E = 207e3
    want = (3 * E * i_col / (block[2] - lo) ** 3, 3 * E * i_col / (hi - block[5]) ** 3)
    assert summary.beam_supports == pytest.approx(want, rel=1e-9)
    beam, span, a = summary.beam.stiffness, hi - lo, summary.beam.mesh_position
    spring = 1 / (1 / beam + ((span - a) / span) ** 2 / want[0] + (a / span) ** 2 / want[1])
    assert summary.preload_spring.linear_stiffness == pytest.approx(spring, rel=1e-9)
    assert spring == pytest.approx({30: 5005, 45: 5667}[thickness_mm], rel=1e-3)


def _beam_on_springs(ei: float, nodes: list[float], springs: dict[int, float], load_at: int) -> float:
    """Lateral deflection under a unit load at node ``load_at`` of a free round beam (Euler-Bernoulli,
    two-node Hermite elements between the sorted ``nodes`` heights, mm) on radial ``springs``
    (node -> N/mm): a matrix-stiffness solve, exact for point loads at the nodes."""
    import numpy as np
    n = len(nodes)
    k = np.zeros((2 * n, 2 * n))
    for i in range(n - 1):
        L = nodes[i + 1] - nodes[i]
        ke = ei / L ** 3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                                     [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
        idx = [2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3]
        k[np.ix_(idx, idx)] += ke
    for node, stiffness in springs.items():
        k[2 * node, 2 * node] += stiffness
    f = np.zeros(2 * n)
    f[2 * load_at] = 1.0
    return float(np.linalg.solve(k, f)[2 * load_at])


def test_split_pinion_compliant_pinion_between_two_supports():
    """The reviewer's split pinion: the compliant pinion hung 86 mm out on the 8.5 mm inner shaft with no
    radial support (1.45 mm and 1.5 deg at 22 N m, into the hollow shaft's 0.5 mm clearance; path 2
    about 771 N m/rad). Now it sits between the clamp collar (on the hollow shaft's overhung end) and
    an outboard bearing, both measured on the built solids; its support stiffness equals an
    independent matrix-stiffness solve of the two shafts (hollow shaft on its bearing pair carrying
    the collar, inner shaft on the collar and the outboard bearing), and its deflection at the
    preload is a few hundredths of the clearance."""
    layout, summary, part_set = _placed(load_design(ROOT / "assemblies/split_pinion.toml"))
    parts = {p.name: p for p in part_set.parts}

    def mid(name):
        return sum(_z_extent(parts[name])) / 2

    compl = layout.gear("pinion_compliant")
    z_pinion = sum(compl.face_z(compl.spec)) / 2
    z_collar, z_outboard = mid("friction_collar"), mid("compliant_bearing")
    z_b2, z_b1 = mid("pinion_bearing_2"), mid("pinion_bearing_1")
    assert z_collar < z_b2 < z_b1 < z_pinion < z_outboard  # straddled: no overhang
    E, kb = 207e3, 50e3
    d_in, d_h, bore_h = 8.5, 16.0, 8.5 + 2 * 0.5
    ei_in = E * math.pi * d_in ** 4 / 64
    ei_h = E * math.pi * (d_h ** 4 - bore_h ** 4) / 64
    # the hollow shaft at the collar: its end overhangs the lower bearing of the pair
    collar_compliance = _beam_on_springs(ei_h, [z_collar, z_b2, z_b1], {1: kb, 2: kb}, 0)
    pinion_compliance = _beam_on_springs(ei_in, [z_collar, z_pinion, z_outboard],
                                         {0: 1 / collar_compliance, 2: kb}, 1)
    comp = next(c for c in summary.components if c.name == "compliant_support")
    assert comp.local == pytest.approx(1 / pinion_compliance, rel=1e-9)
    (sup,) = [x for x in summary.supports if x.component == "compliant_support"]
    assert sup.force == pytest.approx(22e3 / 4 / compl.spec.base_radius, rel=1e-9)  # 22 N m at the output, ratio 4
    assert sup.deflection == pytest.approx(sup.force * pinion_compliance, rel=1e-9)
    assert sup.deflection < 0.05  # mm, against 1.45 mm unsupported and the 0.5 mm clearance
    # path 2 by hand: mesh (Eq. 1), the inner shaft twisting collar face to pinion face, the support
    out = layout.gear("output")
    G = 79.3e3
    mesh = E * compl.spec.face_width / 11 * out.spec.base_radius ** 2
    twist = G * math.pi * d_in ** 4 / 32 / (compl.face_z(compl.spec)[0] - (z_collar + 5.0)) * 16  # collar 10 mm wide
    support = 1 / pinion_compliance * compl.spec.base_radius ** 2 * 16
    path2 = 1 / (1 / mesh + 1 / twist + 1 / support)
    assert summary.drive.k2 == pytest.approx(path2, rel=1e-6)
    assert 6000 < path2 / 1e3 < 8000  # N m/rad: 6,821 (the unsupported pinion gave about 771)


def test_robot_joint_rotating_shafts_clear_the_link():
    """The reviewer saw the rotating shafts (and the bearings' inner rings) standing on the stationary
    link floor. The bosses now hold only the lower bearings' outer rings: each shaft end clears the
    link by the relief bore, reaching the ring's middle diameter, so radially by (OD - d) / 4, and
    each lower bearing still touches the link (the contact the build verifies)."""
    from geargen.cad.assembly import contact_gap
    from geargen.model.shafts import shafts
    layout, _, part_set = _placed(load_design(ROOT / "assemblies/robot_joint.toml"))
    parts = {p.name: p for p in part_set.parts}
    link = parts["link"].world()
    for placed in (s for key, s in shafts(layout).items() if key != "input"):
        lower = placed.supports()[0]
        assert contact_gap(parts[lower.name].world(), link, 1e-3) < 1e-6, lower.name
        gap = contact_gap(parts[placed.name].world(), link, 1e-3)
        assert gap == pytest.approx((lower.outer_diameter - placed.diameter) / 4, rel=1e-6), placed.name


def _structure(name: str):
    """The structure report of a shipped assembly's placed parts."""
    from geargen.pipeline import structure_check
    layout, _, part_set = _placed(load_design(ROOT / f"assemblies/{name}.toml"))
    return structure_check(part_set, layout)


def test_structure_of_the_shipped_assemblies():
    """Connectivity read from the verified contacts: the split pinion is sound (every bearing seated in
    a plate, the compliant pinion's shaft between collar and outboard bearing), so is the robot joint
    (the upper bearings seated in the link cover, the lower ones on the floor bosses by their outer
    rings, the input bearings in the carriage on its blades), and so is the C-axis (the dual pinions'
    bearings in their quills, which slide in the housing block and meet the travel stops by their
    lugs; the long pinion's bearings in plates on the drive column, the gearhead and motor on its
    motor plate)."""
    assert _structure("split_pinion").failures == []
    robot = _structure("robot_joint")
    assert robot.failures == []
    # the body that carries the output gear holds its shaft and nothing stationary
    assert ("output", "output_shaft") in robot.bodies
    c_axis = _structure("c_axis")
    assert c_axis.failures == []
    # each dual pinion turns with its shaft, locking ring and locknut: no quill, stop or housing in it
    for side in "ab":
        (body,) = [b for b in c_axis.bodies if f"cluster_shaft_{side}" in b]
        assert set(body) == {f"cluster_large_{side}", f"cluster_small_{side}", f"cluster_shaft_{side}",
                             f"friction_ring_{side}", f"locknut_{side}"}
    # the quills, stops, column and plates are one stationary body with the housing block
    (fixed,) = [b for b in c_axis.bodies if "housing" in b]
    assert {"quill_a", "quill_b", "travel_stop_engaged_a", "travel_stop_retracted_b", "drive_column",
            "input_bearing_lower_plate", "input_bearing_upper_plate", "motor_plate"} <= set(fixed)
    assert ("coupling", "input", "input_shaft") in c_axis.bodies


def _unseated(part_set, *pairs):
    """``part_set`` without the contacts between the ``pairs`` of parts (a broken assembly)."""
    from dataclasses import replace
    gone = {frozenset(p) for p in pairs}
    return replace(part_set, intended_contacts=[c for c in part_set.intended_contacts if frozenset(c[:2]) not in gone])


def test_structure_check_fails_the_check_unless_reported(tmp_path):
    """A C-axis whose upper bearing of pinion A has lost its seat in the quill (that joint taken out
    of the resolved drive: the bearing then joins nothing to anything) is one structure finding of
    the verdict check and build share: a note where the design file says structure = "report", a
    failure with the default "fail". The shipped C-axis passes with the default."""
    from dataclasses import replace
    from geargen.checks.verdict import verify

    def outcome_of(path, *unseat):
        layout = resolve(load_design(path))
        gone = {frozenset(p) for p in unseat}
        hardware = replace(layout.hardware, joints=tuple(j for j in layout.hardware.joints
                                                         if frozenset((j.a, j.b)) not in gone))
        return verify(replace(layout, hardware=hardware), tolerances=False)

    shipped = ROOT / "assemblies/c_axis.toml"
    assert "[checks]" not in shipped.read_text()  # the default: structure = "fail"
    finding = "cluster_bearing_upper_a touches only cluster_shaft_a: it joins nothing to anything"
    failed = outcome_of(shipped, ("quill_a", "cluster_bearing_upper_a"))
    assert [f.message for f in failed.all_failures if f.kind == "structure"] == [f"{finding} (no seat on its other side)"]
    reporting = tmp_path / "c_axis.toml"
    reporting.write_text(shipped.read_text() + '\n[checks]\nstructure = "report"\n')
    reported = outcome_of(reporting, ("quill_a", "cluster_bearing_upper_a"))
    assert not any(f.kind == "structure" for f in reported.all_failures)
    assert [n for n in reported.notes if n.startswith("structure")] == \
        [f'structure ([checks] structure = "report"): {finding} (no seat on its other side)']
    # the bearing still touches the quill: taking the joint out is no overlap, the structure is all
    assert reported.all_failures == [] and reported.parts.ok
    assert outcome_of(shipped).all_failures == []


def test_c_axis_quills_hold_the_bearings_and_meet_the_stops():
    """Each dual pinion's quill holds both bearings' outer rings and slides in the housing block's bore
    (all touching: faces within 1e-6 mm); the turning shaft and locknut run clear of it, by the ring
    relief of the shoulder between the bearings (42.5 mm: (42.5 - 30) / 2 = 6.25 mm) and by the seat
    bore around the locknut ((55 - 45) / 2 = 5 mm). Engaged, the quill's lug rests on the engaged stop;
    disengaged, the quill has slid out by the stroke onto the retracted stop; the stops meet nothing
    but the quill (and the housing that holds them)."""
    from geargen.cad.assembly import contact_gap
    design = load_design(ROOT / "assemblies/c_axis.toml")
    low = {}
    for position in ("engaged", "disengaged"):
        layout, _, part_set = _placed(design, position=position)
        parts = {p.name: p for p in part_set.parts}

        def gap(a, b):
            return contact_gap(parts[a].world(), parts[b].world(), 1e-3)

        contacts = [set(c[:2]) for c in part_set.intended_contacts]
        for side in "ab":
            quill = f"quill_{side}"
            for other in (f"cluster_bearing_lower_{side}", f"cluster_bearing_upper_{side}", "housing"):
                assert gap(quill, other) < 1e-6, (position, quill, other)
            assert gap(quill, f"cluster_shaft_{side}") == pytest.approx((42.5 - 30) / 2, abs=1e-6)
            assert gap(quill, f"locknut_{side}") == pytest.approx((55 - 45) / 2, abs=1e-6)
            on, off = ((f"travel_stop_engaged_{side}", f"travel_stop_retracted_{side}") if position == "engaged"
                       else (f"travel_stop_retracted_{side}", f"travel_stop_engaged_{side}"))
            assert gap(quill, on) < 1e-6 and gap(quill, off) > 1.0, (position, side)
            # the stops are held by the housing and meet nothing but the quill
            for stop in (on, off):
                assert set().union(*(c for c in contacts if stop in c)) - {stop} <= {"housing", quill}
            low[position, side] = _z_extent(parts[quill])[0]
    shift = resolve(design, "disengaged").axial_shift
    for side in "ab":
        assert low["disengaged", side] - low["engaged", side] == pytest.approx(shift[f"cluster_{side}"], abs=1e-6)
