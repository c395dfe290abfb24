"""Load capacity (ISO 6336-2/-3:2019 method B): the published ISO/TR 6336-30 example 1 through
``geargen pair``, a spur and a helical case worked by hand factor by factor (the arithmetic written
out here, not a call of geargen.core.load_capacity), Y_F's critical section against the generated
trochoid, the face width solve, the damage sum, the families ISO 6336 does not cover."""

import json
import math

import numpy as np
import pytest

from geargen.cli import main
from geargen.core import load_capacity as lc
from geargen.core.iso6336_materials import MATERIALS, Material, allowable_stress
from geargen.design.gear import GearSpec
from geargen.errors import DesignError

DEG = math.pi / 180


def inv(a):
    return math.tan(a) - a


def run_pair(capsys, *options):
    """``geargen pair OPTIONS --json -``: (exit status, JSON, table)."""
    code = main(["pair", *options, "--json", "-"])
    out, err = capsys.readouterr()
    assert code in (0, 1), err
    return code, json.loads(out), err


# ISO/TR 6336-30:2017 Annex A example 1: m_n 8, z 17/103, x 0.145/0, beta 15.8 deg, b 100, a 500,
# basic rack h_fP 1.4 m_n (ISO 53 profile D, rho_fP 0.39 m_n), T1 9000 N m at 360 rpm, case carburised
# MQ, 50 000 h, K_A 1, K_Hbeta 1.16 given, ISO 1328 grade 5, Ra 1 um, ISO VG 320, C_a 70 um
TR_EXAMPLE_1 = ["--teeth", "17", "103", "--module", "8", "--helix-angle", "15.8", "--profile-shift", "0.145", "0",
                "--face-width", "100", "--centre-distance", "500", "--dedendum-coefficient", "1.4",
                "--rack-tip-radius", "0.39", "--torque", "9000", "--speed", "360", "--life", "50000",
                "--material", "case_carburised", "--quality", "MQ", "--application-factor", "1",
                "--face-load-factor", "1.16", "--accuracy-grade", "5", "--roughness", "1", "--viscosity", "320",
                "--tip-relief", "70", "--minimum-safety", "1.0", "1.4"]


def test_tr_6336_30_example_1_pitting_reproduces_the_published_values(capsys):
    # The published values of ISO/TR 6336-30:2017 Annex A example 1, as tabulated (column "Reference")
    # in MATISO_6336.example_01 of github.com/gfsReboucas/Drivetrain: sigma_H0 1206.58207, K_Hbeta 1.16,
    # Z_NT 0.91 / 0.962, sigma_HP 1338.48050 / 1414.52551, S_H 1.02853 / 1.08696 (S_Hmin 1), and from the
    # same column F_t 127352, v 2.664, K_v 1.003, Z_L 1.04739, Z_v 0.96911, Z_R 0.96599, Z_E 189.8117,
    # Z_H 2.39533, Z_beta 1.01944, Z_eps 0.803, K_Fbeta 1.12803, N_L 1.080e9 / 1.783e8.
    # Tolerance 1 %: the issue's; the published values carry 3 to 6 digits.
    code, data, table = run_pair(capsys, *TR_EXAMPLE_1)
    lc_block = data["load_capacity"]
    published = {"sigma_H0": 1206.58207, "K_Hbeta": 1.16, "F_t": 127352.0, "v": 2.664, "K_v": 1.003,
                 "Z_L": 1.04739, "Z_v": 0.96911, "Z_R": 0.96599, "Z_E": 189.81170, "Z_H": 2.39533,
                 "Z_beta": 1.01944, "Z_eps": 0.803, "K_Fbeta": 1.12803, "K_Halpha": 1.0, "K_Falpha": 1.0}
    for key, value in published.items():
        assert lc_block[key] == pytest.approx(value, rel=1e-2), key
    for key, values in {"Z_NT": (0.91, 0.962), "sigma_HP": (1338.48050, 1414.52551), "S_H": (1.02853, 1.08696),
                        "N_L": (1.080e9, 1.783e8), "Z_BD": (1.0, 1.0)}.items():
        assert lc_block[key] == pytest.approx(list(values), rel=1e-2), key
    # closer than the issue asks: every published digit but sigma_H0's last (1206.48 against 1206.58)
    assert lc_block["S_H"] == pytest.approx([1.02853, 1.08696], abs=6e-5)
    assert lc_block["sigma_HP"] == pytest.approx([1338.48050, 1414.52551], abs=1e-2)
    assert lc_block["sigma_H0"] == pytest.approx(1206.58207, rel=1e-4)
    assert lc_block["standard"] == "ISO 6336-2:2019 / ISO 6336-3:2019, method B"
    assert code == 0 and lc_block["ok"] is True  # S_H >= 1, S_F >= 1.4
    line = next(l for l in table.splitlines() if l.startswith("safety factor S_H"))
    assert line.split()[-2:] == [f"{v:.4f}" for v in lc_block["S_H"]]


# ---------------------------------------------------------------------------------------------
# The hand calculation: ISO 6336 written out again, factor by factor
# ---------------------------------------------------------------------------------------------

def iso1328_round(v):
    """ISO 1328-1:2013 5.2.3: above 10 um to 1 um, 5..10 um to 0.5 um, below to 0.1 um."""
    step = 1.0 if v > 10 else 0.5 if v >= 5 else 0.1
    return math.floor(v / step + 0.5) * step


def hand_method_b_root(z, x, m, a_n, beta, beta_b, d, d_a, eps_a, h_fp, rho_fp):
    """ISO 6336-3 method B, spelt out: Y_F, Y_S and the critical section."""
    z_n = z / (math.cos(beta_b) ** 2 * math.cos(beta))
    eps_an = eps_a / math.cos(beta_b) ** 2
    E = math.pi / 4 * m - h_fp * math.tan(a_n) - (1 - math.sin(a_n)) * rho_fp / math.cos(a_n)
    G = rho_fp / m - h_fp / m + x
    H = 2 / z_n * (math.pi / 2 - E / m) - math.pi / 3
    th = math.pi / 6
    for _ in range(100):
        th = 2 * G / z_n * math.tan(th) - H
    s_fn = m * (z_n * math.sin(math.pi / 3 - th) + math.sqrt(3) * (G / math.cos(th) - rho_fp / m))
    rho_f = rho_fp + 2 * G * G * m / (math.cos(th) * (z_n * math.cos(th) ** 2 - 2 * G))
    d_n = m * z_n
    d_bn = d_n * math.cos(a_n)
    d_an = d_n + d_a - d
    d_en = 2 * math.sqrt((math.sqrt((d_an / 2) ** 2 - (d_bn / 2) ** 2)
                          - math.pi * d * math.cos(beta) * math.cos(a_n) / z * (eps_an - 1)) ** 2 + (d_bn / 2) ** 2)
    a_en = math.acos(d_bn / d_en)
    g_e = (0.5 * math.pi + 2 * x * math.tan(a_n)) / z_n + inv(a_n) - inv(a_en)
    a_fen = a_en - g_e
    h_fe = 0.5 * m * ((math.cos(g_e) - math.sin(g_e) * math.tan(a_fen)) * d_en / m - z_n * math.cos(math.pi / 3 - th)
                      - G / math.cos(th) + rho_fp / m)
    y_f = 6 * h_fe / m * math.cos(a_fen) / ((s_fn / m) ** 2 * math.cos(a_n))
    L = s_fn / h_fe
    q_s = s_fn / (2 * rho_f)
    y_s = (1.2 + 0.13 * L) * q_s ** (1 / (1.21 + 2.3 / L))
    return {"Y_F": y_f, "Y_S": y_s, "s_Fn": s_fn, "rho_F": rho_f, "h_Fe": h_fe, "q_s": q_s}


def log_interp(n, n0, f0, n1, f1):
    return f0 * (f1 / f0) ** (math.log(n / n0) / math.log(n1 / n0))


def hand_rating(c, block):
    """Every factor of ``c`` (the case's inputs) by hand; c' and c_gamma (ISO 6336-1's stiffness, the
    tested geargen.core.iso6336) are read from ``block``."""
    m, a_n, beta = c["m"], c["alpha_n"] * DEG, c["beta"] * DEG
    z1, z2 = c["z"]
    x1, x2 = c["x"]
    b, a = c["b"], c["a"]
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    beta_b = math.asin(math.sin(beta) * math.cos(a_n))
    d = [z * m / math.cos(beta) for z in (z1, z2)]
    db = [di * math.cos(a_t) for di in d]
    da = [di + 2 * m * (c["h_a"] + xi) for di, xi in zip(d, (x1, x2))]
    df = [di - 2 * m * (c["h_fp"] - xi) for di, xi in zip(d, (x1, x2))]
    a_wt = math.acos((db[0] + db[1]) / (2 * a))
    p_bt = math.pi * m / math.cos(beta) * math.cos(a_t)
    roll = [math.sqrt(da[i] ** 2 - db[i] ** 2) / 2 for i in (0, 1)]
    eps_a = (roll[0] + roll[1] - a * math.sin(a_wt)) / p_bt
    eps_b = b * math.sin(beta) / (math.pi * m)
    eps_g = eps_a + eps_b
    u = z2 / z1
    h = {}
    f_t = h["F_t"] = 2000 * c["T"] / d[0]
    v = h["v"] = math.pi * d[0] * c["n"] / 60000
    k_a = c["K_A"]
    # --- K_v, ISO 6336-1 method B, subcritical (N <= N_S)
    step = math.sqrt(2) ** (c["grade"] - 5)
    f_pb = max(iso1328_round((0.001 * di + 0.4 * m + 5) * step) for di in d)
    f_fa = iso1328_round((0.55 * m + 5) * step)
    f_hb = max(iso1328_round((0.05 * math.sqrt(di) + 0.35 * math.sqrt(b) + 4) * step) for di in d)
    hlim = c["sigma_Hlim"]
    if c["surface_hardened"]:
        y_a, y_f = min(0.075 * f_pb, 3), min(0.075 * f_fa, 3)
    else:
        y_a, y_f = 160 / hlim * f_pb, 160 / hlim * f_fa  # v <= 5 m/s: no limit
        assert v <= 5
    c_p, c_ga = block["c_prime"], block["c_gamma_alpha"]
    dm = [(da[i] + df[i]) / 2 for i in (0, 1)]
    mass = [math.pi / 8 * 7.83e-6 * dm[i] ** 4 / db[i] ** 2 for i in (0, 1)]
    m_red = mass[0] * mass[1] / (mass[0] + mass[1])
    n_e1 = 30000 / (math.pi * z1) * math.sqrt(c_ga / m_red)
    ratio = c["n"] / n_e1
    w = f_t * k_a / b
    n_s = 0.85 if w >= 100 else 0.5 + 0.35 * math.sqrt(w / 100)
    assert ratio <= n_s, "the hand case is subcritical"
    cv2, cv3 = (0.34, 0.23) if eps_g <= 2 else (0.57 / (eps_g - 0.3), 0.096 / (eps_g - 1.56))
    b_p, b_f = c_p * (f_pb - y_a) / w, c_p * (f_fa - y_f) / w
    b_k = abs(1 - c_p * c["C_a"] / w)
    k_v = h["K_v"] = ratio * (0.32 * b_p + cv2 * b_f + cv3 * b_k) + 1
    # --- K_Hbeta: given, or method C (stiff pinion shaft centred, f_ma = f_HbetaT)
    if c["K_Hbeta"] is not None:
        k_hb = c["K_Hbeta"]
    else:
        f_m = f_t * k_a * k_v
        f_bx = max(1.33 * 0.023 * f_m / b * (b / d[0]) ** 2 + f_hb, 0.005 * f_m / b, 0.5 * f_hb)
        y_b = min(0.15 * f_bx, 6) if c["surface_hardened"] else 320 / hlim * f_bx
        cgb = 0.85 * c_ga
        k = cgb * (f_bx - y_b) / (2 * f_m / b)
        k_hb = 1 + k if k <= 1 else 2 * math.sqrt(k)
    h["K_Hbeta"] = k_hb
    bh = max(min(b / ((c["h_a"] + c["h_fp"]) * m), b / ((c["h_a"] + c["h_fp"]) * m)), 3)
    h["K_Fbeta"] = k_hb ** (bh ** 2 / (1 + bh + bh ** 2))
    # --- Z factors
    z_h = h["Z_H"] = math.sqrt(2 * math.cos(beta_b) * math.cos(a_wt) / (math.cos(a_t) ** 2 * math.sin(a_wt)))
    z_e = h["Z_E"] = math.sqrt(1 / (math.pi * 2 * (1 - 0.3 ** 2) / 206000))
    z_eps = h["Z_eps"] = (math.sqrt((4 - eps_a) / 3) if eps_b == 0 else math.sqrt(1 / eps_a) if eps_b >= 1
                          else math.sqrt((4 - eps_a) / 3 * (1 - eps_b) + eps_b / eps_a))
    z_beta = h["Z_beta"] = 1 / math.sqrt(math.cos(beta))
    # K_Halpha = K_Falpha (method B), F_tH = F_t K_A K_v K_Hbeta
    f_th = f_t * k_a * k_v * k_hb
    k_al = (eps_g / 2 * (0.9 + 0.4 * c_ga * (f_pb - y_a) / (f_th / b)) if eps_g <= 2
            else 0.9 + 0.4 * math.sqrt(2 * (eps_g - 1) / eps_g) * c_ga * (f_pb - y_a) / (f_th / b))
    h["K_Halpha"] = min(max(k_al, 1), eps_g / (eps_a * z_eps ** 2))
    h["K_Falpha"] = min(max(k_al, 1), eps_g / (0.25 * eps_a + 0.75))
    # Z_B, Z_D: ISO 6336-2's M_1, M_2
    M1 = math.tan(a_wt) / math.sqrt((math.sqrt(da[0] ** 2 / db[0] ** 2 - 1) - 2 * math.pi / z1)
                                     * (math.sqrt(da[1] ** 2 / db[1] ** 2 - 1) - (eps_a - 1) * 2 * math.pi / z2))
    M2 = math.tan(a_wt) / math.sqrt((math.sqrt(da[1] ** 2 / db[1] ** 2 - 1) - 2 * math.pi / z2)
                                     * (math.sqrt(da[0] ** 2 / db[0] ** 2 - 1) - (eps_a - 1) * 2 * math.pi / z1))
    if eps_b >= 1:
        zb = zd = 1.0
    else:
        zb, zd = (max(1.0, Mi - eps_b * (Mi - 1)) for Mi in (M1, M2))
    h["Z_BD"] = [zb, zd]
    s_h0 = h["sigma_H0"] = z_h * z_e * z_eps * z_beta * math.sqrt(f_t * (u + 1) / (d[0] * b * u))
    kh = k_a * k_v * k_hb * h["K_Halpha"]
    h["sigma_H"] = [zb * s_h0 * math.sqrt(kh), zd * s_h0 * math.sqrt(kh)]
    n_l = h["N_L"] = [60 * c["n"] * c["life"], 60 * c["n"] * c["life"] / u]
    # Z_NT: ISO 6336-2 Table 2, no pitting permitted: 1.6 to 1e5, 1.0 at 5e7, 0.85 at 1e10 (log-log)
    h["Z_NT"] = [1.6 if n <= 1e5 else log_interp(n, 1e5, 1.6, 5e7, 1.0) if n <= 5e7
                 else log_interp(n, 5e7, 1.0, 1e10, 0.85) for n in n_l]
    czl = 0.83 if hlim < 850 else 0.91 if hlim > 1200 else hlim / 4375 + 0.6357
    z_l = h["Z_L"] = czl + 4 * (1 - czl) / (1.2 + 134 / c["nu40"]) ** 2
    czv = czl + 0.02
    z_v = h["Z_v"] = czv + 2 * (1 - czv) / math.sqrt(0.8 + 32 / v)
    rho = [db[i] / 2 * math.tan(a_wt) for i in (0, 1)]
    rz10 = 6 * c["Ra"] * (10 / (rho[0] * rho[1] / (rho[0] + rho[1]))) ** (1 / 3)
    czr = 0.15 if hlim < 850 else 0.08 if hlim > 1200 else 0.32 - 0.0002 * hlim
    z_r = h["Z_R"] = (3 / rz10) ** czr
    h["sigma_HP"] = [hlim * zn * z_l * z_v * z_r / c["S_Hmin"] for zn in h["Z_NT"]]
    h["S_H"] = [hlim * zn * z_l * z_v * z_r / s for zn, s in zip(h["Z_NT"], h["sigma_H"])]
    # --- tooth root
    roots = [hand_method_b_root(z, xi, m, a_n, beta, beta_b, di, dai, eps_a, c["h_fp"] * m, c["rho_fp"] * m)
             for z, xi, di, dai in zip((z1, z2), (x1, x2), d, da)]
    h["Y_F"] = [r["Y_F"] for r in roots]
    h["Y_S"] = [r["Y_S"] for r in roots]
    y_beta = h["Y_beta"] = 1 - min(eps_b, 1) * min(c["beta"], 30) / 120
    h["sigma_F0"] = [f_t / (b * m) * r["Y_F"] * r["Y_S"] * y_beta for r in roots]
    kf = k_a * k_v * h["K_Fbeta"] * h["K_Falpha"]
    h["sigma_F"] = [s * kf for s in h["sigma_F0"]]
    y_nt = h["Y_NT"] = [c["Y_NT"](n) for n in n_l]
    rho_p = c["rho_prime"]
    h["Y_deltarelT"] = [(1 + math.sqrt(rho_p * (1 + 2 * r["q_s"]) / 5)) / (1 + math.sqrt(rho_p * 1.2)) for r in roots]
    rz = 6 * c["Ra"]
    y_r = 1.120 if rz < 1 else 1.674 - 0.529 * (rz + 1) ** 0.1  # V, Eh, IF
    h["Y_RrelT"] = [y_r, y_r]
    y_x = (1.0 if m <= 5 else (1.05 - 0.01 * m) if c["surface_hardened"] else (1.03 - 0.006 * m))
    h["Y_X"] = [y_x, y_x]
    fe = c["sigma_FE"]
    h["sigma_FP"] = [fe * yn * yd * y_r * y_x / c["S_Fmin"] for yn, yd in zip(y_nt, h["Y_deltarelT"])]
    h["S_F"] = [fe * yn * yd * y_r * y_x / s for yn, yd, s in zip(y_nt, h["Y_deltarelT"], h["sigma_F"])]
    return h


def assert_factors(block, hand, rel):
    for key, value in hand.items():
        assert block[key] == pytest.approx(value, rel=rel), key


def eh_root_life(n):
    """Y_NT, ISO 6336-3 Table 3, Eh/IF: 2.5 to 1e3 cycles, 1.0 at 3e6, 0.85 at 1e10 (log-log)."""
    return 2.5 if n <= 1e3 else log_interp(n, 1e3, 2.5, 3e6, 1.0) if n <= 3e6 else log_interp(n, 3e6, 1.0, 1e10, 0.85)


def v_root_life(n):
    """Y_NT, ISO 6336-3 Table 3, V: 2.5 to 1e4 cycles, 1.0 at 3e6, 0.85 at 1e10 (log-log)."""
    return 2.5 if n <= 1e4 else log_interp(n, 1e4, 2.5, 3e6, 1.0) if n <= 3e6 else log_interp(n, 3e6, 1.0, 1e10, 0.85)


TR_CASE = {"m": 8, "alpha_n": 20, "beta": 15.8, "z": (17, 103), "x": (0.145, 0.0), "b": 100, "a": 500, "h_a": 1.0,
           "h_fp": 1.4, "rho_fp": 0.39, "T": 9000, "n": 360, "life": 50000, "K_A": 1.0, "K_Hbeta": 1.16, "grade": 5,
           "Ra": 1.0, "nu40": 320, "C_a": 70, "surface_hardened": True, "sigma_Hlim": 1500.0,
           # ISO 6336-5 Table 8, case carburised MQ (core >= 30 HRC): sigma_Flim 500, sigma_FE = 2 x 500
           "sigma_FE": 1000.0, "rho_prime": 0.0030, "Y_NT": eh_root_life, "S_Hmin": 1.0, "S_Fmin": 1.4}


def test_tr_6336_30_example_1_bending_by_hand(capsys):
    # The example's published root results could not be found; the bending chain is worked by hand
    # (hand_rating, every factor of ISO 6336-3 method B written out above) for the example's data.
    # Tolerance 1e-9: the same formulas evaluated twice; only the theta iteration's stopping differs.
    _, data, _ = run_pair(capsys, *TR_EXAMPLE_1)
    block = data["load_capacity"]
    hand = hand_rating(TR_CASE, block)
    assert_factors(block, hand, rel=1e-9)
    # the resulting safety factors, rounded as printed: pinion 1.9860, wheel 2.1221
    assert block["S_F"] == pytest.approx([1.98598, 2.12209], abs=1e-5)


#: geargen's default rack tip radius where ISO 53 A's 0.38 m_n does not fit: the largest whose arc stays
#: within the clearance (h_fP - h_aP) m_n = 0.25 m_n, rho = 0.25 / (1 - sin 20 deg) = 0.37995 m_n
RHO_FITTING = 0.25 / (1 - math.sin(20 * DEG))

SPUR_CASE = {"m": 4, "alpha_n": 20, "beta": 0.0, "z": (21, 47), "x": (0.25, -0.1), "b": 36, "a": 136.5, "h_a": 1.0,
             "h_fp": 1.25, "rho_fp": RHO_FITTING, "T": 180, "n": 1000, "life": 20000, "K_A": 1.25, "K_Hbeta": 1.3,
             "grade": 6, "Ra": 0.8, "nu40": 150, "C_a": 0, "surface_hardened": False,
             # ISO 6336-5 Table 8, through hardened alloy steel MQ at 300 HV: 1.313 x 300 + 373 and
             # 2 (0.425 x 300 + 187); rho' 0.0064 mm (0.2 % proof stress 800 N/mm^2)
             "sigma_Hlim": 1.313 * 300 + 373, "sigma_FE": 2 * (0.425 * 300 + 187), "rho_prime": 0.0064,
             "Y_NT": v_root_life, "S_Hmin": 1.0, "S_Fmin": 1.4}
SPUR_OPTIONS = ["--teeth", "21", "47", "--module", "4", "--profile-shift", "0.25", "-0.1", "--face-width", "36",
                "--centre-distance", "136.5", "--torque", "180", "--speed", "1000", "--life", "20000",
                "--material", "through_hardened", "--hardness", "300", "--application-factor", "1.25",
                "--face-load-factor", "1.3", "--accuracy-grade", "6", "--roughness", "0.8", "--viscosity", "150"]


def test_spur_case_by_hand(capsys):
    # z 21/47, m 4, x 0.25/-0.1 at a = 136.5 mm (a little backlash), b 36, 180 N m at 1000 rpm for
    # 20 000 h, K_A 1.25, K_Hbeta 1.3, through hardened MQ 300 HV, grade 6, Ra 0.8, nu_40 150, no tip
    # relief. A spur pair below eps_alpha 2 has Z_B > 1 (the pinion's inner single contact).
    # Tolerance 1e-9: the same formulas evaluated twice.
    code, data, _ = run_pair(capsys, *SPUR_OPTIONS)
    block = data["load_capacity"]
    hand = hand_rating(SPUR_CASE, block)
    assert_factors(block, hand, rel=1e-9)
    assert block["Z_BD"][0] > 1.0 and block["Y_beta"] == 1.0 and block["Z_beta"] == 1.0
    assert code == (0 if block["ok"] else 1)


HELICAL_CASE = {"m": 3, "alpha_n": 20, "beta": 22.0, "z": (19, 64), "x": (0.3, 0.0), "b": 24, "a": 136.0,
                "h_a": 1.0, "h_fp": 1.25, "rho_fp": RHO_FITTING, "T": 160, "n": 1500, "life": 10000, "K_A": 1.1,
                "K_Hbeta": None, "grade": 5, "Ra": 0.5, "nu40": 220, "C_a": 15, "surface_hardened": True,
                "sigma_Hlim": 1500.0, "sigma_FE": 1000.0, "rho_prime": 0.0030, "Y_NT": eh_root_life,
                "S_Hmin": 1.0, "S_Fmin": 1.4}
HELICAL_OPTIONS = ["--teeth", "19", "64", "--module", "3", "--helix-angle", "22", "--profile-shift", "0.3", "0",
                   "--face-width", "24", "--centre-distance", "136", "--torque", "160", "--speed", "1500",
                   "--life", "10000", "--material", "case_carburised", "--application-factor", "1.1",
                   "--accuracy-grade", "5", "--roughness", "0.5", "--viscosity", "220", "--tip-relief", "15"]


def test_helical_case_by_hand(capsys):
    # z 19/64, m_n 3, beta 22 deg, x 0.3/0 at a = 136 mm, b 24 (eps_beta 0.95 < 1: Z_eps's blend),
    # 160 N m at 1500 rpm for 10 000 h, K_A 1.1, case carburised MQ, grade 5, Ra 0.5, nu_40 220, C_a 15 um;
    # K_Hbeta computed by method C (stiff pinion shaft centred, f_ma = f_HbetaT, running-in 0.15 F_betax).
    # Tolerance 1e-9: the same formulas evaluated twice.
    _, data, _ = run_pair(capsys, *HELICAL_OPTIONS)
    block = data["load_capacity"]
    hand = hand_rating(HELICAL_CASE, block)
    assert 0 < block["eps_beta"] < 1
    assert_factors(block, hand, rel=1e-9)
    assert block["K_Hbeta"] > 1.0 and "method C" in block["K_Hbeta_source"]


# ---------------------------------------------------------------------------------------------
# Y_F's critical section against the tooth geargen generates
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("teeth, shift, thinning", [(21, 0.25, 0.0), (47, -0.1, 0.0), (14, 0.5, 0.0),
                                                    (21, 0.25, 0.12), (14, 0.5, 0.3)])
def test_critical_section_is_the_30_degree_tangent_on_the_generated_trochoid(teeth, shift, thinning):
    # Method B's s_Fn and rho_F are closed forms for the point of the fillet where the tangent makes
    # 30 deg with the tooth's centreline. Measured here on the fillet geargen generates (the rack tip
    # circle rolled, geargen.core.geometry._rack_fillet_in_gear): the point is found by bisection on
    # the tangent's angle, rho_F as the radius of the circle through three close points.
    # Tolerance 1e-6 relative: the bisection resolves s_Fn to 1e-8 mm; the three-point radius with a
    # step of 1e-4 rad in the fillet's parameter is within 2e-7 of the curvature (smaller steps drown
    # in rounding: 1e-5 rad reads 3e-5 off).
    # A thinned gear is cut by a thicker rack tooth at the same infeed: its root section is
    # narrower (the sign of s_n/2 in E; it once widened the root).
    from geargen.core.geometry import _rack_fillet_in_gear

    spec = GearSpec(teeth=teeth, module=4.0, pressure_angle=20 * DEG, face_width=30.0, profile_shift=shift,
                    thinning=thinning)
    form = lc.tooth_root_form(teeth, shift, 4.0, 20 * DEG, 0.0, 0.0, spec.tip_radius - spec.reference_radius, 1.5,
                              1.25, spec.rack_tip_radius_coefficient, thinning_normal=thinning)
    if thinning:
        plain = lc.tooth_root_form(teeth, shift, 4.0, 20 * DEG, 0.0, 0.0, spec.tip_radius - spec.reference_radius,
                                   1.5, 1.25, spec.rack_tip_radius_coefficient)
        assert form.s_Fn < plain.s_Fn

    def point(t):
        r, phi = _rack_fillet_in_gear(spec, t)
        # the space is centred on +y; the tooth whose fillet this is has its centreline at
        # pi/2 -+ pi/z, on the fillet's side: rotate that centreline onto +y
        side = -1.0 if float(phi) < math.pi / 2 else 1.0
        a = float(phi) - (math.pi / 2 + side * math.pi / teeth)
        return np.array([-float(r) * math.sin(a), float(r) * math.cos(a)])  # x across, y along the centreline

    def tangent_angle(t):
        p, q = point(t - 1e-7), point(t + 1e-7)
        dx, dy = q - p
        return math.atan2(abs(dx), abs(dy))  # 0 along the centreline

    lo, hi = -math.pi / 2 + 1e-6, -20 * DEG - 1e-6
    f_lo = tangent_angle(lo) - 30 * DEG
    for _ in range(200):
        mid = (lo + hi) / 2
        if (tangent_angle(mid) - 30 * DEG) * f_lo > 0:
            lo, f_lo = mid, tangent_angle(mid) - 30 * DEG
        else:
            hi = mid
    t = (lo + hi) / 2
    assert 2 * abs(point(t)[0]) == pytest.approx(form.s_Fn, rel=1e-6)
    p1, p2, p3 = point(t - 1e-4), point(t), point(t + 1e-4)
    a, b, c = np.linalg.norm(p2 - p1), np.linalg.norm(p3 - p2), np.linalg.norm(p3 - p1)
    cross = abs((p2 - p1)[0] * (p3 - p1)[1] - (p2 - p1)[1] * (p3 - p1)[0])
    assert a * b * c / (2 * cross) == pytest.approx(form.rho_F, rel=1e-6)


# ---------------------------------------------------------------------------------------------
# Face width, spectra, materials, scope
# ---------------------------------------------------------------------------------------------

def helical_gears(face_width=24.0):
    g1 = GearSpec(teeth=19, module=3.0, pressure_angle=20 * DEG, face_width=face_width, helix_angle=22 * DEG,
                  hand="right", profile_shift=0.3)
    g2 = GearSpec(teeth=64, module=3.0, pressure_angle=20 * DEG, face_width=face_width, helix_angle=22 * DEG,
                  hand="left", profile_shift=0.0)
    return g1, g2


CONDITIONS = lc.RatingConditions(speed=1500, life=10000, accuracy_grade=5, roughness=0.5, viscosity=220,
                                 application_factor=1.1, tip_relief=15, minimum_safety=(1.1, 1.6))
CARBURISED = (Material("case_carburised"), Material("case_carburised"))


@pytest.mark.parametrize("given", [None, 1.25])
def test_rated_at_the_solved_face_width_the_safety_factor_is_the_minimum(given):
    # K_Hbeta computed (it changes with b through f_sh and the line load) and given
    g1, g2 = helical_gears()
    conditions = lc.RatingConditions(**{**CONDITIONS.__dict__, "face_load_factor": given})
    load = 2 * 160e3 / (19 * 3 / math.cos(22 * DEG))
    sol = lc.face_width_for_minimum_safety(lc.rating_geometry(g1, g2, 136.0), load, conditions, CARBURISED)
    assert sol.message == ""
    # rated at the returned widths with the mesh built anew for that width (not the solve's shortcut)
    at_h = lc.rate_pair(lc.rating_geometry(g1, g2, 136.0, sol.pitting), load, conditions, CARBURISED)
    at_f = lc.rate_pair(lc.rating_geometry(g1, g2, 136.0, sol.bending), load, conditions, CARBURISED)
    # 1e-6: the solve's tolerance is 1e-13 on log b; the safety factors are smooth in b
    assert min(at_h.S_H) == pytest.approx(1.1, abs=1e-6)
    assert min(at_f.S_F) == pytest.approx(1.6, abs=1e-6)
    assert sol.required == max(sol.pitting, sol.bending)


def test_one_level_spectrum_has_the_rated_safety_factor_and_damage_adds():
    # ISO 6336-6: D = sum n_i/N_i on the S-N curve of the life factor. A single level over the whole
    # life is the case rated alone, so the stress factor that makes D = 1 is S_H (S_F); two half
    # shares of the same load make the same D. Tolerance 1e-9: brentq's xtol 1e-12 on log S.
    g1, g2 = helical_gears()
    load = 9000.0
    whole = lc.rate_mesh(g1, g2, 136.0, [lc.LoadCase(load, "spectrum level 1", "drive", 1.0)], CONDITIONS, CARBURISED)
    (case, rating), = whole.cases
    spectrum, = whole.spectra
    assert spectrum.pitting_safety == pytest.approx(rating.S_H, rel=1e-9)
    assert spectrum.bending_safety == pytest.approx(rating.S_F, rel=1e-9)
    halves = lc.rate_mesh(g1, g2, 136.0, [lc.LoadCase(load, "level a", "drive", 0.5),
                                           lc.LoadCase(load, "level b", "drive", 0.5)], CONDITIONS, CARBURISED)
    assert halves.spectra[0].pitting == pytest.approx(spectrum.pitting, rel=1e-12)
    assert halves.spectra[0].bending == pytest.approx(spectrum.bending, rel=1e-12)
    # the drive's report writes it as strict JSON
    text = json.dumps(halves.to_dict(), allow_nan=False)
    assert json.loads(text)["spectra"][0]["flank"] == "drive"


def test_loads_on_both_flanks_reverse_the_bending_by_y_m_0_7():
    # ISO 6336-3/-5: fully reversed bending, 0.7 of the one-way strength (a preloaded mesh whose drive
    # torque reverses loads both flanks of each tooth)
    g1, g2 = helical_gears()
    one = lc.rate_mesh(g1, g2, 136.0, [lc.LoadCase(9000.0, "preload", "drive")], CONDITIONS, CARBURISED)
    both = lc.rate_mesh(g1, g2, 136.0, [lc.LoadCase(9000.0, "preload", "drive"),
                                         lc.LoadCase(9000.0, "drive torque", "coast")], CONDITIONS, CARBURISED)
    r1, r2 = one.cases[0][1], both.cases[0][1]
    assert r2["Y_M"] == (0.7, 0.7) and r1["Y_M"] == (1.0, 1.0)
    assert r2.S_F == pytest.approx(tuple(0.7 * s for s in r1.S_F), rel=1e-14)
    assert r2.S_H == r1.S_H


def test_a_spectrum_of_one_level_needs_the_face_width_that_level_needs():
    # a single level over the whole life is the case rated alone (ISO 6336-6 above), so the width at
    # which the spectrum reaches the minimum is the width face_width_for_minimum_safety solves for
    g1, g2 = helical_gears()
    geo = lc.rating_geometry(g1, g2, 136.0)
    load = 2 * 160e3 / (19 * 3 / math.cos(22 * DEG))
    alone = lc.face_width_for_minimum_safety(geo, load, CONDITIONS, CARBURISED)
    spectrum = lc.face_width_for_spectrum(geo, [lc.LoadCase(load, "level 1", "drive", 1.0)], CONDITIONS, CARBURISED)
    # 1e-8: both solves stop at 1e-13 on log b; the spectrum's inner solve for S at 1e-12 on log S
    assert spectrum.pitting == pytest.approx(alone.pitting, rel=1e-8)
    assert spectrum.bending == pytest.approx(alone.bending, rel=1e-8)
    assert lc.face_width_for_spectrum(geo, [lc.LoadCase(load, "preload", "drive")], CONDITIONS, CARBURISED) is None


def test_load_cycles_per_turn_and_reversed_bending_per_gear():
    # a sun meshing with three planets: each of its flanks is loaded three times a turn (ISO 6336-2 N_L)
    g1, g2 = helical_gears()
    geo = lc.rating_geometry(g1, g2, 136.0)
    sun = lc.RatingConditions(**{**CONDITIONS.__dict__, "load_cycles_per_turn": (3.0, 1.0)})
    once, thrice = (lc.rate_pair(geo, 9000.0, c, CARBURISED) for c in (CONDITIONS, sun))
    assert thrice["N_L"] == pytest.approx((3 * once["N_L"][0], once["N_L"][1]), rel=1e-15)
    assert thrice["Z_NT"][0] < once["Z_NT"][0] and thrice["Z_NT"][1] == once["Z_NT"][1]
    # a drive passes per gear whether its teeth see both flanks (a gear shared by two meshes)
    r = lc.rate_mesh(g1, g2, 136.0, [lc.LoadCase(9000.0, "preload", "drive")], CONDITIONS, CARBURISED,
                     reversed_bending=(False, True)).cases[0][1]
    assert r["Y_M"] == (1.0, 0.7)
    with pytest.raises(DesignError, match="load_cycles_per_turn"):
        lc.RatingConditions(**{**CONDITIONS.__dict__, "load_cycles_per_turn": (0.5, 1.0)})


def test_iso6336_5_lines_and_their_ranges():
    # ISO 6336-5:2016 Table 8: through hardened alloy MQ sigma_Hlim = 1.313 HV + 373, sigma_Flim =
    # 0.425 HV + 187 on 200..360 HV; case carburised MQ 1500 / 500; sigma_FE = 2 sigma_Flim
    a = allowable_stress(Material("through_hardened", "MQ", 300))
    assert (a.sigma_Hlim, a.sigma_Flim, a.sigma_FE) == pytest.approx((766.9, 314.5, 629.0), rel=1e-12)
    e = allowable_stress(Material("case_carburised", "MQ"))
    assert (e.sigma_Hlim, e.sigma_FE) == (1500.0, 1000.0)
    with pytest.raises(DesignError, match=r"200\.\.360 HV"):
        allowable_stress(Material("through_hardened", "MQ", 400))
    with pytest.raises(DesignError) as exc:
        allowable_stress(Material("through_hardened", "MQ"))
    assert exc.value.field == "hardness"
    with pytest.raises(DesignError) as exc:
        Material("bronze")
    assert exc.value.field == "material" and "case_carburised" in exc.value.allowed


def test_life_curves_pass_through_the_standards_points():
    # ISO 6336-2 Table 2 / ISO 6336-3 Table 3: static value, 1.0 at the reference, 0.85 at 1e10;
    # cycles_at inverts factor. Tolerance 1e-12: log-log arithmetic.
    for cls in MATERIALS.values():
        for curve in (cls.z_nt, cls.y_nt):
            (n0, f0), (n1, f1), (n2, f2) = curve.points
            assert curve.factor(n0 / 10) == f0 and curve.factor(n1) == pytest.approx(1.0, abs=1e-12)
            assert curve.factor(1e10) == pytest.approx(0.85, rel=1e-12)
            for n in (3e5, 4e7, 2e9, 5e10):
                assert curve.cycles_at(curve.factor(n)) == pytest.approx(n, rel=1e-9)


def test_families_outside_iso6336_are_named_not_rated():
    from geargen.families.bevel.spec import BevelGearSpec

    bevel = BevelGearSpec(teeth=20, mate_teeth=40, module=3, face_width=15)
    result = lc.rate_mesh(bevel, bevel, None, [lc.LoadCase(1000.0, "drive")], CONDITIONS, CARBURISED)
    assert result.scope.startswith("not rated by ISO 6336") and "ISO 10300" in result.scope
    assert result.to_dict() == {"standard": lc.STANDARD, "rated": False, "scope": result.scope}

    class WormWheelSpec:  # the name is what tells a worm wheel (geargen.families.worm.spec's class)
        kind = "worm_wheel"
    assert "ISO/TS 14521" in lc.rating_scope(WormWheelSpec())


def test_internal_pair_and_rack_change_what_the_standard_says():
    # internal: u negative in sigma_H0 ((|u| - 1)/|u|), Z_D = 1; rack: u infinite (factor 1), Z_D = 1.
    # Tolerance 1e-12: the formula recomputed from the block's own factors.
    from geargen.families.rack.spec import RackSpec

    pinion = GearSpec(teeth=18, module=2.0, pressure_angle=20 * DEG, face_width=20.0)
    from geargen.families.internal.spec import InternalGearSpec

    ring = InternalGearSpec(teeth=60, module=2.0, pressure_angle=20 * DEG, face_width=20.0)
    rack = RackSpec(teeth=40, module=2.0, pressure_angle=20 * DEG, face_width=20.0, pitch_line_height=10.0)
    cond = lc.RatingConditions(speed=600, life=5000, accuracy_grade=6, roughness=0.8, viscosity=100)
    mats = (Material("through_hardened", "MQ", 300), Material("through_hardened", "MQ", 280))
    for mate, ratio in ((ring, (60 / 18 - 1) / (60 / 18)), (rack, 1.0)):
        r = lc.rate_mesh(pinion, mate, None, [lc.LoadCase(2000.0, "drive")], cond, mats).cases[0][1]
        hand = r["Z_H"] * r["Z_E"] * r["Z_eps"] * r["Z_beta"] * math.sqrt(2000.0 * ratio / (36.0 * 20.0))
        assert r["sigma_H0"] == pytest.approx(hand, rel=1e-12)
        assert r["Z_BD"][1] == 1.0
        assert r["tooth_root"][1]["z_n"] == lc.RACK_VIRTUAL_TEETH
        assert all(math.isfinite(s) and s > 0 for s in r.S_F + r.S_H)
    # a rack cut with a sharp root has no finite Y_S: refused by name, not rated as infinitely weak
    sharp = RackSpec(teeth=40, module=2.0, pressure_angle=20 * DEG, face_width=20.0, pitch_line_height=10.0,
                     root_fillet_coefficient=0.0)
    with pytest.raises(DesignError) as exc:
        lc.rate_mesh(pinion, sharp, None, [lc.LoadCase(2000.0, "drive")], cond, mats)
    assert exc.value.field == "rack_tip_radius"
