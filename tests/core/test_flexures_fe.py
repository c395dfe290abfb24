"""Flexure and beam formulas against numerical references written here: a small 2-D frame finite-
element model (Timoshenko beam elements, which reduce to Euler-Bernoulli when shear is left out)
and the large-deflection elastica solved with scipy's solve_bvp.

Tolerances: a frame of Hermite beam elements with nodal point loads is exact at the nodes for
uniform Euler-Bernoulli members, so single-member checks use 1e-9; whole-frame checks (carriages on
real, extensible blades) and interpolated positions use what the discretisation allows, said at
each assert.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from geargen.core import flexures as fx
from geargen.core.stiffness import shaft_bending_stiffness


# --- a minimal 2-D frame FE model ----------------------------------------------------------------

class Frame:
    """Nodes (x, y) with dofs (u, v, theta); members of E, A, I and optional shear area."""

    def __init__(self):
        self.nodes: list[tuple[float, float]] = []
        self.members: list[tuple[int, int, float, float, float, float | None]] = []
        self.fixed: set[int] = set()
        self.loads: dict[int, float] = {}
        self.springs: dict[int, float] = {}  # grounded springs on single dofs (elastic supports)

    def node(self, x, y):
        self.nodes.append((float(x), float(y)))
        return len(self.nodes) - 1

    def member(self, i, j, E, A, I, shear_rigidity=None, pieces=1):
        """Member i-j, split into ``pieces`` elements; ``shear_rigidity`` = kappa G A (None: no shear)."""
        (xi, yi), (xj, yj) = self.nodes[i], self.nodes[j]
        ids = [i] + [self.node(xi + (xj - xi) * t, yi + (yj - yi) * t) for t in np.arange(1, pieces) / pieces] + [j]
        for a, b in zip(ids[:-1], ids[1:]):
            self.members.append((a, b, E, A, I, shear_rigidity))
        return ids

    def fix(self, node, *dofs):
        for d in dofs:
            self.fixed.add(3 * node + "uvt".index(d))

    def spring(self, node, dof, k):
        i = 3 * node + "uvt".index(dof)
        self.springs[i] = self.springs.get(i, 0.0) + k

    def load(self, node, dof, value):
        k = 3 * node + "uvt".index(dof)
        self.loads[k] = self.loads.get(k, 0.0) + value

    @staticmethod
    def element(E, A, I, L, shear):
        phi = 0.0 if shear is None else 12 * E * I / (shear * L ** 2)
        b = E * I / (L ** 3 * (1 + phi))
        k = np.zeros((6, 6))
        k[0, 0] = k[3, 3] = E * A / L
        k[0, 3] = k[3, 0] = -E * A / L
        sub = b * np.array([[12, 6 * L, -12, 6 * L],
                            [6 * L, (4 + phi) * L ** 2, -6 * L, (2 - phi) * L ** 2],
                            [-12, -6 * L, 12, -6 * L],
                            [6 * L, (2 - phi) * L ** 2, -6 * L, (4 + phi) * L ** 2]])
        idx = [1, 2, 4, 5]
        k[np.ix_(idx, idx)] = sub
        return k

    def _transform(self, a, b):
        (xa, ya), (xb, yb) = self.nodes[a], self.nodes[b]
        L = math.hypot(xb - xa, yb - ya)
        c, s = (xb - xa) / L, (yb - ya) / L
        r = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])
        t = np.zeros((6, 6))
        t[:3, :3] = t[3:, 3:] = r
        return L, t

    def solve(self):
        n = 3 * len(self.nodes)
        K = np.zeros((n, n))
        for a, b, E, A, I, shear in self.members:
            L, t = self._transform(a, b)
            ke = t.T @ self.element(E, A, I, L, shear) @ t
            dofs = [3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2]
            K[np.ix_(dofs, dofs)] += ke
        for i, k in self.springs.items():
            K[i, i] += k
        f = np.zeros(n)
        for k, v in self.loads.items():
            f[k] = v
        free = np.array([k for k in range(n) if k not in self.fixed])
        u = np.zeros(n)
        u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
        self.u = u
        return u

    def disp(self, node, dof):
        return self.u[3 * node + "uvt".index(dof)]

    def end_moments(self):
        """Bending moment at both ends of every element (local end forces, sign of element end 'a')."""
        out = []
        for a, b, E, A, I, shear in self.members:
            L, t = self._transform(a, b)
            ue = self.u[[3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2]]
            fe = self.element(E, A, I, L, shear) @ (t @ ue)
            out.append((a, b, fe[2], -fe[5]))
        return out


E = 207e3


# --- blade flexures ------------------------------------------------------------------------------

def test_single_fixed_guided_blade_stiffness_and_clamp_stress():
    t, w, L, F = 0.254, 12.7, 25.4, 1.0
    I, A = w * t ** 3 / 12, w * t
    fr = Frame()
    base, top = fr.node(0, 0), fr.node(0, L)
    fr.member(base, top, E, A, I, pieces=8)
    fr.fix(base, "u", "v", "t")
    fr.fix(top, "t")  # guided: the carriage does not tilt
    fr.load(top, "u", F)
    fr.solve()
    delta = fr.disp(top, "u")
    assert F / delta == pytest.approx(fx.blade_stiffness_along(E, w, t, L), rel=1e-9)
    m_max = max(max(abs(m1), abs(m2)) for *_, m1, m2 in fr.end_moments())
    assert m_max == pytest.approx(F * L / 2, rel=1e-9)  # the clamp moment 6 E I delta / L^2
    assert m_max * (t / 2) / I == pytest.approx(fx.blade_max_stress(E, t, L, delta), rel=1e-9)


def test_three_blades_with_a_real_carriage_act_as_guided_blades():
    # Three blades clamped to the base, their tops bolted to a stiff carriage bar; nothing forces
    # the carriage not to tilt except the blades' own axial stiffness.
    t, w, L, spacing = 0.254, 12.7, 25.4, 20.0
    I, A = w * t ** 3 / 12, w * t
    fr = Frame()
    tops = []
    for i in range(3):
        base, top = fr.node(i * spacing, 0), fr.node(i * spacing, L)
        fr.member(base, top, E, A, I, pieces=10)
        fr.fix(base, "u", "v", "t")
        tops.append(top)
    for a, b in zip(tops[:-1], tops[1:]):
        fr.member(a, b, E, 10.0 * 12.7 * 5, 12.7 * 10.0 ** 3 / 12)  # a 10 mm thick carriage bar
    fr.load(tops[1], "u", 1.0)
    fr.solve()
    k_frame = 1.0 / fr.disp(tops[1], "u")
    # the carriage tilts only through blade stretch (E A / L >> bending stiffness): within 0.1 %
    assert k_frame == pytest.approx(fx.blade_stiffness_along(E, w, t, L, count=3), rel=1e-3)
    tilt = fr.disp(tops[1], "t")
    assert abs(tilt) * L < 1e-3 * fr.disp(tops[1], "u")


def test_lateral_blade_stiffness_with_shear_matches_timoshenko_frame():
    t, w, L, nu = 0.254, 12.7, 25.4, 0.29
    G = E / (2 * (1 + nu))
    I, A = t * w ** 3 / 12, w * t  # bending about the blade's strong axis
    fr = Frame()
    base, top = fr.node(0, 0), fr.node(0, L)
    fr.member(base, top, E, A, I, shear_rigidity=5 / 6 * G * A, pieces=6)
    fr.fix(base, "u", "v", "t")
    fr.fix(top, "t")
    fr.load(top, "u", 1.0)
    fr.solve()
    k_fe = 1.0 / fr.disp(top, "u")
    assert k_fe == pytest.approx(fx.blade_stiffness_lateral(E, w, t, L, 1, G), rel=1e-9)
    # shear is not negligible for a blade this short and wide: leaving it out is > 30 % too stiff
    assert fx.blade_stiffness_lateral(E, w, t, L, 1) > 1.3 * k_fe
    b = fx.blade_flexure(1, t, L, w, E, 500.0, 0.1, poisson_ratio=nu)
    assert b.stiffness_lateral == pytest.approx(k_fe, rel=1e-9)


def test_blade_large_deflection_elastica_gives_stiffness_and_parasitic_shortening():
    # Exact fixed-guided elastica (arc length s): x' = cos th, y' = sin th, th' = M/EI, M' = -F cos th,
    # clamped at s = 0, guided (th = 0) at s = L with tip deflection delta; F is the unknown parameter.
    t, w, L = 0.254, 12.7, 25.4
    EI = E * w * t ** 3 / 12
    for ratio in (0.02, 0.05):
        delta = ratio * L
        def ode(s, y, p):
            return np.vstack([np.cos(y[2]), np.sin(y[2]), y[3] / EI, -p[0] * np.cos(y[2])])
        def bc(ya, yb, p):
            return np.array([ya[0], ya[1], ya[2], yb[2], yb[1] - delta])
        s = np.linspace(0, L, 41)
        k_lin = 12 * EI / L ** 3
        xi = s / L
        guess = np.vstack([s, delta * (3 * xi ** 2 - 2 * xi ** 3), delta * 6 * xi * (1 - xi) / L,
                           k_lin * delta * (L / 2 - s)])
        sol = solve_bvp(ode, bc, s, guess, p=[k_lin * delta], tol=1e-10, max_nodes=100000)
        assert sol.success, sol.message
        force, x_tip = sol.p[0], sol.sol(L)[0]
        # stiffening from the blade's geometry is second order in delta/L: under 0.5 % here
        assert force / delta == pytest.approx(fx.blade_stiffness_along(E, w, t, L), rel=5e-3)
        # the parasitic shortening 3 delta^2 / (5 L) is the leading term; next term is O((delta/L)^2)
        assert L - x_tip == pytest.approx(fx.blade_parasitic_shortening(L, delta), rel=5e-3)


# --- the beam-spring pinion and shaft bending ------------------------------------------------------

def _simply_supported(span, a, d, pieces=200):
    fr = Frame()
    area, inertia = math.pi * d ** 2 / 4, math.pi * d ** 4 / 64
    left, load_node, right = fr.node(0, 0), fr.node(a, 0), fr.node(span, 0)
    ids_left = fr.member(left, load_node, E, area, inertia, pieces=int(round(pieces * a / span)))
    ids_right = fr.member(load_node, right, E, area, inertia, pieces=pieces - int(round(pieces * a / span)))
    fr.fix(left, "u", "v")
    fr.fix(right, "v")
    fr.load(load_node, "v", 1.0)
    fr.solve()
    ids = ids_left + ids_right[1:]
    x = np.array([fr.nodes[i][0] for i in ids])
    v = np.array([fr.disp(i, "v") for i in ids])
    th = np.array([fr.disp(i, "t") for i in ids])
    return fr, load_node, x, v, th


@pytest.mark.parametrize("a", [50.0, 30.0, 72.5])
def test_simply_supported_beam_against_frame_model(a):
    span, d = 100.0, 12.0
    EI = E * math.pi * d ** 4 / 64
    fr, load_node, x, v, th = _simply_supported(span, a, d)
    # nodal values of Hermite elements are exact for point loads on uniform beams; what is left is
    # round-off of a 600-dof solve (condition number ~1e10), hence 1e-7
    assert 1.0 / fr.disp(load_node, "v") == pytest.approx(fx.beam_stiffness_at_load(span, a, EI), rel=1e-7)
    assert np.allclose(v, fx.simply_supported_deflection(x, span, a, 1.0, EI), rtol=1e-7, atol=1e-13)
    assert np.allclose(th, fx.simply_supported_slope(x, span, a, 1.0, EI), rtol=1e-7, atol=1e-13)
    # zero slope: where the FE rotation changes sign, located by linear interpolation between nodes
    i = np.flatnonzero(np.sign(th[:-1]) != np.sign(th[1:]))[0]
    x0 = x[i] - th[i] * (x[i + 1] - x[i]) / (th[i + 1] - th[i])
    h = span / 200
    assert x0 == pytest.approx(fx.zero_slope_position(span, a), abs=h ** 2 / span * 5)
    # bending moment under the load from element end forces
    m_fe = max(abs(m) for *_, m1, m2 in fr.end_moments() for m in (m1, m2))
    assert m_fe == pytest.approx(float(fx.simply_supported_moment(a, span, a, 1.0)), rel=1e-7)


def test_beam_pinion_sized_for_a_stiffness_delivers_it_in_the_frame_model():
    b = fx.beam_pinion(10.0, E, 250.0, target_stiffness=1500.0, face_width=12.0)
    fr, load_node, x, v, th = _simply_supported(b.span, b.mesh_position, 10.0)
    assert 1.0 / fr.disp(load_node, "v") == pytest.approx(1500.0, rel=1e-7)  # round-off as above
    assert abs(fr.disp(load_node, "t")) * b.span < 1e-7 * abs(fr.disp(load_node, "v"))  # zero slope at the mesh


@pytest.mark.parametrize("support, a", [("simple", 20.0), ("fixed", 20.0), ("fixed", 50.0), ("cantilever", 35.0)])
def test_shaft_bending_stiffness_against_frame_model(support, a):
    d, span = 8.0, 60.0
    I = math.pi * d ** 4 / 64
    fr = Frame()
    if support == "cantilever":
        root, tip = fr.node(0, 0), fr.node(a, 0)
        fr.member(root, tip, E, 50.0, I, pieces=4)
        fr.fix(root, "u", "v", "t")
        load = tip
        k_formula = shaft_bending_stiffness(E, d, None, a, "cantilever")
    else:
        left, load, right = fr.node(0, 0), fr.node(a, 0), fr.node(span, 0)
        fr.member(left, load, E, 50.0, I, pieces=4)
        fr.member(load, right, E, 50.0, I, pieces=4)
        fr.fix(left, "u", "v", *(("t",) if support == "fixed" else ()))
        fr.fix(right, "v", *(("t",) if support == "fixed" else ()))
        k_formula = shaft_bending_stiffness(E, d, span, a, support)
    fr.load(load, "v", 1.0)
    fr.solve()
    assert 1.0 / fr.disp(load, "v") == pytest.approx(k_formula, rel=1e-9)


@pytest.mark.parametrize("load_position", [-20.0, 12.0, 30.0, 83.5])
def test_shaft_on_elastic_bearings_against_frame_model(load_position):
    """A 30 mm shaft on two bearings 30 mm apart (150 N/um and 90 N/um), the gear between them or
    overhung on either side (the C-axis dual pinion: 53.5 mm beyond the upper bearing): deflection
    and slope under the load from the frame model with spring supports."""
    from geargen.core.stiffness import supported_shaft_compliance
    d, span, k1, k2 = 30.0, 30.0, 150e3, 90e3
    I = math.pi * d ** 4 / 64
    fr = Frame()
    xs = sorted({0.0, span, load_position})
    nodes = {x: fr.node(x, 0) for x in xs}
    for a, b in zip(xs[:-1], xs[1:]):
        fr.member(nodes[a], nodes[b], E, 700.0, I, pieces=6)
    fr.fix(nodes[xs[0]], "u")  # axial only; laterally the shaft floats on its bearings
    fr.spring(nodes[0.0], "v", k1)
    fr.spring(nodes[span], "v", k2)
    fr.load(nodes[load_position], "v", 1.0)
    fr.solve()
    compliance, slope = supported_shaft_compliance(E, d, span, load_position, (k1, k2))
    assert compliance == pytest.approx(fr.disp(nodes[load_position], "v"), rel=1e-9)
    assert slope == pytest.approx(fr.disp(nodes[load_position], "t"), rel=1e-9)


@pytest.mark.parametrize("load_position, at", [(53.5, 35.0), (35.0, 53.5), (12.0, 22.0), (-20.0, 83.5), (83.5, -20.0)])
def test_shaft_influence_at_another_point_against_frame_model(load_position, at):
    """The displacement and slope at one gear of a shaft on elastic bearings under the other gear's
    load (a cluster's two gears: the C-axis pinion and large gear both overhung, the robot joint's
    between the bearings), from the frame model; and reciprocity (Maxwell) between the two points."""
    from geargen.core.stiffness import shaft_influence
    d, span, k1, k2 = 30.0, 30.0, 150e3, 90e3
    I = math.pi * d ** 4 / 64
    fr = Frame()
    xs = sorted({0.0, span, load_position, at})
    nodes = {x: fr.node(x, 0) for x in xs}
    for a, b in zip(xs[:-1], xs[1:]):
        fr.member(nodes[a], nodes[b], E, 700.0, I, pieces=6)
    fr.fix(nodes[xs[0]], "u")
    fr.spring(nodes[0.0], "v", k1)
    fr.spring(nodes[span], "v", k2)
    fr.load(nodes[load_position], "v", 1.0)
    fr.solve()
    displacement, slope = shaft_influence(E, d, span, load_position, at, (k1, k2))
    assert displacement == pytest.approx(fr.disp(nodes[at], "v"), rel=1e-9)
    assert slope == pytest.approx(fr.disp(nodes[at], "t"), rel=1e-9)
    assert shaft_influence(E, d, span, at, load_position, (k1, k2))[0] == pytest.approx(displacement, rel=1e-12)
