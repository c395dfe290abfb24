"""Path 2 (sections of exported solids) against path 1 and against theory.

The polygon algorithm is first checked without any CAD on finely sampled exact outlines; the
slow tests build the paper's gears, export STL and STEP, and section the files.
"""

import math

import numpy as np
import pytest

from geargen.checks.mesh2d import CheckSettings, MeshSetup, check_mesh, mesh_positions, polar_outline
from geargen.checks.solids import (GearSections, check_mesh_sections, compare_paths, polygon_play,
                                   section_planes, stated_tolerance)
from geargen.profile.segments import sample_outline

from checks_support import gear, inch_gear, theory_normal_backlash, tight_centre_distance

IN = 25.4


def _sampled_sections(spec, planes, step):
    """The exact outline sampled ``step`` mm apart as chord segments (no CAD); deviation is the
    largest chord sagitta step^2 / (8 rho_min), rho_min the smallest radius of curvature
    (the rack tip radius on the fillet)."""
    from geargen.profile.tooth import section_rotation

    prof = polar_outline(spec).profile
    segs = []
    for z in planes:
        pts = sample_outline(prof.outline(section_rotation(spec, z)), step)
        segs.append(np.stack([pts, np.roll(pts, -1, axis=0)], axis=1))
    rho = spec.rack_tip_radius_coefficient * spec.module
    return GearSections(spec, np.asarray(planes, float), segs, step ** 2 / (8 * rho), "sampled exact outline")


def test_polygon_play_has_the_closed_form_answer():
    """A square [1, 2] x [-0.5, 0.5] turning about the origin against a short bar at y = 1.5 left
    of the y axis: its top edge reaches the bar's end (0, 1.5) after turning
    pi/2 - atan2(0.5, sqrt(1.5^2 - 0.5^2)) counter-clockwise; clockwise nothing is in reach."""
    sq = np.array([[1, -0.5], [2, -0.5], [2, 0.5], [1, 0.5]], float)
    seg1 = np.stack([sq, np.roll(sq, -1, 0)], 1)
    bar = np.array([[[0.0, 1.5], [-0.1, 1.5]]])
    ccw, cw = polygon_play(seg1, bar, (0.0, 0.0))
    assert ccw == pytest.approx(math.pi / 2 - math.atan2(0.5, math.sqrt(1.5 ** 2 - 0.25)), abs=1e-14)
    assert cw == math.inf
    # moved into the square (y = 0.3, x from 1.45 to 1.55): its end (1.45, 0.3) is freed soonest
    # by turning the square clockwise until the top edge passes it - a negative counter-clockwise play
    ccw, cw = polygon_play(seg1, bar + np.array([1.55, -1.2]), (0.0, 0.0))
    r = math.hypot(1.45, 0.3)
    assert ccw == pytest.approx(-(math.atan2(0.5, math.sqrt(r * r - 0.25)) - math.atan2(0.3, 1.45)), abs=1e-14)


@pytest.mark.parametrize("pair", [(gear(20), gear(41)), (gear(17, 1.5, beta_deg=18), gear(43, 1.5, beta_deg=18, hand="left"))])
def test_polygon_path_on_sampled_exact_outlines_agrees_with_path_1(pair):
    g1, g2 = pair
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.02)
    planes = section_planes(su, 2)
    s1, s2 = _sampled_sections(g1, planes, 0.005), _sampled_sections(g2, planes, 0.005)
    pos = mesh_positions(su, 6)
    exact = check_mesh(su, CheckSettings(steps_per_tooth=6))
    sec = check_mesh_sections(su, s1, s2, CheckSettings(steps_per_tooth=6), pos)
    a = compare_paths(su, sec)
    assert a["agree"], a
    assert sec.tolerance == pytest.approx(stated_tolerance(s1, s2))
    assert np.all(np.abs(sec.sweep.normal_backlash - theory_normal_backlash(g1, g2, su.centre_distance)) <= sec.tolerance)


def test_polygon_path_sees_overlap():
    g1, g2 = gear(20), gear(41)
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) - 0.02)
    planes = np.array([5.0])
    sec = check_mesh_sections(su, _sampled_sections(g1, planes, 0.005), _sampled_sections(g2, planes, 0.005),
                              CheckSettings(), [0.0, 0.1])
    assert "flank_interference" in sec.failure_kinds


# ----------------------------------------------------------------------------- built solids
PAPER = {"mesh1": (inch_gear(16, name="input", face_width=0.25 * IN), inch_gear(48, name="cluster_large", face_width=0.1875 * IN), 1.004 * IN),
         "mesh2": (inch_gear(21, name="cluster_small", face_width=0.3125 * IN), inch_gear(112, name="output", face_width=0.25 * IN), 2.078125 * IN)}


@pytest.mark.slow
@pytest.mark.parametrize("mesh", ["mesh1", "mesh2"])
def test_paper_meshes_two_paths_agree_on_exported_stl(mesh, tmp_path):
    """The paper's meshes (32 DP, 20 deg, C1 = 1.004 in, C2 = 2.078125 in): exported STL sectioned
    at three planes agrees with the exact outlines within the stated tessellation tolerance,
    and both agree with theory."""
    from geargen.checks.solids import export_and_section

    g1, g2, c = PAPER[mesh]
    su = MeshSetup.centred(g1, g2, c, mesh)
    planes = section_planes(su, 3)
    s1 = export_and_section(g1, planes, tmp_path, chordal_tolerance=2e-3)
    s2 = export_and_section(g2, planes, tmp_path, chordal_tolerance=2e-3)
    assert (tmp_path / f"{g1.name}.stl").exists()
    settings = CheckSettings(steps_per_tooth=4)
    exact = check_mesh(su, settings)
    sec = check_mesh_sections(su, s1, s2, settings, exact.sweep.mesh_position)
    agreement = compare_paths(su, sec)
    assert agreement["agree"], agreement
    assert sec.tolerance <= 2 * (2e-3 + 1e-5)
    theory = theory_normal_backlash(g1, g2, c)
    assert np.all(np.abs(sec.sweep.normal_backlash - theory) <= sec.tolerance)
    assert np.all(np.abs(exact.sweep.normal_backlash - theory) < 1e-5)
    # chords cut into the convex flanks: the solid's teeth are, if anything, thinner
    assert np.all(sec.sweep.normal_backlash >= exact.sweep.normal_backlash - 1e-5)


@pytest.mark.slow
def test_step_sections_agree_with_path_1(tmp_path):
    from geargen.cad.export import export_step
    from geargen.cad.gear_solid import build_gear
    from geargen.checks.solids import sections_from_step

    g1, g2 = gear(18, 1.0, name="p", face_width=4.0), gear(29, 1.0, name="w", face_width=4.0)
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.03, "step")
    planes = np.array([2.0])
    secs = []
    for g in (g1, g2):
        export_step([(g.name, build_gear(g).shape)], tmp_path / f"{g.name}.step", length_unit="mm")
        secs.append(sections_from_step(g, tmp_path / f"{g.name}.step", planes, samples_per_face=48))
    settings = CheckSettings(steps_per_tooth=3)
    exact = check_mesh(su, settings)
    sec = check_mesh_sections(su, secs[0], secs[1], settings, exact.sweep.mesh_position)
    assert sec.tolerance < 2e-4  # chords between exact section points
    assert compare_paths(su, sec)["agree"]


def test_helical_gears_with_offset_faces_agree_and_wrong_frames_are_refused():
    from dataclasses import replace

    g1 = gear(17, 1.5, beta_deg=18, hand="right", face_width=12.0)
    g2 = gear(43, 1.5, beta_deg=18, hand="left", face_width=6.0)
    from geargen.profile.tooth import section_rotation

    # gear 2's face starts 4 mm up gear 1's: its z = 0 section meets gear 1's section at z = 4
    centred = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.02)
    su = replace(centred, face_offset2=4.0,
                 rotation2=centred.rotation2 - g1.teeth / g2.teeth * section_rotation(g1, 4.0))
    planes = section_planes(su, 2)  # gear 1's face coordinates, inside the common face [4, 10]
    s1 = _sampled_sections(g1, planes, 0.005)
    s2 = _sampled_sections(g2, planes - su.face_offset2, 0.005)
    sec = check_mesh_sections(su, s1, s2, CheckSettings(), [0.0, 0.1, 0.2])
    a = compare_paths(su, sec)
    assert a["agree"] and a["normal_backlash_difference_max"] <= sec.tolerance, a
    assert not sec.failure_kinds
    # gear 2 sectioned at gear 1's heights (not its own): the teeth sit off their helix there
    wrong = _sampled_sections(g2, planes, 0.005)
    wrong.planes = planes - su.face_offset2
    with pytest.raises(ValueError, match="face coordinates"):
        check_mesh_sections(su, s1, wrong, CheckSettings(), [0.0])
