"""Triangle mesh of a helical compression spring straight from its exact geometry (numpy only).

The spring (:func:`geargen.cad.parts.compression_spring`) is the disc of radius a = d/2 centred at
radius R = D/2 in the half-plane through the axis at angle 0, screwed along the helix
z = z0 + c phi (c = pitch / 2 pi, right hand, phi in [0, 2 pi n]): the kernel's sweep of that
circle in the helix's Frenet frame. Its side is

    S(phi, psi) = ((R + a cos psi) cos phi, (R + a cos psi) sin phi, z0 + c phi + a sin psi),

closed by the discs at phi = 0 and 2 pi n (plain ends), or, with ground ends, cut by the planes
z = z0 and z0 + 2 pi n c: each plane takes the half disc below it at the end and a lens (the
plane's section of the wire, ``(r - R)^2 + (c phi)^2 <= a^2`` in polar coordinates) in its place.

The side is a grid of rows (phi) by m columns (psi), every vertex on S. Near a ground end the rows
follow the cut: at phi = (a / c) sin(beta) the wire above the plane is psi in
[-beta, pi + beta], spanned by the m columns, so the first and last column run along the cut
outline, exactly in the plane, and the row at beta = pi / 2 (the lens's tip) is the first whole
ring. The end faces are flat: the discs and half discs fanned from a vertex, the lens zipped
between its outer and inner outline.

Bound (every triangle of the side, checked as the mesh is made): the flat triangle through three
points of S lies within ``(1/2) r^2`` of S (at the same parameters) where r is the radius of the
smallest circle holding the triangle's parameters in the metric ``(R + a + a k) dphi^2 +
a (1 + 1/k) dpsi^2`` (Taylor's remainder with |S_phiphi| <= R + a, |S_psipsi| = a,
|S_phipsi| <= a, and 2 |dphi dpsi| <= k dphi^2 + dpsi^2 / k). The flat faces lie in their planes.

The tolerance used is at most a / 2 (coarser, the chords along the coil would pass near the centre
line); the steps also keep to an angular tolerance where one is asked (the view's, as the kernel's).

Used for the view and the STL of the springs (geargen.cad.export.solid_triangles). Measured
(tests/profile/test_spring_tessellate.py, tests/cad/test_spring_mesh.py): the robot joint's spring at
0.05 mm, 6,160 triangles in 1.6 ms against the kernel's 13,186 in 127 ms; probes on every triangle
reach 0.65-0.82 of the tolerance (the bound's margin); vertices within 1e-6 mm of the kernel's sweep
fitted to 1e-7 mm (within 2.5e-5 of the sweep as the kernel builds it, to its default 1e-4).
"""

from __future__ import annotations

import math

import numpy as np

from geargen.profile.tessellate import TessellationError, enclosing_radius_squared

#: most rows a ground end's cut region is given before the mesher gives up (the kernel meshes it)
_MAX_END_ROWS = 4096


def _ring_steps(a: float, rho: float, tolerance: float, angle: float | None) -> tuple[int, float]:
    """(even columns m, row step dphi) of the fewest side triangles whose right triangles (legs
    dphi, dpsi = 2 pi / m) meet the bound: ``(rho dphi^2 + a dpsi^2 + 2 a dphi dpsi) / 8 <= tolerance``
    (k = dpsi / dphi), and whose neighbours' normals turn by at most ``angle`` (rad; None: no limit)
    across the wire (dpsi) and along it (dphi). Even m: a ground spring's two lens tips lie half a
    turn of psi apart."""
    least = 2 * math.ceil(math.pi / math.sqrt(8 * tolerance / a))  # the wire's circle alone
    if angle is not None:
        least = max(least, 2 * math.ceil(math.pi / angle))
    best = None
    for m in range(max(4, least), max(4, least) + 24, 2):
        dpsi = 2 * math.pi / m
        free = 8 * tolerance - a * dpsi * dpsi
        if free <= 0:
            continue
        dphi = (-a * dpsi + math.sqrt((a * dpsi) ** 2 + rho * free)) / rho  # root of the bound
        if angle is not None:
            dphi = min(dphi, angle)  # the normal turns by one radian a radian of phi (at psi = 0)
        if best is None or m / dphi < best[0]:
            best = (m / dphi, m, dphi)
    return best[1], best[2]


def spring_triangles(wire_diameter: float, mean_coil_diameter: float, z0: float, pitch: float,
                     total_coils: float, chordal_tolerance: float, slab: tuple[float, float] | None = None,
                     angular_tolerance: float | None = None) -> np.ndarray:
    """The closed, outward-oriented triangle mesh ``(n, 3, 3)`` (mm) of the spring described in the
    module docstring, every vertex on its exact surface, every triangle within ``chordal_tolerance``
    mm of it (and of half the wire's radius). ``slab``: ground ends, the planes ``(low, high)`` that cut it, through the helix's ends
    (z0 and z0 + pitch total_coils; the cut outlines' vertices lie in them to the last bit).
    ``angular_tolerance`` (rad): also the most the side's facets turn from one to the next, round
    the wire and along it (as the kernel's mesher keeps a thin wire round at a coarse tolerance).

    Raises :class:`TessellationError` where this layout does not hold (the two lenses of a ground
    spring under a turn meet; coils touching; the index D/d at most 2)."""
    a, radius, t = wire_diameter / 2, mean_coil_diameter / 2, float(chordal_tolerance)
    ground = slab is not None
    if ground and not (math.isclose(slab[0], z0, rel_tol=0, abs_tol=1e-9 * pitch * total_coils)
                       and math.isclose(slab[1], z0 + pitch * total_coils, rel_tol=1e-9)):
        raise TessellationError(f"spring: the slab {slab} does not pass through the helix's ends")
    turns = 2 * math.pi * total_coils
    c = pitch / (2 * math.pi)
    if not (a > 0 and radius > 2 * a and t > 0 and total_coils > 0 and pitch > wire_diameter
            and (angular_tolerance is None or angular_tolerance > 0)):
        raise TessellationError(f"spring d {wire_diameter:g}, D {mean_coil_diameter:g}, pitch {pitch:g}: "
                                "not a spring this mesher lays out")
    # at most half the wire's radius: a coarser mesh's chords along the coil would pass near the
    # centre line, the facets there facing in (a thin wire in a large assembly's view)
    t = min(t, a / 2)
    rho = radius + a  # the largest radius of the side: its largest curvature along phi
    m, dphi = _ring_steps(a, rho, t, angular_tolerance)
    k = (2 * math.pi / m) / dphi
    lens = a / c if ground else 0.0  # the angle a ground end's cut reaches round the helix
    middle = turns - 2 * lens
    if not middle > 0:
        raise TessellationError(f"ground spring of {total_coils:g} coils: the end cuts meet")
    metric = np.sqrt([rho + a * k, a * (1 + 1 / k)])
    rows_middle = max(1, math.ceil(middle / dphi))
    refine = 1.0
    while True:
        betas = _cut_betas(lens, dphi / refine, (2 * math.pi / m) / refine) if ground else np.zeros(0)
        end_rows = len(betas)
        phis, psis = _side_rows(m, lens, turns, rows_middle, betas)
        lower, upper = _row_pairs(psis, m, end_rows, rows_middle)
        low_phi, up_phi = phis[:-1], phis[1:]
        a_, b_ = np.stack([low_phi[:, :-1], lower[:, :-1]], -1), np.stack([low_phi[:, 1:], lower[:, 1:]], -1)
        d_, c_ = np.stack([up_phi[:, :-1], upper[:, :-1]], -1), np.stack([up_phi[:, 1:], upper[:, 1:]], -1)
        a_, b_, c_, d_ = a_ * metric, b_ * metric, c_ * metric, d_ * metric
        rising = _rising(a_, b_, c_, d_)
        tri = np.concatenate([np.where(rising[..., None, None], np.stack([a_, d_, c_], -2), np.stack([a_, d_, b_], -2)),
                              np.where(rising[..., None, None], np.stack([a_, c_, b_], -2), np.stack([b_, d_, c_], -2))])
        tri = tri.reshape(-1, 3, 2)
        worst = float(np.max(enclosing_radius_squared(tri))) / 2
        if worst <= t:
            break
        if not ground or end_rows >= _MAX_END_ROWS:
            raise TessellationError(f"spring side: no mesh within {t:g} mm (bound {worst:.3g} mm)")
        refine *= 2  # only the cut regions' skewed rows can fail: the middle's meet the bound by its steps
    return _assembled(phis, psis, m, a, radius, z0, c, end_rows, rows_middle, slab, rising)


def _rising(a_, b_, c_, d_):
    """Per quad (A = row i col j, B = row i col j+1, C = row i+1 col j+1, D = row i+1 col j; in the
    bound's metric) whether it is split along A-C, the shorter diagonal (triangles (A, D, C) and
    (A, C, B)), else along D-B ((A, D, B), (B, D, C)): the cut rows' skewed quads near a lens's tip
    are thin, and their long diagonal would make slivers whose facets turn sharply. The middle's
    quads are rectangles in the metric: D-B (a shorter A-C by more than rounding)."""
    along_ac = np.sum((c_ - a_) ** 2, axis=-1)
    along_db = np.sum((b_ - d_) ** 2, axis=-1)
    return along_ac < along_db * (1 - 1e-9)


def _cut_betas(lens: float, dphi: float, dbeta: float) -> np.ndarray:
    """The cut rows' beta from 0 up to (not including) the tip pi/2, at phi = lens sin(beta): even
    steps of the length of the curve (phi / dphi, beta / dbeta), so that phi moves at most dphi and
    beta (the columns' shear) at most dbeta a row; even steps of beta alone would crowd the rows
    near the tip (phi's step going as cos(beta)) into thin sheared quads."""
    beta = np.linspace(0.0, math.pi / 2, 513)
    speed = np.hypot(lens * np.cos(beta) / dphi, 1.0 / dbeta)
    length = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(beta))])
    rows = max(2, math.ceil(length[-1]))
    return np.interp(length[-1] * np.arange(rows) / rows, length, beta)


def _side_rows(m: int, lens: float, turns: float, rows_middle: int, betas: np.ndarray):
    """The side's grid: (phi, psi) of each row's m + 1 columns (rows, m + 1), psi unwrapped along
    each row. The whole rings run from the bottom of the wire (psi = -pi/2) at the first ground
    end's tip, so that at the other end's tip (psi = pi/2) they are the same ring started half a
    turn (m / 2 columns) on."""
    j = np.arange(m + 1) / m
    phi_rows, psi_rows = [], []
    if len(betas):
        beta = betas  # the tip, beta = pi / 2, is the middle's first row
        phi_rows.append(lens * np.sin(beta))
        psi_rows.append(-beta[:, None] + (math.pi + 2 * beta[:, None]) * j)
    middle = lens + (turns - 2 * lens) * np.arange(rows_middle + 1) / rows_middle
    phi_rows.append(middle)
    start = -math.pi / 2 if len(betas) else 0.0
    psi_rows.append(np.broadcast_to(start + 2 * math.pi * j, (rows_middle + 1, m + 1)))
    if len(betas):
        beta = betas[::-1]
        phi_rows.append(turns - lens * np.sin(beta))
        psi_rows.append((math.pi - beta[:, None]) + (math.pi + 2 * beta[:, None]) * j)
    phis = np.concatenate(phi_rows)
    return np.broadcast_to(phis[:, None], (len(phis), m + 1)), np.concatenate(psi_rows)


def _row_pairs(psis, m: int, end_rows: int, rows_middle: int):
    """psi of the lower and upper row of each pair of consecutive rows: the middle's last ring read
    from column m/2 (psi = pi/2) where the second ground end's cut rows follow it."""
    lower, upper = psis[:-1].copy(), psis[1:]
    if end_rows:
        lower[end_rows + rows_middle] = math.pi / 2 + 2 * math.pi * np.arange(m + 1) / m
    return lower, upper


def _assembled(phis, psis, m, a, radius, z0, c, end_rows, rows_middle, slab, rising):
    """The triangles of the side grid ``phis, psis`` (rows: ``end_rows`` cut rows, ``rows_middle``
    + 1 whole rings, ``end_rows`` cut rows) and of the end faces (the lenses in the ``slab``'s planes)."""
    rows = len(phis)
    index = np.arange(rows * (m + 1)).reshape(rows, m + 1)
    first_ring, last_ring = end_rows, end_rows + rows_middle
    index[first_ring:last_ring + 1, -1] = index[first_ring:last_ring + 1, 0]  # a ring's last column is its first
    lower, upper = index[:-1].copy(), index[1:]
    ring = index[last_ring]
    if end_rows:  # the middle's last ring in the second end's column order (from psi = pi/2)
        lower[last_ring] = np.concatenate([ring[m // 2:m], ring[:m // 2 + 1]])
    a_, b_, d_, c_ = lower[:, :-1], lower[:, 1:], upper[:, :-1], upper[:, 1:]
    first = np.where(rising[..., None], np.stack([a_, d_, c_], -1), np.stack([a_, d_, b_], -1))
    second = np.where(rising[..., None], np.stack([a_, c_, b_], -1), np.stack([b_, d_, c_], -1))
    faces = [np.concatenate([first.reshape(-1, 3), second.reshape(-1, 3)])]
    if end_rows:
        faces.append(_fan(index[0]))  # the half discs at phi = 0 and at the end
        faces.append(_fan(index[-1]))
        cut = index[:first_ring]  # the lens in z = z0: columns 0 and m of the first cut rows, to the tip
        faces.append(_zip(cut[:, 0], cut[:, m], index[first_ring, 0]))
        cut = index[last_ring + 1:][::-1]  # the lens in the top plane, from its base to its tip
        faces.append(_zip(cut[:, 0], cut[:, m], ring[m // 2]))
    else:
        faces.append(_fan(index[0, :m]))  # the discs at phi = 0 and at the end
        faces.append(_fan(index[-1, :m]))
    phi, psi = phis.ravel(), psis.ravel()
    r = radius + a * np.cos(psi)
    points = np.stack([r * np.cos(phi), r * np.sin(phi), z0 + c * phi + a * np.sin(psi)], axis=1)
    if end_rows:  # the cut outlines: z0 + c phi + a sin(psi) is the plane's height but for rounding
        points[index[:first_ring + 1, [0, m]].ravel(), 2] = slab[0]  # the last row: the tip
        points[np.append(index[last_ring + 1:, [0, m]].ravel(), ring[m // 2]), 2] = slab[1]
    side, *ends = (points[f] for f in faces)
    # the flat faces turned to face out: the disc at phi = 0 along -e_phi(0), the one at the end
    # along +e_phi(end); a ground spring's lenses down and up
    end = phis[-1, 0]
    outward = [np.array([0.0, -1.0, 0.0]), np.array([-math.sin(end), math.cos(end), 0.0]),
               np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0])]
    for i, (tri, out) in enumerate(zip(ends, outward)):
        if np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]).sum(axis=0) @ out < 0:
            ends[i] = tri[:, ::-1]
    return np.concatenate([side] + ends)


def _fan(ring):
    """A flat convex polygon's triangles fanned from its first vertex (orientation fixed later)."""
    ring = np.asarray(ring)
    j = np.arange(1, len(ring) - 1)
    return np.stack([np.full(len(j), ring[0]), ring[j], ring[j + 1]], axis=-1)


def _zip(outer, inner, tip):
    """A lens between two outlines from a common base (their first vertices joined by the half
    disc's diameter) to a common tip: quads between consecutive rows, a triangle at the tip."""
    quads = np.concatenate([np.stack([outer[:-1], inner[:-1], inner[1:]], axis=-1),
                            np.stack([outer[:-1], inner[1:], outer[1:]], axis=-1)])
    return np.concatenate([quads, [[outer[-1], inner[-1], tip]]])


__all__ = ["spring_triangles"]
