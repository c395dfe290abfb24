"""One home per formula (issue 26): the involute function, the working pressure angle at a centre
distance, the backlash a centre distance gives, the roll length and length of action live in
:mod:`geargen.core.involute`; the B-spline least-squares fit and the Greville abscissae in
:mod:`geargen.profile.bspline_fit`; the kernel helpers (B-spline curves and surfaces from poles,
vertex, edge and wire builders, booleans, volume) in :mod:`geargen.cad.kernel`. The scans below fail when a copy of one of
these formulas is written afresh elsewhere in ``geargen/``, or when a module imports another
module's private name; the closed-form tests check each home against published numbers and
independent constructions.

The scans are pure source reading (ast); each pattern is the form the copies had when they were
brought home. A site that must keep its own copy is listed in :data:`ALLOWED` with its reason.
"""

from __future__ import annotations

import ast
import math
from pathlib import Path

import numpy as np
import pytest

from geargen.core.involute import (backlash_change, involute, inverse_involute, length_of_action, roll_length,
                                   working_pressure_angle_at)

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "geargen"
DEG = math.pi / 180

#: where each formula lives
HOMES = {"involute": "core/involute.py", "working pressure angle": "core/involute.py",
         "backlash at a centre distance": "core/involute.py", "line of action": "core/involute.py",
         "B-spline fit": "profile/bspline_fit.py", "Greville abscissae": "profile/bspline_fit.py",
         "kernel boolean": "cad/kernel.py", "kernel volume": "cad/kernel.py"}

#: (file under geargen/, formula) -> why that file keeps its own copy
ALLOWED = {
    ("design/feasibility.py", "involute"): "design is the bottom layer (tests/test_layering.py) and may not import "
                                           "core; tests/design/test_feasibility.py checks its closed forms against "
                                           "core.involute and the outline",
    ("families/worm/geometry.py", "Greville abscissae"): "a family's geometry is core, below profile (tests/test_layering.py): the helix spline's "
                                            "Greville abscissae of its unclamped knots, one line",
}


def _name(node: ast.AST) -> str:
    """The last part of a called name: ``np.tan`` -> ``tan``."""
    if isinstance(node, ast.Attribute):
        return node.attr
    if isinstance(node, ast.Name):
        return node.id
    return ""


def _call(node: ast.AST, *names: str) -> bool:
    return isinstance(node, ast.Call) and _name(node.func) in names


def _unwrapped(node: ast.AST) -> ast.AST:
    """The argument inside min(..., 1)/np.clip(..., -1, 1)/np.minimum(...) (a clamp to acos's domain)."""
    while _call(node, "min", "max", "clip", "minimum", "maximum") and node.args:
        inner = [a for a in node.args if not isinstance(a, ast.Constant) and not isinstance(a, ast.UnaryOp)]
        if len(inner) != 1:
            break
        node = inner[0]
    return node


def _is_base_sum_over_distance(node: ast.AST) -> bool:
    """``(r_b1 +- r_b2) / a``, ``a_0 cos(alpha) / a``, ``base_sum / a`` (a sum of base radii over a
    centre distance), or a ``cos_w`` computed so."""
    node = _unwrapped(node)
    if isinstance(node, (ast.Name, ast.Attribute)):
        return _name(node).startswith("cos_")
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div)):
        return False
    top = node.left
    text = ast.unparse(top)
    if isinstance(top, ast.BinOp) and isinstance(top.op, (ast.Add, ast.Sub)):
        return "base" in text or "rb" in text
    if isinstance(top, ast.BinOp) and isinstance(top.op, ast.Mult):
        return any(_call(n, "cos") for n in ast.walk(top))
    return isinstance(top, (ast.Name, ast.Attribute)) and (_name(top).endswith("_sum") or "cos" in _name(top))


def _mentions_sin(node: ast.AST) -> bool:
    return any(_call(n, "sin") for n in ast.walk(node))


def _is_roll_length(node: ast.AST) -> bool:
    """``sqrt(r_a^2 - r_b^2)`` of a tip and a base radius, or the home's ``roll_length(r_a, r_b)``."""
    if _call(node, "roll_length"):
        return True
    if not _call(node, "sqrt") or not node.args:
        return False
    arg = _unwrapped(node.args[0])
    return (isinstance(arg, ast.BinOp) and isinstance(arg.op, ast.Sub)
            and any(k in ast.unparse(arg.right) for k in ("rb", "base", "cos")))


def formula_copies(path: Path) -> list[tuple[int, str, str]]:
    """(line, formula, source) of every copy of a home's formula in ``path``."""
    tree = ast.parse(path.read_text(), str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub):
            # tan(a) - a
            if _call(node.left, "tan") and node.left.args and ast.dump(node.left.args[0]) == ast.dump(node.right):
                found.append((node.lineno, "involute", ast.unparse(node)))
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
            # sqrt(r_a1^2 - r_b1^2) +- sqrt(r_a2^2 - r_b2^2) -+ a sin(alpha_w), in either order
            rolls = [n for n in ast.walk(node) if _is_roll_length(n)]
            if len(rolls) >= 2 and _mentions_sin(node):
                found.append((node.lineno, "line of action", ast.unparse(node)))
        if _call(node, "acos", "arccos") and node.args and _is_base_sum_over_distance(node.args[0]):
            found.append((node.lineno, "working pressure angle", ast.unparse(node)))
        # 2 R (inv(alpha_w) - inv(alpha_0)), the involutes written as involute() or tan(a) - a
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):
            factors = [node.left, node.right]
            two = any(isinstance(n, ast.Constant) and n.value in (2, 2.0) for f in factors for n in ast.walk(f))
            difference = [f for f in factors if isinstance(f, ast.BinOp) and isinstance(f.op, ast.Sub)]
            if two and difference and "inv" in ast.unparse(difference[0]) and any(
                    _call(n, "involute", "tan") or (isinstance(n, ast.Name) and n.id.startswith("tan"))
                    for n in ast.walk(difference[0].left)):
                found.append((node.lineno, "backlash at a centre distance", ast.unparse(node)))
        # the Greville abscissae: [t[j + 1:j + p + 1].mean() for j in ...]
        if isinstance(node, ast.ListComp) and _call(node.elt, "mean") and isinstance(node.elt.func, ast.Attribute) \
                and isinstance(node.elt.func.value, ast.Subscript):
            found.append((node.lineno, "Greville abscissae", ast.unparse(node)))
        # a boolean's arguments and tools set by hand, the kernel's plain volume integration
        if _call(node, "SetArguments"):
            found.append((node.lineno, "kernel boolean", ast.unparse(node)))
        if _call(node, "VolumeProperties_s"):
            found.append((node.lineno, "kernel volume", ast.unparse(node)))
    # a least-squares fit on a B-spline basis (the basis of a design matrix solved by lstsq)
    calls = {_name(n.func) for n in ast.walk(tree) if isinstance(n, ast.Call)}
    if {"design_matrix", "lstsq"} <= calls:
        line = min(n.lineno for n in ast.walk(tree) if _call(n, "design_matrix"))
        found.append((line, "B-spline fit", "BSpline.design_matrix(...) solved by np.linalg.lstsq"))
    # the same site is found once per formula
    return sorted(set(found))


def _sources() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def _copies_outside_homes() -> list[str]:
    problems = []
    for path in _sources():
        rel = path.relative_to(PACKAGE).as_posix()
        for line, formula, text in formula_copies(path):
            if rel == HOMES[formula] or (rel, formula) in ALLOWED:
                continue
            problems.append(f"geargen/{rel}:{line}: {formula}: {text}")
    return problems


def test_no_formula_is_written_outside_its_home():
    problems = _copies_outside_homes()
    assert not problems, ("formulas written again outside their home (call geargen.core.involute's function "
                          "instead):\n" + "\n".join(problems))


def test_every_allowed_copy_is_still_one():
    """An allowance whose copy is gone is removed (the list stays the copies that exist)."""
    sites = {(p.relative_to(PACKAGE).as_posix(), f) for p in _sources() for _, f, _ in formula_copies(p)}
    assert set(ALLOWED) <= sites, sorted(set(ALLOWED) - sites)


def test_the_homes_hold_each_formula():
    """The scan recognises each formula in its home (else it could not find a copy anywhere)."""
    found = {f for _, f, _ in formula_copies(PACKAGE / "core/involute.py")}
    assert {"involute", "working pressure angle", "backlash at a centre distance", "line of action"} <= found, found
    found = {f for _, f, _ in formula_copies(PACKAGE / "profile/bspline_fit.py")}
    assert {"B-spline fit", "Greville abscissae"} <= found, found
    found = {f for _, f, _ in formula_copies(PACKAGE / "cad/kernel.py")}
    assert {"kernel boolean", "kernel volume"} <= found, found


def test_the_scan_finds_each_form_of_copy(tmp_path):
    """The forms the copies had, written here, and look-alikes the scan must leave alone."""
    copy = tmp_path / "copy.py"
    copy.write_text(
        "import math\nimport numpy as np\n"
        "def f(rb1, rb2, a, ra1, ra2, alpha, inv0, base_sum, c_std, alpha_t):\n"
        "    x = np.tan(alpha) - alpha\n"
        "    w = math.acos((rb1 + rb2) / a)\n"
        "    w2 = np.arccos(np.clip(base_sum / a, -1, 1))\n"
        "    w3 = math.acos(min(1.0, (rb2 - rb1) / a))\n"
        "    w4 = np.arccos(c_std * np.cos(alpha_t) / a)\n"
        "    j = 2.0 * (rb1 + rb2) * (involute(w) - inv0)\n"
        "    g = math.sqrt(ra1 ** 2 - rb1 ** 2) + math.sqrt(ra2 ** 2 - rb2 ** 2) - a * math.sin(w)\n"
        "    design = BSpline.design_matrix(s, t, 3).toarray()\n"
        "    poles = np.linalg.lstsq(design, y, rcond=None)[0]\n"
        "    gr = np.array([t[j + 1:j + 4].mean() for j in range(len(t) - 4)])\n"
        "    return x, w, w2, w3, w4, j, g\n")
    kinds = [f for _, f, _ in formula_copies(copy)]
    assert kinds.count("involute") == 1
    assert kinds.count("working pressure angle") == 4
    assert kinds.count("backlash at a centre distance") == 1
    assert kinds.count("line of action") == 1
    assert kinds.count("B-spline fit") == 1 and kinds.count("Greville abscissae") == 1
    alike = tmp_path / "alike.py"
    alike.write_text(
        "import math\nimport numpy as np\n"
        "def f(rb, r, a, b, alpha):\n"
        "    p = np.arccos(np.clip(rb / r, -1.0, 1.0))\n"  # pressure angle at a radius: not a working angle
        "    q = math.tan(a) - b\n"
        "    s = math.sqrt(r ** 2 - rb ** 2) - a * math.tan(alpha)\n"
        "    values = BSpline.design_matrix(x, t, 3).toarray() @ poles\n"  # evaluation, not a fit
        "    return p, q, s\n")
    assert formula_copies(alike) == []


# ------------------------------------------------------------------ private names across modules

def private_imports(package: Path) -> list[str]:
    """``path:line: module.name`` of every private name (one leading underscore) imported from another
    geargen module."""
    found = []
    for path in sorted(package.rglob("*.py")):
        own = ".".join(path.relative_to(ROOT).with_suffix("").parts)
        tree = ast.parse(path.read_text(), str(path))
        modules = {}  # local name -> another geargen module it is bound to (``from geargen.report import drawing``)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").startswith("geargen") \
                    and node.module != own:
                found += [f"{path.relative_to(ROOT)}:{node.lineno}: {node.module}.{a.name}" for a in node.names
                          if _private(a.name)]
                for a in node.names:
                    target = ROOT.joinpath(*node.module.split("."), a.name)
                    if target.with_suffix(".py").is_file() or target.is_dir():
                        modules[a.asname or a.name] = f"{node.module}.{a.name}"
            elif isinstance(node, ast.Import):
                modules.update({a.asname: a.name for a in node.names if a.asname and a.name.startswith("geargen")})
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules \
                    and _private(node.attr) and modules[node.value.id] != own:
                found.append(f"{path.relative_to(ROOT)}:{node.lineno}: {modules[node.value.id]}.{node.attr}")
    return found


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def test_no_module_imports_a_private_name_of_another():
    """On main before issue 26's helpers: 64 names in 25 imports (29 in cad/, the kernel helpers)."""
    found = private_imports(PACKAGE)
    assert not found, "modules import another module's private names (make them public, the kernel helpers in " \
                      "geargen/cad/kernel.py):\n" + "\n".join(found)


def test_the_private_import_scan_finds_one(tmp_path):
    (tmp_path / "geargen").mkdir()
    (tmp_path / "geargen" / "m.py").write_text("from geargen.cad.gear_solid import build_gear, _x\n"
                                               "from geargen.cad.gear_solid import __all__\n"
                                               "from geargen import cad as kernel_side\n"
                                               "y = kernel_side._hidden + kernel_side.__name__\n")
    (tmp_path / "geargen" / "cad").mkdir()
    global ROOT
    saved, ROOT = ROOT, tmp_path
    try:
        assert private_imports(tmp_path / "geargen") == ["geargen/m.py:1: geargen.cad.gear_solid._x",
                                                         "geargen/m.py:4: geargen.cad._hidden"]
    finally:
        ROOT = saved


# ------------------------------------------------------------------ the homes against closed forms

def test_involute_and_its_inverse():
    # inv(20 deg) = 0.014904383867336 (involute tables, e.g. KHK's; tan 20 deg - 20 pi/180 written out)
    assert involute(20 * DEG) == pytest.approx(0.014904383867336, abs=1e-15)  # 15 digits of the table value
    angles = np.linspace(0.01, 1.5, 50)
    # Newton to machine precision: the round trip is good to a few ulp of the angle
    assert np.allclose(inverse_involute(involute(angles)), angles, rtol=0, atol=1e-13)


def test_working_pressure_angle_of_khk_profile_shifted_pair():
    # KHK "Gear Technical Reference", profile-shifted spur gears (Table 4.x): m = 3, alpha = 20 deg,
    # z = 12 and 24, x = 0.6 and 0.36: inv alpha_w = 0.034316, alpha_w = 26.0886 deg, a = 56.4999 mm
    base_sum = (12 + 24) * 3 / 2 * math.cos(20 * DEG)
    alpha_w = working_pressure_angle_at(base_sum, 56.4999)
    # a printed to 1e-4 mm moves alpha_w by <= 0.5e-4 * cot(alpha_w) / a = 1.8e-6 rad = 1.0e-4 deg;
    # alpha_w itself printed to 0.5e-4 deg
    assert alpha_w / DEG == pytest.approx(26.0886, abs=1.5e-4)
    assert involute(alpha_w) == pytest.approx(0.034316, abs=1e-5)  # printed to 1e-6, a's rounding ~7e-6
    # the same angle from the profile shifts (geometry's shift form), at that form's exact centre distance
    from geargen.core.geometry import working_centre_distance, working_pressure_angle
    from_shifts = working_pressure_angle(0.96, 36, 20 * DEG)
    a_exact = working_centre_distance(0.96, 36, 3.0, 20 * DEG)
    assert a_exact == pytest.approx(56.4999, abs=0.5e-4)  # KHK's a, printed to 1e-4 mm
    assert working_pressure_angle_at(base_sum, a_exact) == pytest.approx(from_shifts, abs=1e-14)  # round-off


def test_working_pressure_angle_outside_the_base_circles_and_arrays():
    assert math.isnan(working_pressure_angle_at(50.0, 49.0))
    assert working_pressure_angle_at(50.0, 49.0, clamp=True) == 0.0
    a = np.array([49.0, 50.0, 60.0])
    out = working_pressure_angle_at(50.0, a)
    assert np.isnan(out[0]) and out[1] == 0.0 and out[2] == pytest.approx(math.acos(50 / 60), abs=1e-15)
    # plain floats and numpy values give the same angle to the last bit or two
    assert float(working_pressure_angle_at(np.float64(50.0), 60.0)) == pytest.approx(
        working_pressure_angle_at(50.0, 60.0), rel=4e-16)


@pytest.mark.parametrize("alpha_w_deg", [14.5, 20.0, 26.0886])
def test_backlash_change_for_a_small_centre_distance_change(alpha_w_deg):
    # opening the centre distance by da from a tight mesh at alpha_0 adds 2 tan(alpha_w) da of arc on
    # the working pitch circles (to first order); the exact involute expression written out here
    base_sum = 50.0
    a0 = base_sum / math.cos(alpha_w_deg * DEG)
    alpha_0 = math.acos(base_sum / a0)
    for da in (1e-3, 1e-2):
        a = a0 + da
        alpha_w = math.acos(base_sum / a)
        exact_base = 2 * base_sum * ((math.tan(alpha_w) - alpha_w) - (math.tan(alpha_0) - alpha_0))
        j_bt = backlash_change(base_sum, alpha_w, involute(alpha_0))
        assert j_bt == pytest.approx(exact_base, rel=1e-12)  # the same expression, other rounding
        j_wt = backlash_change(a, alpha_w, involute(alpha_0))  # working pitch circles: R = a
        # the second-order term is da / (2 a sin^2(alpha)) of the first (d tan(alpha_w)/da =
        # 1 / (a sin cos)); twice that is the tolerance, and it shrinks with da (a first-order claim)
        second_order = da / (a0 * math.sin(alpha_0) ** 2)
        assert j_wt == pytest.approx(2 * math.tan(alpha_0) * da, rel=second_order)
        assert j_bt == pytest.approx(2 * math.sin(alpha_0) * da, rel=second_order)  # along the line of action


def test_backlash_change_is_the_pair_backlash_of_geometry():
    """backlash_at_centre_distance (the pair's, from its tooth thicknesses) and the home agree."""
    from geargen.core.geometry import GearPair, backlash_at_centre_distance, tight_mesh_centre_distance
    from geargen.design.gear import GearSpec
    g1 = GearSpec(teeth=12, module=3.0, pressure_angle=20 * DEG, face_width=20.0, profile_shift=0.6, thinning=0.05)
    g2 = GearSpec(teeth=24, module=3.0, pressure_angle=20 * DEG, face_width=20.0, profile_shift=0.36)
    pair = GearPair(g1, g2)
    tight = tight_mesh_centre_distance(pair)
    base_sum = g1.base_radius + g2.base_radius
    b = backlash_at_centre_distance(pair, tight + 0.1)
    alpha_0 = math.acos(base_sum / tight)
    assert b.base_tangent == pytest.approx(backlash_change(base_sum, b.working_pressure_angle, involute(alpha_0)),
                                           abs=1e-12)  # mm; round-off of the two routes to the tight angle
    # at the tight mesh the thinning of 0.05 mm (reference arc) is the whole backlash at the shifts'
    # working centre distance: 2 a0 (inv alpha_w - inv alpha_0) on the reference circles
    from geargen.core.geometry import working_centre_distance
    a_shift = working_centre_distance(0.96, 36, 3.0, 20 * DEG)
    ref = backlash_change(pair.standard_centre_distance, math.acos(base_sum / a_shift), involute(alpha_0))
    assert ref == pytest.approx(0.05, abs=1e-12)  # mm: exact up to round-off


def _line_of_action_by_construction(ra1, rb1, ra2, rb2, a, internal):
    """The path of contact measured on the drawing: gear 1 at the origin, gear 2 at (a, 0); the line
    n.x = r_b1 tangent to both base circles (the centres on opposite sides of it for an external
    pair, on one side for an internal one); where it crosses the tip circles, from the quadratic
    |p0 + s t - centre|^2 = r_a^2; the length between the crossings that bound contact."""
    nx = (rb1 + rb2) / a if not internal else (rb1 - rb2) / a
    n = np.array([nx, math.sqrt(1 - nx * nx)])
    t = np.array([-n[1], n[0]])
    centre2 = np.array([a, 0.0])
    tangent2 = centre2 - (n @ centre2 - rb1) * n  # gear 2's tangent point: the foot of its centre
    p0 = rb1 * n  # gear 1's tangent point, s = 0
    s_t2 = float((tangent2 - p0) @ t)
    # external: T2 ahead of T1 (s > 0); internal: T2 behind it, the contact on the pinion's far side
    if (s_t2 < 0) != internal:
        t, s_t2 = -t, -s_t2

    def crossings(centre, radius):
        d = p0 - centre
        b, c = d @ t, d @ d - radius ** 2
        return np.roots([1.0, 2 * b, c]).real

    tip1, tip2 = crossings(np.zeros(2), ra1), crossings(centre2, ra2)
    if internal:
        return max(tip1) - max(tip2)  # the ring's tip crossing on the far side of T2 to the pinion's tip
    return max(tip1) - min(tip2)  # gear 2's tip crossing nearer T1 to gear 1's nearer T2


@pytest.mark.parametrize("z1,z2,x1,x2", [(20, 40, 0.0, 0.0), (12, 24, 0.6, 0.36), (17, 60, 0.3, -0.2)])
def test_length_of_action_of_an_external_pair_by_construction(z1, z2, x1, x2):
    m, alpha = 2.0, 20 * DEG
    rb1, rb2 = z1 * m / 2 * math.cos(alpha), z2 * m / 2 * math.cos(alpha)
    ra1, ra2 = (z1 / 2 + 1 + x1) * m, (z2 / 2 + 1 + x2) * m
    a = (z1 + z2) * m / 2 + 0.3 * m  # an operating centre distance a little open
    g = length_of_action((ra1, ra2), (rb1, rb2), a)
    # the construction solves quadratics in other variables: agrees to round-off
    assert g == pytest.approx(_line_of_action_by_construction(ra1, rb1, ra2, rb2, a, False), abs=1e-12)


def test_length_of_action_of_an_internal_pair_by_construction():
    m, alpha = 1.0, 20 * DEG
    z1, z2 = 20, 50
    rb1, rb2 = z1 * m / 2 * math.cos(alpha), z2 * m / 2 * math.cos(alpha)
    ra1, ra2 = (z1 / 2 + 1) * m, (z2 / 2 - 1) * m
    a = (z2 - z1) * m / 2
    g = length_of_action((ra1, ra2), (rb1, rb2), a, internal=True)
    assert g == pytest.approx(_line_of_action_by_construction(ra1, rb1, ra2, rb2, a, True), abs=1e-12)  # round-off


def test_roll_length_is_the_unwound_string():
    # the involute point at roll angle t lies at r = r_b sqrt(1 + t^2) and r_b t from its tangent point
    rb, t = 18.793852415718167, np.array([0.1, 0.5, 1.2])
    # r^2 - r_b^2 cancels ~1/t^2 of the digits (100x at t = 0.1): 1e-12 relative covers it
    assert np.allclose(roll_length(rb * np.sqrt(1 + t * t), rb), rb * t, rtol=1e-12, atol=0)
    assert roll_length(rb * 0.99, rb) == 0.0  # inside the base circle: no involute, no roll
