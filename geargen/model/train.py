"""The drive as its servo sees it (``geargen train``): every rotating part's inertia and speed, each
stage's stiffness and lost motion at the output, the position loop against a direct drive, the
paper's strategy (which stages to preload) and the alternatives to an anti-backlash train.

Pure data (no CAD kernel): the solids' mass properties come in from the CAD layer
(:func:`geargen.cad.mass.mass_properties`) as :class:`BodyPart` records; everything else is read
from the resolved drive (:class:`geargen.model.Layout`) and the one stiffness summary
(:func:`geargen.model.analysis.stiffness`), so the numbers here are the ones every command reports.

Conventions (Hale & Slocum's R^2 law):

* a part's ``speed`` is its speed over the output's; ``ratio_to_motor`` = motor speed / its speed;
  its inertia reflected to the motor is ``J / ratio_to_motor^2`` exactly;
* a stage is a mesh with the shaft of its driven gear (the first stage also with its driver's shaft
  when nothing drives that shaft through a modelled stage): its stiffness at the output is the series sum
  of its mesh and of the components on that shaft ([stiffness.components] and the loop's meshes, as
  ``geargen stiffness`` has them); in the preloaded loop the two paths share each stage by the torque
  each carries (stage compliance ``sum_p (share_p)^2 c_stage,p``: the stage's elastic energy, so the
  stages add up to the loop's drive compliance exactly when a preload spring stores none);
* a stage's lost motion is its backlash as an angle at the output: circumferential backlash ``B``
  at the driver's reference circle, ``B / (r_driver speed_driver)``; a stage in the preloaded loop
  has none left while the preload holds (the paper's Type 1/2 drives), the others keep theirs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from geargen.core.servo import TwoMass, chain_modes, closed_loop, gains_for, mesh_loss_factor
from geargen.core.stiffness import series
from geargen.design.train import TrainSettings, train_settings
from geargen.drives.kind import two_loop_meshes
from geargen.errors import DesignError

NM = 1e3  # N·mm per N·m


@dataclass(frozen=True)
class BodyPart:
    """A solid's mass properties from the CAD layer, unit density, in its own frame (mm)."""

    name: str
    volume: float  # mm^3
    axial_moment: float  # mm^5, integral of r^2 dV about its own axis
    off_axis: float  # mm, its centre of mass from that axis
    body: tuple[str, ...]  # the parts of its rigid body (geargen.checks.structure)
    on_motor: bool = False  # its body is turned by the motor directly (touches the motor's shaft)


@dataclass(frozen=True)
class PartInertia:
    name: str
    material: str
    mass_kg: float
    inertia_own_axis_kg_m2: float
    speed: float  # over the output's
    ratio_to_motor: float
    turns_with: str  # the gear (or "motor") whose speed it has

    @property
    def reflected_to_motor_kg_m2(self) -> float:
        return self.inertia_own_axis_kg_m2 / self.ratio_to_motor ** 2

    @property
    def reflected_to_output_kg_m2(self) -> float:
        return self.inertia_own_axis_kg_m2 * self.speed ** 2


@dataclass(frozen=True)
class TrainStage:
    """One stage from the motor: ``ratio`` its own (driven teeth / driver teeth); ``speed`` its
    driver's speed over the output's; stiffness at the output N·mm/rad (None: not modelled);
    lost motion at the output, rad (None: backlash not known)."""

    name: str
    driver: str
    driven: str
    ratio: float
    speed: float
    preloaded: bool
    stiffness: float | None
    single_path_stiffness: float | None
    lost_motion: float | None
    lost_motion_max: float | None
    loss_factor: float
    lost_motion_min: float | None = None  # at the design's smallest backlash
    components: tuple[str, ...] = ()
    source: str = ""
    pressure_angle: float = math.radians(20.0)
    driven_base_radius: float = math.nan
    driven_speed: float = math.nan
    runout_tir: float | None = None  # both gears' TIRs summed (mm): crowded centres' leftover
    single_path_mesh_compliance: float = 0.0  # rad/N·mm: the stage's mesh in one path


@dataclass(frozen=True)
class TrainAnalysis:
    name: str
    motor_speed: float  # over the output's
    parts: tuple[PartInertia, ...]
    stages: tuple[TrainStage, ...]
    settings: TrainSettings
    summary: Any  # geargen.core.stiffness.StiffnessSummary
    loop_spring_compliance: float = 0.0  # what the preload spring adds to the drive compliance
    warnings: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()

    # ---- totals
    @property
    def parts_inertia_at_motor(self) -> float:
        return sum(p.reflected_to_motor_kg_m2 for p in self.parts)

    @property
    def inertia_at_motor(self) -> float:
        """kg·m²: the rotor, every modelled rotating part and the load, at the motor."""
        rotor = self.settings.motor_rotor_inertia or 0.0
        return rotor + self.parts_inertia_at_motor + self.settings.load_inertia / self.motor_speed ** 2

    @property
    def stiffness_at_output(self) -> float:
        """N·mm/rad: the modelled stages in series (and the preload spring's share)."""
        spring = 1.0 / self.loop_spring_compliance if self.loop_spring_compliance else None
        return _series([s.stiffness for s in self.stages] + [spring])

    @property
    def lost_motion(self) -> float:
        """rad at the output, as built: the stages outside the preloaded loop."""
        return sum(s.lost_motion or 0.0 for s in self.stages if not s.preloaded)

    @property
    def lost_motion_without_preload(self) -> float:
        return sum(s.lost_motion or 0.0 for s in self.stages)

    @property
    def max_output_torque(self) -> float:
        return self.summary.max_output_torque

    @property
    def preload_friction(self) -> float:
        """N·mm at the output: the loop's preload torque drags in every preloaded mesh of both paths."""
        preload = self.summary.drive.preload
        return sum(2 * preload * s.loss_factor for s in self.stages if s.preloaded)

    def dominant_stage(self) -> TrainStage | None:
        known = [s for s in self.stages if s.lost_motion is not None]
        return max(known, key=lambda s: s.lost_motion) if known else None

    # ---- the servo
    def two_mass(self) -> TwoMass | None:
        """Motor side (rotor and every part faster than the output) against the output's shaft and
        the load, on the train's stiffness, all at the output (SI)."""
        rotor = self.settings.motor_rotor_inertia
        if rotor is None or not math.isfinite(self.stiffness_at_output):
            return None
        j1 = rotor * self.motor_speed ** 2 + sum(p.reflected_to_output_kg_m2 for p in self.parts if p.speed > 1 + 1e-9)
        j2 = self.settings.load_inertia + sum(p.reflected_to_output_kg_m2 for p in self.parts if p.speed <= 1 + 1e-9)
        if not j2 > 0:
            return None
        return TwoMass(j1, j2, self.stiffness_at_output / NM)

    def chain(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The train as a chain at the output (SI): one inertia per shaft speed, motor first, a
        spring per stage between them (the stages without a modelled stiffness are rigid: merged)."""
        rotor = self.settings.motor_rotor_inertia
        if rotor is None:
            return None
        speeds = [self.motor_speed] + [s.driven_speed for s in self.stages]
        inertia = [0.0] * len(speeds)
        inertia[0] = rotor * self.motor_speed ** 2
        for p in self.parts:
            i = min(range(len(speeds)), key=lambda k: abs(speeds[k] - p.speed))
            inertia[i] += p.reflected_to_output_kg_m2
        inertia[-1] += self.settings.load_inertia
        nodes, springs = [inertia[0]], []
        for s, j in zip(self.stages, inertia[1:]):
            if s.stiffness is None:
                nodes[-1] += j
            else:
                springs.append(s.stiffness / NM)
                nodes.append(j)
        # the loop spring's compliance rides with the last spring (in series with the loop)
        if springs and self.loop_spring_compliance:
            springs[-1] = 1.0 / (1.0 / springs[-1] + self.loop_spring_compliance * NM)
        return np.array(nodes), np.array(springs)

    def servo(self) -> dict[str, Any] | None:
        """The position loop on the geared drive and on a direct drive of the same motor, gains and
        load; None without a motor and a loop in [train]."""
        st = self.settings
        if not st.has_servo:
            return None
        j_geared = self.inertia_at_motor
        if st.bandwidth is not None:
            kp, kd = gains_for(j_geared, st.bandwidth, st.damping_ratio)
        else:
            kp, kd = st.position_gain, st.velocity_gain
        geared = closed_loop(j_geared, kp, kd)
        j_direct = st.motor_rotor_inertia + st.load_inertia + sum(
            p.inertia_own_axis_kg_m2 for p in self.parts if p.speed <= 1 + 1e-9)
        direct = closed_loop(j_direct, kp, kd)
        # the same bandwidth on the direct drive (its gains retuned), the motor's damping kept
        direct_same_bandwidth_damping = kd / (2.0 * geared.natural_frequency * j_direct)
        out = {"position_gain_Nm_per_rad": kp, "velocity_gain_Nm_s_per_rad": kd,
               "inertia_at_motor_kg_m2": j_geared, "direct_drive_inertia_kg_m2": j_direct,
               "natural_frequency_Hz": geared.natural_frequency_hz, "damping_ratio": geared.damping_ratio,
               "direct_natural_frequency_Hz": direct.natural_frequency_hz,
               "direct_damping_ratio": direct.damping_ratio,
               "frequency_gain_over_direct": geared.natural_frequency / direct.natural_frequency,
               "damping_gain_over_direct": geared.damping_ratio / direct.damping_ratio,
               "damping_gain_at_equal_bandwidth": geared.damping_ratio / direct_same_bandwidth_damping,
               "ratio": self.motor_speed,
               "servo_stiffness_at_output_Nm_per_rad": kp * self.motor_speed ** 2}
        two = self.two_mass()
        if two is not None:
            out["resonance_Hz"] = two.resonance / (2 * math.pi)
            out["antiresonance_Hz"] = two.antiresonance / (2 * math.pi)
            out["two_mass"] = {"j_motor_side_at_output_kg_m2": two.j_motor, "j_load_side_kg_m2": two.j_load,
                               "stiffness_Nm_per_rad": two.stiffness}
            nodes, springs = self.chain()
            if len(springs):
                out["chain_first_mode_Hz"] = float(chain_modes(nodes, springs)[1]) / (2 * math.pi)
        return out

    # ---- the paper's strategy
    def advice(self) -> dict[str, Any] | None:
        """Which stages, from the output up, to make anti-backlash for the allowed lost motion, and
        what it costs: each preloaded stage doubles its path's stiffness (Type 2, equal paths) and
        drags ``2 x preload x loss factor`` (preload = half the maximum load, the paper's minimum)."""
        allowed = self.settings.allowed_lost_motion
        if allowed is None:
            return None
        order = list(reversed(self.stages))
        preload = self.max_output_torque / 2
        chosen, left = [], self.lost_motion_without_preload
        unknown = [s.name for s in self.stages if s.lost_motion is None]
        for s in order:
            if left <= allowed * (1 + 1e-12):
                break
            chosen.append(s)
            left -= s.lost_motion or 0.0
        met = left <= allowed * (1 + 1e-12)
        friction = sum(2 * preload * s.loss_factor for s in chosen)
        stiff_single = _series(s.single_path_stiffness for s in self.stages)
        stiff_advised = _series(self._stage_stiffness(s, s in chosen) for s in self.stages if s.single_path_stiffness)
        design = [s.name for s in self.stages if s.preloaded]
        return {"allowed_lost_motion_urad": allowed * 1e6, "preload": [s.name for s in chosen],
                "met": met, "lost_motion_left_urad": left * 1e6,
                "stiffness_no_preload_Nm_per_rad": stiff_single / NM,
                "stiffness_advised_Nm_per_rad": stiff_advised / NM,
                "preload_friction_Nm": friction / NM, "preload_Nm": preload / NM,
                "design_preloads": design, "design_agrees": sorted(design) == sorted(s.name for s in chosen),
                "stages_backlash_unknown": unknown}

    def _stage_stiffness(self, stage: TrainStage, preloaded: bool) -> float:
        """A stage's stiffness with or without a preloaded second path: the model's where the design
        has it so, else one path (doubled for a second, equal path: Type 2)."""
        if preloaded == stage.preloaded and stage.stiffness:
            return stage.stiffness
        return stage.single_path_stiffness * (2 if preloaded else 1)

    # ---- the alternatives on one load spec
    def alternatives(self) -> list[dict[str, Any]]:
        """Each way of dealing with backlash that the paper weighs, on this drive's stages and its
        maximum output torque ``T`` (both ways). The preloaded stages are what each alternative
        replaces; the stages outside the loop stay as built (except under a constant force, which
        keeps the whole train from reversing). Stiffness and lost motion at the output; motor torque
        to carry ``T`` plus the friction; friction torque at the output."""
        T = self.max_output_torque
        R = self.motor_speed
        loop = [s for s in self.stages if s.preloaded]
        rest = [s for s in self.stages if not s.preloaded]
        if not loop:
            return []
        rest_lost = sum(s.lost_motion or 0.0 for s in rest)
        single = _series(s.single_path_stiffness for s in self.stages)
        loss_loop = sum(s.loss_factor for s in loop)
        loss_all = sum(s.loss_factor for s in self.stages)
        rows = []

        def row(name, stiffness, lost, friction, motor_torque, note, motors=1):
            rows.append({"name": name, "stiffness_at_output_Nm_per_rad": stiffness / NM,
                         "lost_motion_at_output_urad": lost * 1e6, "preload_friction_Nm": friction / NM,
                         "motor_torque_Nm": motor_torque / NM, "motors": motors, "how": note})

        kind = self.summary.drive_type
        f_design = self.preload_friction
        row(f"{'Type 2' if kind == 'type2' else 'Type 1'}: this design", self.stiffness_at_output, self.lost_motion,
            f_design, (T + f_design) / R, f"preload {self.summary.drive.preload / NM:.4g} N·m in both paths")
        f1 = 2 * T * loss_loop
        row("Type 1 (preload = maximum load)", _series(s.stiffness for s in self.stages), self.lost_motion, f1,
            (T + f1) / R, "the same paths; the paper: Type 1 needs a preload equal to the maximum load")
        if kind == "type1":
            f2 = 2 * (T / 2) * loss_loop
            row("Type 2 (preload = half the maximum load)", _series(s.stiffness for s in self.stages), self.lost_motion,
                f2, (T + f2) / R, "the same paths with a preload spring at the common input")
        fc = T * loss_all
        row("constant force", single, 0.0, fc, (2 * T + fc) / R,
            "one path; a constant torque T keeps the load from reversing: the train carries up to 2 T one way")
        crowded = rest_lost
        unknown_runout = [s.name for s in loop if s.runout_tir is None]
        for s in loop:
            if s.runout_tir is not None:
                crowded += 2 * math.tan(s.pressure_angle) * s.runout_tir / (s.driven_base_radius / math.cos(
                    s.pressure_angle)) / s.driven_speed
        row("crowded centres, rigid", single, crowded, 0.0, T / R,
            "one path, centres set where the error budget is tightest: the runout's backlash stays"
            + (f" (no [errors] for {', '.join(unknown_runout)})" if unknown_runout else ""))
        fsum, comp = 0.0, []
        for s in loop:
            # the spring must out-push the separating force T tan(alpha) / r_w at the driven gear
            r_w = s.driven_base_radius / math.cos(s.pressure_angle)
            spring = (T / s.driven_speed) * math.tan(s.pressure_angle) / r_w
            flank = spring / (2 * math.sin(s.pressure_angle))
            fsum += s.loss_factor * 2 * flank * s.driven_base_radius * s.driven_speed
            comp.append(f"{s.name} {spring:.4g} N")
        # one path whose loop meshes carry on both flanks: their mesh compliance halves
        compliant = _series(1.0 / (1.0 / s.single_path_stiffness - (s.single_path_mesh_compliance / 2 if s.preloaded
                                                                    else 0.0))
                            for s in self.stages if s.single_path_stiffness)
        row("crowded centres, compliant", compliant, rest_lost, fsum, (T + fsum) / R,
            "one path, each loop mesh pushed into mesh by a spring (both flanks carry): " + ", ".join(comp))
        fb = 2 * (T / 2) * loss_all
        row("dual motor, constant bias", 2 * single, 0.0, fb, T / R,
            "two motors each with its own train, bias T/2 between them (Fig. 1b): each motor carries T", motors=2)
        return rows


def analyse(layout, summary, parts: list[BodyPart]) -> TrainAnalysis:
    """The train of the resolved drive ``layout`` with the stiffness ``summary``
    (:func:`geargen.model.analysis.stiffness`) and the rotating solids' ``parts``."""
    settings = layout.resolved.train
    train = layout.resolved.drive_train
    if train is None:
        raise DesignError("stiffness.train", "'custom': geargen train needs the gears of a dual or split pinion",
                          "'dual_pinion' or 'split_pinion'")
    motor_speed = float(layout.ratio["total"])
    warnings, notes = [], []

    # --- which gear each rotating body turns with
    gear_names = {g.name: [b.name for b in g.gears] for g in layout.gears}
    orbits = _planet_motions(layout, train)
    inertias = []
    for bp in parts:
        if bp.name in orbits:
            # a planet (or its pin) turns about its own axis and orbits with the carrier: its kinetic
            # energy is J_own w_own^2 / 2 plus m a^2 w_carrier^2 / 2, two rows (its mass counted once)
            own, carrier, radius = orbits[bp.name]
            body = _part_inertia(bp, settings, own, motor_speed, "carrier" if own == carrier else f"{bp.name} (spin)")
            inertias += [body, PartInertia(f"{bp.name} orbit", body.material, 0.0, body.mass_kg * radius ** 2 * 1e-6,
                                           carrier, motor_speed / carrier, "carrier (m a^2)")]
            continue
        turns_with, speed = None, None
        for member in bp.body:
            for gname in gear_names.get(member, ()):
                s = train.gear_ratio(gname)
                if s is not None:
                    turns_with, speed = gname, s
                    break
            if speed is not None:
                break
        if speed is None:
            if not bp.on_motor:
                raise DesignError("train", f"part {bp.name} turns, but geargen cannot say how fast: no gear of the "
                                  "train and no motor in its rigid body", "a part on a gear's or the motor's shaft")
            turns_with, speed = "motor", motor_speed
        gyration = math.sqrt(bp.axial_moment / bp.volume)
        if bp.off_axis > 0.1 * gyration:  # a slit collar is a little unbalanced; a part built off its axis is not
            raise DesignError("train", f"part {bp.name}: its centre of mass is {bp.off_axis:.4g} mm off its own axis, "
                              f"{bp.off_axis / gyration:.0%} of its radius of gyration",
                              "rotating parts built about their local z axis (within 10 %)")
        inertias.append(_part_inertia(bp, settings, speed, motor_speed, turns_with))

    # --- stages, motor first; the preload spring's share of the loop's drive compliance (unequal
    # type 2 paths only) is what the paths' shares of the stages leave of it
    stages, paths_c = _stages(layout, summary, train, settings, motor_speed, warnings)
    loop_c = 1.0 / summary.drive.drive_stiffness
    spring = max(loop_c - paths_c, 0.0)
    if spring > 1e-9 * loop_c:
        notes.append(f"the preload spring stores {spring / loop_c:.1%} of the loop's drive compliance (unequal paths)")
    if settings.motor_rotor_inertia is None:
        warnings.append("no motor_rotor_inertia_* in [train]: the inertia at the motor leaves the rotor out")
    return TrainAnalysis(layout.identity.name, motor_speed, tuple(inertias), tuple(stages), settings, summary,
                         loop_spring_compliance=spring, warnings=tuple(warnings), notes=tuple(notes))


def _planet_motions(layout, train) -> dict[str, tuple[float, float, float]]:
    """Each planet and planet pin of a planetary stage, by part name: (its speed about its own
    axis, its carrier's speed, both over the output's, and its carrier radius, mm). Ring fixed:
    relative to the carrier the ring turns at -w_c and the planet at -w_c z_r / z_p (an internal
    mesh turns both one way), so its spin is w_c (1 - z_r / z_p), a speed |1 - z_r / z_p| times the
    carrier's; a pin, fixed in the carrier, turns with it."""
    out = {}
    for st in layout.resolved.stages:
        if st.kind != "planetary":
            continue
        group = [g for g in layout.gears if g.group == f"stage_{st.name}"]
        ring = next(g for g in group if "planetary_ring" in g.roles)
        carrier = train.gear_ratio(st.sun) / float(st.ratio(layout.resolved.gears))
        planets = [g for g in group if "planetary_planet" in g.roles]
        for i, g in enumerate(planets, start=1):
            radius = math.dist(g.centre, ring.centre)
            out[g.name] = (carrier * abs(1 - ring.spec.teeth / g.spec.teeth), carrier, radius)
            out[f"carrier_{st.name}_pin_{i}"] = (carrier, carrier, radius)  # geargen.drives.planetary.place.carrier
    return out


def _part_inertia(bp: BodyPart, settings: TrainSettings, speed: float, motor_speed: float,
                  turns_with: str) -> PartInertia:
    """``bp`` in its material (kg, kg·m² from mm^3, mm^5 and kg/m^3), turning ``speed`` times the output."""
    density = settings.density(bp.name)
    return PartInertia(bp.name, settings.material_of(bp.name), density * bp.volume * 1e-9,
                       density * bp.axial_moment * 1e-15, speed, motor_speed / speed, turns_with)


def _series(stiffnesses) -> float:
    """The known (non-None, non-zero) stiffnesses in series; ``inf`` when there are none."""
    known = [k for k in stiffnesses if k]
    return series(*known) if known else math.inf


def _path_shares(summary) -> tuple[float, float]:
    """The share of a drive torque each path carries while both are loaded."""
    g1, g2 = summary.drive.path_force_rates
    return g1 / (g1 + g2), g2 / (g1 + g2)


def _stages(layout, summary, train, settings: TrainSettings, motor_speed: float,
            warnings: list) -> tuple[list[TrainStage], float]:
    """The stages, motor first, and the compliance the two paths' shares give the loop's stages."""
    resolved = layout.resolved
    mu = settings.mesh_friction_coefficient
    shares = _path_shares(summary)
    out: list[dict] = []

    def runout(*names) -> float | None:
        total = 0.0
        for n in names:
            e = resolved.gear_errors(n) if resolved.gives_errors(n) else None
            if e is None:
                return None
            total += e.bearing_eccentricity_tir + e.pitch_line_eccentricity_tir + e.tooth_to_tooth_tir
        return total

    def mesh_stage(mesh, name: str, driven_speed: float, preloaded: bool, source: str) -> dict:
        """A stage that is a placed mesh: backlash from its modelled teeth, as output angles."""
        a, b = mesh.gear1, mesh.gear2
        speed = train.gear_ratio(a.name)
        at_output = 1.0 / (a.reference_radius * speed)
        return dict(name=name, driver=a.name, driven=b.name, ratio=b.teeth / a.teeth, speed=speed,
                    driven_speed=driven_speed, preloaded=preloaded, lost_motion=mesh.modelled_backlash * at_output,
                    lost_motion_min=mesh.backlash_min * at_output, lost_motion_max=mesh.backlash_max * at_output, loss_factor=mesh_loss_factor(mu, a.teeth, b.teeth),
                    pressure_angle=a.transverse_pressure_angle, driven_base_radius=b.base_radius,
                    runout_tir=runout(a.name, b.name), source=source)

    def planetary_stage(st) -> dict:
        """The planetary stage (ring fixed, sun in, carrier out) as one stage.

        Lost motion: with the sun held, the carrier turns freely while each planet takes up both its
        meshes' play; along the lines of action, which lie r_bs and r_br from the axis, the carrier's
        turn phi moves the planet by phi r_bs at the sun and phi r_br at the ring, and the planet's
        spin shares the take-up between them, so phi (r_bs + r_br) = j_bt,sp + j_bt,pr: in
        circumferential backlash at the reference circles (j_t = j_bt / cos(alpha_t)),
        phi = (j_sp + j_pr) / (r_s + r_r). Then at the output, / (the carrier's speed over the output's).
        Stiffness: each planet's two meshes in series (equal forces on the planet: its spin balances
        them), Eq. 1 or ISO 6336 as [stiffness] says, acting at r_bs and r_br: per planet
        (r_bs + r_br)^2 / (1/k_sp + 1/k_pr); the planets in parallel sharing the torque equally (a
        floating sun's ideal: with position errors fewer carry at small torques); the carrier, its pins
        and the ring's mounting rigid. Loss: both meshes' losses in the carrier's frame, z_r / (z_s + z_r)
        of the input power."""
        from geargen.core.stiffness import gear_mesh_stiffness, reflect
        from geargen.drives.planetary.place import internal_backlash
        group = [g for g in layout.gears if g.group == f"stage_{st.name}"]
        sun, planet, ring = (next(g.spec for g in group if role in g.roles)
                             for role in ("planetary_sun", "planetary_planet", "planetary_ring"))
        planets = sum("planetary_planet" in g.roles for g in group)
        sun_mesh = next(m for m in layout.meshes if m.name.startswith(f"stage_{st.name}_sun_"))
        a = sun_mesh.centre_distance
        carrier_speed = train.gear_ratio(st.sun) / float(st.ratio(resolved.gears))
        at_output = 1.0 / ((sun.reference_radius + ring.reference_radius) * carrier_speed)
        backlash = sun_mesh.modelled_backlash + internal_backlash(planet, ring, a)
        spec = resolved.stiffness.stiffness
        k_sp = gear_mesh_stiffness(sun, planet, min(sun.face_width, planet.face_width), spec.elastic_modulus,
                                   spec.mesh_stiffness, f"stages.{st.name}")[0]
        k_pr = gear_mesh_stiffness(planet, ring, min(planet.face_width, ring.face_width), spec.elastic_modulus,
                                   "eq1", f"stages.{st.name}")[0]  # ISO 6336's pair model is external: Eq. 1
        arm = sun.base_radius + ring.base_radius
        at_carrier = planets * arm ** 2 / (1.0 / k_sp + 1.0 / k_pr)
        loss = (mesh_loss_factor(mu, sun.teeth, planet.teeth)
                + mesh_loss_factor(mu, planet.teeth, -ring.teeth)) * ring.teeth / (sun.teeth + ring.teeth)
        return dict(name=f"stage {st.name} ({st.sun}-{st.planet} x{planets}-{st.ring})", driver=st.sun,
                    driven="carrier", ratio=float(st.ratio(resolved.gears)), speed=train.gear_ratio(st.sun),
                    driven_speed=carrier_speed, preloaded=False, lost_motion=backlash * at_output,
                    lost_motion_min=2 * st.backlash_min * at_output, lost_motion_max=2 * st.backlash_max * at_output,
                    loss_factor=loss, fixed_stiffness=float(reflect(at_carrier, carrier_speed)),
                    pressure_angle=sun.transverse_pressure_angle, driven_base_radius=math.nan,
                    runout_tir=None, source="planetary: sun-planet and planet-ring backlash at the carrier; "
                    f"stiffness: {planets} planets, each its two meshes in series, sharing equally")

    # upstream stages
    st_list = resolved.stages
    if st_list:
        for st in st_list:
            if st.kind == "planetary":
                out.append(planetary_stage(st))
                continue
            out.append(mesh_stage(layout.mesh(f"stage_{st.name}"), f"stage {st.name} ({st.driver}-{st.driven})",
                                  train.gear_ratio(st.driven), False,
                                  "backlash: the modelled teeth at the placed centres"))
    else:
        pairs = list(layout.settings.get("upstream_stages", ()))
        speed = motor_speed
        for i, (z1, z2) in enumerate(pairs):
            driven_speed = speed * z1 / z2
            lost = settings.upstream_backlash[i] / driven_speed if settings.upstream_backlash else None
            stiff = (settings.upstream_stiffness[i] * NM * driven_speed ** 2 if settings.upstream_stiffness else None)
            source = "backlash and stiffness: [train] upstream_*"
            if stiff is None:
                stiff = _bevel_stiffness(layout, z1, z2, driven_speed)
                if stiff is not None:
                    source = "stiffness: Eq. 1 on the bevel pair of [parts] at its mean radius"
            if lost is None:
                lost = _bevel_lost_motion(layout, z1, z2, driven_speed)
                if lost is not None:
                    source += "; backlash: the bevel pair's as cut ([parts] bevel_backlash)"
            if lost is None:
                warnings.append(f"upstream stage {z1}:{z2}: backlash not known (give [train] upstream_backlash_arcmin, "
                                "or [parts] bevel_backlash_* for the robot joint's bevel pair)")
            if stiff is None:
                warnings.append(f"upstream stage {z1}:{z2}: stiffness not known (give [train] "
                                "upstream_stiffness_Nm_per_arcmin); taken as rigid")
            out.append(dict(name=f"upstream {z1}:{z2}", driver=f"{z1} T", driven=f"{z2} T", ratio=z2 / z1,
                            speed=speed, driven_speed=driven_speed, preloaded=False, lost_motion=lost,
                            lost_motion_min=lost, lost_motion_max=lost, loss_factor=mesh_loss_factor(mu, z1, z2), fixed_stiffness=stiff,
                            source=source))
            speed = driven_speed

    # the loop (preloaded), as its drive kind stages it (geargen.drives.kind.DriveKind.loop_stages)
    loop_stages = layout.drive.loop_stages if layout.drive is not None else two_loop_meshes
    for mesh, name, ratio, source in loop_stages(layout, train.gear_ratio):
        out.append(mesh_stage(mesh, name, ratio, True, source))

    # components to stages: a stage holds the components on its driven shaft (same speed)
    speeds = [d["driven_speed"] for d in out]
    compliance = [0.0] * len(out)
    single = [0.0] * len(out)
    mesh_single = [0.0] * len(out)
    members: list[list[str]] = [[] for _ in out]
    seen = set()
    paths_c = 0.0
    for path, share in ((summary.path1, shares[0]), (summary.path2, shares[1]), (summary.common, None)):
        for c in path.components:
            i = max((k for k in range(len(out)) if math.isclose(speeds[k], c.ratio, rel_tol=1e-9)), default=None)
            if i is None:  # the motor-side shaft of the first stage (a split pinion's pinion shaft)
                i = min((k for k in range(len(out)) if math.isclose(out[k]["speed"], c.ratio, rel_tol=1e-9)),
                        default=None)
            if i is None:
                raise DesignError(f"stiffness.components.{c.name}", f"turns {c.ratio:.6g} times as fast as the output, "
                                  "as no stage's driven shaft does", "a component on a shaft of the train")
            if share is None:
                compliance[i] += 1.0 / c.at_output
                single[i] += 1.0 / c.at_output
            else:
                compliance[i] += share ** 2 / c.at_output
                paths_c += share ** 2 / c.at_output
                if path is summary.path1:
                    single[i] += 1.0 / c.at_output
                    if c.kind == "mesh":
                        mesh_single[i] += 1.0 / c.at_output
            if c.name not in seen:
                members[i].append(c.name)
                seen.add(c.name)
    stages = []
    for d, c, c1, cm, names in zip(out, compliance, single, mesh_single, members):
        fixed = d.pop("fixed_stiffness", None)
        if fixed is not None:
            c += 1.0 / fixed
            c1 += 1.0 / fixed
        stiffness = 1.0 / c if c > 0 else None
        if stiffness is None and not d["name"].startswith("upstream"):
            warnings.append(f"{d['name']}: no [stiffness.components] on it, so the drive stiffness leaves it out")
        stages.append(TrainStage(stiffness=stiffness, single_path_stiffness=1.0 / c1 if c1 > 0 else None,
                                 single_path_mesh_compliance=cm, components=tuple(names), **d))
    return stages, paths_c


def _bevel_lost_motion(layout, z1: int, z2: int, driven_speed: float) -> float | None:
    """The robot joint's bevel pair's backlash as placed (:func:`geargen.drives.dual_pinion.bevel.bevel_drive`:
    circumferential at the gear's heel pitch circle, what its teeth are cut to) as an angle at the
    output: / the heel pitch radius / the driven shaft's speed; None without a bevel pair of these teeth."""
    from geargen.drives.dual_pinion.bevel import bevel_drive
    placed = bevel_drive(layout)
    if placed is None or (placed.pinion.teeth, placed.gear.teeth) != (z1, z2):
        return None
    return placed.backlash / (placed.gear.reference_diameter / 2) / driven_speed


def _bevel_stiffness(layout, z1: int, z2: int, driven_speed: float) -> float | None:
    """Eq. 1 on the robot joint's bevel pair as placed (:func:`geargen.drives.dual_pinion.bevel.bevel_drive`:
    the specs the solids are built from), at the driven gear's mean radius, at the output; None
    without a bevel pair of these teeth."""
    from geargen.core.stiffness import mesh_stiffness, reflect, torsional_from_linear
    from geargen.drives.dual_pinion.bevel import bevel_drive
    placed = bevel_drive(layout)
    if placed is None or (placed.pinion.teeth, placed.gear.teeth) != (z1, z2):
        return None
    gear = placed.gear
    r_mean = gear.reference_diameter / 2 - gear.face_width / 2 * math.sin(gear.pitch_cone_angle)
    r_base = r_mean * math.cos(gear.pressure_angle)
    k = float(mesh_stiffness(layout.resolved.stiffness.stiffness.elastic_modulus, gear.face_width))
    return float(reflect(torsional_from_linear(k, r_base), driven_speed))


# ---------------------------------------------------------------------------------------------
# the dual-motor drive (Fig. 1)

@dataclass(frozen=True)
class DualMotorAnalysis:
    """A ``[dual_motor]`` design: each motor's path (gearhead, pinion shaft, mesh) at the output,
    the Fig. 1 drive (:class:`geargen.core.servo.DualMotorDrive`) for the design's control and the
    other, and the parts' inertias. Torques N·m, stiffnesses N·m/rad (SI, the servo's units)."""

    name: str
    spec: Any  # geargen.design.train.DualMotorSpec
    motor_speed: float
    mesh_ratio: float
    path_components: tuple[tuple[str, float], ...]  # (name, N·m/rad at the output) of one path
    backlash: tuple[float, float]  # rad at the output, each path's mesh
    parts: tuple[PartInertia, ...]
    settings: TrainSettings
    loss_factor: float

    @property
    def path_stiffness(self) -> float:
        return 1.0 / sum(1.0 / k for _, k in self.path_components)

    def drive(self, control: str | None = None):
        from geargen.core.servo import DualMotorDrive
        sp = self.spec
        control = control or sp.control
        peak = sp.motor_peak_torque / NM * self.motor_speed
        bias = sp.bias_torque / NM
        return DualMotorDrive(self.path_stiffness, self.path_stiffness, bias, control, peak, max(self.backlash))

    def comparison(self) -> list[dict[str, Any]]:
        """Both controls on the design's load: capacity, the bias the load needs, each motor's
        torque, the zones' stiffness, the friction the bias drags through both meshes."""
        load = self.spec.max_output_torque / NM
        rows = []
        for control in ("bias", "unidirectional"):
            d = self.drive(control)
            need = d.bias_for(load)
            rows.append({"control": control, "capacity_Nm": d.capacity, "bias_Nm": d.bias,
                         "bias_needed_for_load_Nm": need, "reversal_command_Nm": d.reversal_command,
                         "motor_torque_at_load_Nm": d.peak_needed(load) / self.motor_speed,
                         "zones": d.zones(), "bias_friction_Nm": 2 * d.bias * self.loss_factor,
                         "carries_load": d.peak_needed(load) <= d.peak * (1 + 1e-12)})
        return rows


def dual_motor_analysis(design, parts: list[BodyPart]) -> DualMotorAnalysis:
    """The ``[dual_motor]`` drive of ``design`` with its gears' solids ``parts``."""
    from geargen.core.stiffness import gear_mesh_stiffness, shaft_torsional_stiffness
    from geargen.core.synthesis import modelled_backlash
    from geargen.design.train import dual_motor_spec
    sp = dual_motor_spec(design)
    settings = train_settings(design)
    pin = design.gear(sp.pinions[0])
    out = design.gear(sp.output)
    mesh_ratio = out.teeth / pin.teeth
    motor_speed = sp.upstream_ratio * mesh_ratio
    w = min(pin.face_width, out.face_width)
    k_mesh = gear_mesh_stiffness(pin, out, w, sp.elastic_modulus, sp.mesh_stiffness, "dual_motor.pinions")[0]
    label = "mesh (Eq. 1)" if sp.mesh_stiffness == "eq1" else "mesh (ISO 6336-1 method B)"
    comps = [(label, k_mesh * out.base_radius ** 2 / NM),
             ("pinion shaft", shaft_torsional_stiffness(sp.shear_modulus, sp.pinion_shaft_diameter,
                                                        sp.pinion_shaft_length) * mesh_ratio ** 2 / NM)]
    if sp.upstream_stiffness is not None:
        comps.append(("gearhead", sp.upstream_stiffness * mesh_ratio ** 2 / NM))
    backlash = tuple(modelled_backlash(design.gear(p), out, c) / out.reference_radius
                     for p, c in zip(sp.pinions, sp.centre_distances))
    speeds = {sp.pinions[0]: mesh_ratio, sp.pinions[1]: mesh_ratio, sp.output: 1.0}
    inertias = [_part_inertia(bp, settings, speeds[bp.name], motor_speed, bp.name) for bp in parts]
    return DualMotorAnalysis(design.name, sp, motor_speed, mesh_ratio, tuple(comps), backlash, tuple(inertias),
                             settings, mesh_loss_factor(settings.mesh_friction_coefficient, pin.teeth, out.teeth))


__all__ = ["BodyPart", "PartInertia", "TrainStage", "TrainAnalysis", "analyse", "DualMotorAnalysis",
           "dual_motor_analysis"]
