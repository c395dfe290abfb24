"""The load capacity table: a :meth:`geargen.core.load_capacity.PairRating.to_dict` block printed
for a reader, lengths in the design's unit (the block itself keeps the contract's N, N/mm^2, m/s
and mm)."""

from __future__ import annotations

import math

from geargen.units import from_mm

_LABEL = 50
LBF_PER_N = 1.0 / 4.4482216152605


def _cell(value, decimals: int) -> str:
    if value is None:
        return "-"
    if isinstance(value, float) and not math.isfinite(value):
        return "inf" if value > 0 else "-inf"
    if isinstance(value, float) and abs(value) >= 1e6:
        return f"{value:.4g}"
    return f"{value:.{decimals}f}"


def _row(label: str, *cells: str) -> str:
    return (f"{label:<{_LABEL}}" + "".join(f"{c:>14}" for c in cells)).rstrip()


def format_load_capacity(block: dict, unit: str = "mm", face_width: dict | None = None) -> list[str]:
    """The lines of the table for one rated load (``block``: the ``load_capacity`` dict);
    ``face_width``: the widths that reach the minimum safety factors, in ``unit``."""
    L = lambda mm: from_mm(mm, unit)  # noqa: E731
    n = 6 if unit == "in" else 4
    lines = ["", f"Load capacity: {block['standard']}"]
    force = f"{block['F_t']:.1f} N" + (f" ({block['F_t'] * LBF_PER_N:.2f} lbf)" if unit == "in" else "")
    lines.append(f"F_t {force} at d_1 = {_cell(L(block['d_1_mm']), n)} {unit}, v = {block['v']:.4g} m/s, "
                  f"b = {_cell(L(block['b_mm']), n)} {unit}, n_1 = {block['n_1_rpm']:g} rpm, life {block['life_h']:g} h")
    for m_i, m in enumerate(block["materials"], start=1):
        hard = "" if m["hardness_HV"] is None else f", {m['hardness_HV']:g} HV"
        lines.append(f"gear {m_i}: {m['name']} {m['quality']}{hard} ({m['source']})")
    lines.append(_row("", "gear 1", "gear 2"))

    def both(label, key, decimals=4):
        lines.append(_row(label, *(_cell(v, decimals) for v in block[key])))

    def one(label, key, decimals=4):
        lines.append(_row(label, _cell(block[key], decimals)))

    one("application factor K_A", "K_A")
    one(f"dynamic factor K_v ({block['K_v_method_B']['range']})", "K_v")
    one("face load factors K_Hbeta, K_Fbeta", "K_Hbeta")
    lines[-1] += f"{_cell(block['K_Fbeta'], 4):>14}"
    one("transverse load factors K_Halpha, K_Falpha", "K_Halpha")
    lines[-1] += f"{_cell(block['K_Falpha'], 4):>14}"
    lines.append("Pitting (ISO 6336-2)")
    one("zone factor Z_H", "Z_H")
    one("elasticity factor Z_E (N^0.5/mm)", "Z_E", 2)
    one("contact ratio factor Z_eps, helix Z_beta", "Z_eps")
    lines[-1] += f"{_cell(block['Z_beta'], 4):>14}"
    both("single pair contact factors Z_B, Z_D", "Z_BD")
    one("nominal contact stress sigma_H0 (N/mm^2)", "sigma_H0", 1)
    both("contact stress sigma_H (N/mm^2)", "sigma_H", 1)
    both("allowable stress number sigma_Hlim (N/mm^2)", "sigma_Hlim", 1)
    both("load cycles N_L", "N_L", 0)
    both("life factor Z_NT", "Z_NT")
    lines.append(_row("Z_L, Z_v, Z_R", *(_cell(block[k], 4) for k in ("Z_L", "Z_v", "Z_R"))))
    both("work hardening Z_W (per gear), size Z_X = 1", "Z_W_per_gear")
    both("permissible contact stress sigma_HP (N/mm^2)", "sigma_HP", 1)
    both(f"safety factor S_H (minimum {block['S_Hmin']:g})", "S_H")
    lines.append("Tooth root bending (ISO 6336-3)")
    both("tooth form factor Y_F", "Y_F")
    both("stress correction factor Y_S", "Y_S")
    lines.append(_row("helix Y_beta, deep tooth Y_DT", _cell(block["Y_beta"], 4), _cell(block["Y_DT"], 4)))
    both("rim thickness factor Y_B", "Y_B")
    lines.append(_row(f"critical section chord s_Fn ({unit})",
                      *(_cell(L(r["s_Fn_mm"]), n) for r in block["tooth_root"])))
    lines.append(_row(f"bending moment arm h_Fe ({unit})", *(_cell(L(r["h_Fe_mm"]), n) for r in block["tooth_root"])))
    lines.append(_row(f"root fillet radius rho_F ({unit})", *(_cell(L(r["rho_F_mm"]), n) for r in block["tooth_root"])))
    both("nominal root stress sigma_F0 (N/mm^2)", "sigma_F0", 1)
    both("root stress sigma_F (N/mm^2)", "sigma_F", 1)
    both("allowable stress number sigma_FE (N/mm^2)", "sigma_FE", 1)
    both("life factor Y_NT", "Y_NT")
    both("notch sensitivity Y_deltarelT", "Y_deltarelT")
    both("surface factor Y_RrelT", "Y_RrelT")
    both("size factor Y_X", "Y_X")
    both("permissible root stress sigma_FP (N/mm^2)", "sigma_FP", 1)
    both(f"safety factor S_F (minimum {block['S_Fmin']:g})", "S_F")
    if face_width is not None:
        lines.append(_row(f"face width for S_Hmin, S_Fmin ({unit})",
                          *(_cell(face_width[k], n) for k in ("pitting", "bending"))))
        if face_width.get("message"):
            lines.append(f"  {face_width['message']}")
    failing = [f"{key} of gear {i + 1} = {v:.4f} < {block[key + 'min']:g}"
               for key in ("S_H", "S_F") for i, v in enumerate(block[key]) if v < block[key + "min"]]
    lines.append("result: " + ("FAILS: " + "; ".join(failing) if failing else "both gears reach the minimum safety "
                                                                              "factors"))
    lines += [f"note: {t}" for t in block["notes"]]
    lines += [f"warning: {t}" for t in block["warnings"]]
    return lines


__all__ = ["format_load_capacity"]
