"""The layout drawing's lines of action against independent geometry (Fig. 9 of the paper)."""

import math

import numpy as np
import pytest

from geargen.report.layout import line_of_action, working_side


def _distance_to_line(p, a, b):
    t = (b - a) / np.linalg.norm(b - a)
    v = np.asarray(p, float) - a
    return abs(v[0] * t[1] - v[1] * t[0])


@pytest.mark.parametrize("seed", range(6))
def test_line_of_action_is_the_internal_tangent_of_the_base_circles(seed):
    rng = np.random.default_rng(seed)
    c1, c2 = rng.uniform(-50, 50, 2), rng.uniform(-50, 50, 2)
    a = float(np.linalg.norm(c2 - c1))
    rb1, rb2 = (rng.uniform(0.2, 0.45) * a for _ in range(2))
    for side in (1, -1):
        t1, t2 = line_of_action(c1, rb1, c2, rb2, side)
        # tangent to both base circles: the radii to the tangent points are normal to the line
        assert _distance_to_line(c1, t1, t2) == pytest.approx(rb1, rel=1e-12)
        assert _distance_to_line(c2, t1, t2) == pytest.approx(rb2, rel=1e-12)
        assert np.dot(t1 - c1, t2 - t1) == pytest.approx(0.0, abs=1e-9 * a * a)
        # it crosses the line of centres at the pitch point, a rb1 / (rb1 + rb2) from gear 1
        pitch = c1 + (c2 - c1) * rb1 / (rb1 + rb2)
        assert _distance_to_line(pitch, t1, t2) == pytest.approx(0.0, abs=1e-9 * a)
        # and makes pi/2 - alpha_w with it, cos(alpha_w) = (rb1 + rb2) / a
        alpha_w = math.acos((rb1 + rb2) / a)
        cosang = abs(np.dot((t2 - t1) / np.linalg.norm(t2 - t1), (c2 - c1) / a))
        assert math.degrees(math.acos(cosang)) == pytest.approx(90 - math.degrees(alpha_w), abs=1e-9)


def test_robot_joint_mesh1_line_of_action_is_parallel_to_the_symmetry_line():
    """The Appendix's optimal configuration (Fig. 9): mesh 1's working line of action lies within
    0.12 deg of the x axis (the preload force's direction; appendix-notes: 0.11 deg at the Appendix's
    maximum-backlash centres, 0.111 deg as modelled); it was drawn at 163.2 deg."""
    from pathlib import Path

    from geargen.design.assembly import load_design
    from geargen.drives import resolve

    layout = resolve(load_design(Path(__file__).resolve().parents[2] / "assemblies/robot_joint.toml"))
    mesh = layout.mesh("mesh1_a")
    g1, g2 = layout.gear(mesh.part1), layout.gear(mesh.part2)
    rb1, rb2 = mesh.gear1.base_radius, mesh.gear2.base_radius
    side = working_side(g1.centre, rb1, g2.centre, rb2, "ccw")
    t1, t2 = line_of_action(g1.centre, rb1, g2.centre, rb2, side)
    angle = math.degrees(math.atan2(t2[1] - t1[1], t2[0] - t1[0])) % 180.0
    assert min(angle, 180.0 - angle) < 0.12
