"""Analytic plane curves a tooth outline is made of, and the segment that places one in the gear.

A :class:`Segment` is a curve piece with a parameter range. It can be evaluated anywhere in
that range (points and exact first derivatives, machine precision), so the CAD layer, the mesh
checker and the tests all work from the same exact outline instead of from sampled points.

Conventions: mm and rad; arrays are ``(n, 2) float`` of x, y in the gear's transverse plane,
gear axis through the origin. A segment runs from ``t0`` to ``t1`` (``t1 < t0`` is allowed: the
outline then traverses the curve against its parameter). ``mirrored`` reflects the canonical
curve in the x axis (y -> -y) before ``rotation`` (rad, counter-clockwise) is applied.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

#: segment kinds
KINDS = ("involute", "fillet", "tip_arc", "root_arc")


class ArcCurve:
    """Circle of ``radius`` about the origin, parametrised by polar angle (rad)."""

    def __init__(self, radius: float):
        self.radius = float(radius)

    def point(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return self.radius * np.column_stack([np.cos(t), np.sin(t)])

    def derivative(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return self.radius * np.column_stack([-np.sin(t), np.cos(t)])


class InvoluteCurve:
    """The upper flank of tooth 0: involute of the base circle, parametrised by roll angle t.

    Point: ``r_b (cos w - t sin w, sin w + t cos w)`` with ``w = psi_b - t``, where ``psi_b`` is
    the flank's polar angle at the base circle; its radius is ``r_b sqrt(1 + t^2)`` and its polar
    angle ``psi_b - inv(alpha)`` with ``t = tan(alpha)``. Derivative: ``r_b t (cos w, sin w)``.
    """

    def __init__(self, base_radius: float, base_half_angle: float):
        self.base_radius = float(base_radius)
        self.base_half_angle = float(base_half_angle)

    def point(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        w = self.base_half_angle - t
        c, s = np.cos(w), np.sin(w)
        return self.base_radius * np.column_stack([c - t * s, s + t * c])

    def derivative(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        w = self.base_half_angle - t
        return (self.base_radius * t)[:, None] * np.column_stack([np.cos(w), np.sin(w)])


@dataclass(frozen=True)
class Segment:
    """One analytic piece of an outline (see the module docstring for the conventions).

    ``kind`` is one of :data:`KINDS`; ``side`` is ``"upper"`` or ``"lower"`` for flank and fillet
    pieces (which side of the tooth centreline), ``""`` for arcs; ``tooth`` the tooth index.
    """

    kind: str
    side: str
    curve: object  # has point(t) -> (n, 2) and derivative(t) -> (n, 2) in canonical position
    t0: float
    t1: float
    mirrored: bool = False
    rotation: float = 0.0
    tooth: int = 0

    def _place(self, xy: np.ndarray) -> np.ndarray:
        return self._turn(self._mirror(xy))

    def _mirror(self, xy: np.ndarray) -> np.ndarray:
        return xy * np.array([1.0, -1.0]) if self.mirrored else xy

    def _turn(self, xy: np.ndarray) -> np.ndarray:
        if self.rotation:
            c, s = math.cos(self.rotation), math.sin(self.rotation)
            xy = xy @ np.array([[c, s], [-s, c]])
        return xy

    def point(self, t) -> np.ndarray:
        """Points ``(n, 2)`` at parameters ``t`` (any shape, flattened)."""
        return self._place(self.curve.point(np.ravel(t)))

    def derivative(self, t) -> np.ndarray:
        """Exact first derivatives d(point)/dt ``(n, 2)`` (w.r.t. the parameter, not the traversal)."""
        return self._place(self.curve.derivative(np.ravel(t)))

    def tangent(self, t) -> np.ndarray:
        """Unit tangents ``(n, 2)`` in the direction of traversal (t0 -> t1)."""
        d = self.derivative(t) * (1.0 if self.t1 >= self.t0 else -1.0)
        n = np.linalg.norm(d, axis=1, keepdims=True)
        return d / np.where(n > 0, n, 1.0)

    @property
    def start(self) -> np.ndarray:
        return self.point(self.t0)[0]

    @property
    def end(self) -> np.ndarray:
        return self.point(self.t1)[0]

    def parameters(self, n: int) -> np.ndarray:
        """``n`` evenly spaced parameters from ``t0`` to ``t1`` inclusive."""
        return np.linspace(self.t0, self.t1, n)

    def sample(self, n: int) -> np.ndarray:
        """``n`` points ``(n, 2)`` evenly spaced in the parameter, ``t0`` to ``t1`` inclusive."""
        return self.point(self.parameters(n))

    def rotated(self, angle: float, tooth: int | None = None) -> "Segment":
        """The same piece turned counter-clockwise by ``angle`` (rad) about the gear axis."""
        return replace(self, rotation=self.rotation + angle, tooth=self.tooth if tooth is None else tooth)

    def reversed(self) -> "Segment":
        return replace(self, t0=self.t1, t1=self.t0)

    def area_integral(self, order: int = 48) -> float:
        """The segment's share of the enclosed area, 1/2 integral of (x dy - y dx) (mm^2).

        Exact for arcs and involutes (closed forms); Gauss-Legendre of ``order`` points for the
        fillet, which is smooth on its range (relative error ~1e-16 at the default order).
        """
        sign = -1.0 if self.mirrored else 1.0  # a reflection flips the orientation of the area
        if isinstance(self.curve, ArcCurve):
            return sign * 0.5 * self.curve.radius ** 2 * (self.t1 - self.t0)
        if isinstance(self.curve, InvoluteCurve):
            # x y' - y x' = -r_b^2 t^2 for the canonical involute
            return sign * -self.curve.base_radius ** 2 * (self.t1 ** 3 - self.t0 ** 3) / 6.0
        x, w = np.polynomial.legendre.leggauss(order)
        half = 0.5 * (self.t1 - self.t0)
        t = self.t0 + half * (x + 1.0)
        p = self.curve.point(t)
        d = self.curve.derivative(t)
        return sign * 0.5 * half * float(np.sum(w * (p[:, 0] * d[:, 1] - p[:, 1] * d[:, 0])))


def outline_area(segments) -> float:
    """Area enclosed by a closed counter-clockwise chain of segments (mm^2), by Green's theorem."""
    return float(sum(s.area_integral() for s in segments))


def sample_outline(segments, max_step: float) -> np.ndarray:
    """Points ``(n, 2)`` along a chain of segments, at most about ``max_step`` mm apart.

    The chain's joints appear once (the end of one segment is the start of the next).
    """
    unturned: dict[tuple, np.ndarray] = {}  # a piece's points before its turn: once for all the teeth
    counts: dict[tuple, int] = {}  # a piece's point count, where its turned copies' cannot differ

    def points(s: Segment, n: int) -> np.ndarray:  # s.sample(n), the same arithmetic
        key = (id(s.curve), s.t0, s.t1, s.mirrored, n)
        xy = unturned.get(key)
        if xy is None:
            xy = unturned[key] = s._mirror(s.curve.point(s.parameters(n)))
        return s._turn(xy)

    parts = []
    for s in segments:
        piece = (id(s.curve), s.t0, s.t1, s.mirrored)
        n = counts.get(piece)
        if n is None:
            steps = float(np.sum(np.linalg.norm(np.diff(points(s, 9), axis=0), axis=1))) / max_step
            n = max(2, int(math.ceil(steps)) + 1)
            # a turn changes the chord by rounding only (~1e-15 of it): the count holds for every turned
            # copy unless the chord is that close to a whole number of steps (then each copy counts its own)
            if abs(steps - round(steps)) > 1e-9 * max(1.0, steps):
                counts[piece] = n
        parts.append(points(s, n)[:-1])
    return np.concatenate(parts)
