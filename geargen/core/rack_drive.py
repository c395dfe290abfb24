"""The Type 2 dual-pinion rack drive (numpy/scipy only): loop closure, preload lever and forces.

Frame (mm, rad; the assembly frame of :mod:`geargen.drives.rack_dual_pinion.place`): the rack's pitch line is
the x axis, its teeth point to +y; the two path shafts stand at ``(+-h, y_s)`` (``h`` half the
pinion spacing, ``y_s`` the pinions' centre height), each carrying a rack pinion and a path gear;
the input gear (the motor's) sits on the symmetry line at ``(0, y)`` on the preload carriage,
which slides along y. Side "a" is the path at ``x = +h``, side "b" its mirror image.

Preload (Hale & Slocum, Fig. 9, radial motion). The carriage spring pushes the input toward the
path shafts (-y) with ``F_e``. The input then turns path a counter-clockwise and path b
clockwise, so pinion a pushes the rack toward +x and pinion b toward -x: each loop is tight on
one flank of each of its meshes. Contact forces ``F_1``, ``F_2`` on the input meshes act along
their lines of action, at ``gamma`` to the carriage's motion: ``(F_1 + F_2) cos(gamma) = F_e``
and ``(F_1 - F_2) r_b,in = T`` (the drive torque at the input).

Lever. Moving the carriage by ``dy`` toward the shafts (input held) moves the input's flank along
mesh a's line of action by ``dy cos(gamma)``, turning path a by ``dy cos(gamma) / r_b,path``,
so pinion a moves the rack by ``lambda dy`` with ``lambda = r_pinion cos(gamma) / r_b,path``
(the pinion's reference circle rolls on the rack line), and pinion b by ``-lambda dy``.

Stiffness referred to the rack (linear, N/mm along x; a path's linear stiffness ``k`` on the
rack). Path forces on the rack ``F_a = k_1 (lambda y - x)``, ``F_b = k_2 (-lambda y - x)``
(``x`` the rack's displacement, ``y`` the carriage's); the carriage's equilibrium by virtual
work, ``lambda (F_b - F_a) = k_c y``. Eliminating ``y`` gives Eq. 5 with
``k_3 = k_c / lambda^2``; a loop error ``e`` in path a (``F_a = k_1 (lambda y - x + e)``, no
drive force) gives ``F_a = e / (1/k_1 + 1/k_2 + 4/k_3)``, Eq. 6. Each path is the input mesh
reflected to the rack, ``k_m,in (r_b,path / r_pinion)^2``, in series with the rack mesh along
the rack, ``k_m,rack cos^2(alpha_t)`` (Eq. 1 meshes along their lines of action).

Loop closure. With the rack placed and each pinion tight against it (its working flank short of
contact by the loaded flank gap), the path gears' rotations follow from their keying to the
pinions; the input's rotation and the carriage's height are the two unknowns of the two input
meshes' contact conditions. The drive is mirror-symmetric about x = 0 (rack, shafts and keying
mirrored), so the input sits symmetric (a tooth centred on -y) and one condition remains: the
involute relation of :func:`geargen.core.synthesis.mate_rotation` at the centre distance and
working backlash of each carriage height, solved for ``y`` by a bracketed root find.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.optimize import brentq

from geargen.core.involute import working_pressure_angle_at
from geargen.core.synthesis import mate_rotation, wrap
from geargen.errors import GeometryError


@dataclass(frozen=True)
class RackDriveFrame:
    """The fixed geometry of the loop (mm, rad): half the pinion spacing ``half_spacing``, the
    shafts' height ``shaft_y``, teeth of the input and path gear, the path gear's reference and
    base radius, the pinion's reference radius, the input's base radius."""

    half_spacing: float
    shaft_y: float
    input_teeth: int
    path_teeth: int
    path_reference_radius: float
    path_base_radius: float
    input_base_radius: float
    pinion_reference_radius: float

    def centre_distance(self, y) -> np.ndarray | float:
        """Input-to-path-gear centre distance at carriage height ``y``."""
        return np.hypot(self.half_spacing, np.asarray(y, dtype=float) - self.shaft_y)

    def direction_a(self, y) -> float:
        """Direction angle from path gear a's centre to the input's centre."""
        return math.atan2(y - self.shaft_y, -self.half_spacing)

    def working_pressure_angle(self, y: float) -> float:
        c = float(self.centre_distance(y))
        alpha_w = working_pressure_angle_at(float(self.input_base_radius + self.path_base_radius), c)
        if not alpha_w > 0:  # NaN: inside the base circles; 0: touching them
            raise GeometryError("carriage", f"centre distance {c:.6g} mm is inside the base circles")
        return alpha_w

    def line_of_action_a(self, y: float) -> np.ndarray:
        """Unit vector of the force the input puts on path gear a (along mesh a's working line of
        action): ``sin(alpha_w) c - cos(alpha_w) t`` with ``c`` the unit vector input -> path a and
        ``t`` it turned +90 deg (turns path a counter-clockwise; see the module docstring)."""
        aw = self.working_pressure_angle(y)
        c = np.array([self.half_spacing, self.shaft_y - y]) / float(self.centre_distance(y))
        t = np.array([-c[1], c[0]])
        return math.sin(aw) * c - math.cos(aw) * t

    def cos_gamma(self, y: float) -> float:
        """Cosine of the angle between the carriage's motion (-y, toward the shafts) and mesh a's
        working line of action (1 at Fig. 9's optimum)."""
        return float(-self.line_of_action_a(y)[1])

    def lever(self, y: float) -> float:
        """``lambda``: rack travel at pinion a per carriage travel toward the shafts (mm/mm)."""
        return self.pinion_reference_radius * self.cos_gamma(y) / self.path_base_radius


def closure_residual(frame: RackDriveFrame, path_rotation_a: float, input_rotation: float,
                     backlash_of: Callable[[float], float], loaded_flank_gap: float, y: float) -> float:
    """How far (rad, wrapped to half a path-gear pitch) path gear a stands from touching the input
    on its working flank with the loaded flank gap left, at carriage height ``y``: zero where the
    loop closes. ``backlash_of(c)``: the input mesh's circumferential backlash at centre distance
    ``c`` (circumferential, the same arc on both reference circles). Path gear a is pushed
    counter-clockwise by the input, so it stands turned clockwise from centred (``mate_rotation``
    flank -1), the input's tooth a loaded flank gap from its flank: the input turning clockwise
    would drive it."""
    c = float(frame.centre_distance(y))
    touching = mate_rotation(frame.direction_a(y), input_rotation, frame.path_teeth, frame.input_teeth,
                             (backlash_of(c) - 2 * loaded_flank_gap) / frame.path_reference_radius, -1)
    return float(wrap(path_rotation_a - touching, 2 * math.pi / frame.path_teeth))


def solve_carriage(frame: RackDriveFrame, path_rotation_a: float, input_rotation: float,
                   backlash_of: Callable[[float], float], loaded_flank_gap: float, y_nominal: float,
                   search: float) -> float:
    """The carriage height (mm) nearest ``y_nominal`` within ``+-search`` where the loop closes
    (:func:`closure_residual` is zero; brentq on a sign change, skipping the wrap's jumps).
    Raises :class:`GeometryError` (kind "carriage") when no closure lies within the search."""
    def f(y):
        return closure_residual(frame, path_rotation_a, input_rotation, backlash_of, loaded_flank_gap, y)

    samples = y_nominal + np.linspace(-search, search, 401)
    values = np.array([f(y) for y in samples])
    half = math.pi / frame.path_teeth
    roots = []
    for i in range(len(samples) - 1):
        a, b = values[i], values[i + 1]
        if a == 0.0:
            roots.append(samples[i])
        elif a * b < 0 and abs(a - b) < half:  # a true crossing, not the wrap's jump
            roots.append(brentq(f, samples[i], samples[i + 1], xtol=1e-13, rtol=1e-15))
    if not roots:
        raise GeometryError("carriage", f"the loop does not close within {search:.4g} mm of the nominal carriage "
                            "height")
    return float(min(roots, key=lambda r: abs(r - y_nominal)))


def keying_for_closure(frame: RackDriveFrame, pinion_rotation_a: float, input_rotation: float,
                       backlash_of: Callable[[float], float], loaded_flank_gap: float, y_nominal: float) -> float:
    """The path gear's angular position on its shaft relative to the pinion (rad, path gear a's
    rotation minus pinion a's) that closes the loop with the carriage at ``y_nominal``: the timing
    the assembler sets (the mark on each shaft)."""
    c = float(frame.centre_distance(y_nominal))
    touching = mate_rotation(frame.direction_a(y_nominal), input_rotation, frame.path_teeth, frame.input_teeth,
                             (backlash_of(c) - 2 * loaded_flank_gap) / frame.path_reference_radius, -1)
    return float(touching - pinion_rotation_a)


def pinion_rotation_on_rack(pinion_x: float, pinion_reference_radius: float, space_x: float,
                            rack_backlash: float, loaded_flank_gap: float, sense: int) -> float:
    """Rotation (tooth 0's centreline, CCW from +x) of a pinion at ``x = pinion_x`` over a rack
    whose space is centred at ``space_x``, turned ``sense`` (+1 counter-clockwise, which pushes the
    rack toward +x) until its working flank is ``loaded_flank_gap`` short of the rack's flank.
    Centred, a pinion tooth points down at the space centre that lies ``r phi`` along the rolling
    line (the reference circle rolls on the rack); the free play either way is half the
    circumferential backlash."""
    centred = -math.pi / 2 + (space_x - pinion_x) / pinion_reference_radius
    return centred + sense * (rack_backlash / 2 - loaded_flank_gap) / pinion_reference_radius


@dataclass(frozen=True)
class PreloadForces:
    """Fig. 9 at the input (N, N·mm): the contact forces of the two input meshes at zero drive
    torque and at ``drive_torque``, and the drive torque (and rack force) at which one path unloads."""

    spring_force: float
    cos_gamma: float
    mesh_force_at_rest: float
    drive_torque: float
    mesh_force_1: float
    mesh_force_2: float
    unloading_torque: float
    unloading_rack_force: float


def preload_forces(spring_force: float, cos_gamma: float, input_base_radius: float, path_base_radius: float,
                   pinion_reference_radius: float, drive_torque: float = 0.0) -> PreloadForces:
    """``F_1 + F_2 = F_e / cos(gamma)`` and ``F_1 - F_2 = T / r_b,in`` (Fig. 9). The rack force
    of the drive is ``(F_1 - F_2) r_b,path / r_pinion`` (each path's torque on its pinion, over
    the rolling radius), so a path unloads at ``T = F_e r_b,in / cos(gamma)``."""
    total = spring_force / cos_gamma
    diff = drive_torque / input_base_radius
    unload_t = total * input_base_radius
    return PreloadForces(spring_force, cos_gamma, total / 2, drive_torque, (total + diff) / 2, (total - diff) / 2,
                         unload_t, total * path_base_radius / pinion_reference_radius)


def path_stiffness_at_rack(input_mesh: float, rack_mesh: float, path_base_radius: float,
                           pinion_reference_radius: float, rack_pressure_angle: float,
                           shaft_torsion: float = math.inf) -> float:
    """One path's linear stiffness at the rack (N/mm along x), the input held: the input mesh
    (N/mm along its line of action) reflected through the path shaft, ``(r_b,path / r_pinion)^2``,
    the path shaft's torsion between its two gears (N·mm/rad) over ``r_pinion^2``, and the rack
    mesh along the rack, ``k cos^2(alpha_t)``, in series."""
    reflected = input_mesh * (path_base_radius / pinion_reference_radius) ** 2
    along = rack_mesh * math.cos(rack_pressure_angle) ** 2
    twist = shaft_torsion / pinion_reference_radius ** 2
    return 1.0 / (1.0 / reflected + 1.0 / twist + 1.0 / along)


def carriage_k3(carriage_spring_rate: float, lever: float) -> float:
    """The carriage spring as the ``k_3`` of Eqs. 5-6 at the rack (N/mm): ``k_c / lambda^2``."""
    return carriage_spring_rate / lever ** 2


__all__ = ["RackDriveFrame", "closure_residual", "solve_carriage", "keying_for_closure", "pinion_rotation_on_rack",
           "PreloadForces", "preload_forces", "path_stiffness_at_rack", "carriage_k3"]
