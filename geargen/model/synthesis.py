"""What the centre synthesis and its error analysis computed for one design (internal units):
the record every command reads (``geargen synth`` prints it, the resolved layout carries it)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.core.synthesis import CentreSynthesis, LoopSolution, Placement
from geargen.core.tolerance import ErrorBudget, ExactErrorBudget, MonteCarloResult, SensitivityTable
from geargen.design.synthesis import GearErrors, MonteCarloSettings, SynthesisInputs
from geargen.units import LENGTH_SUFFIXES


@dataclass(frozen=True)
class SynthesisRun:
    """Everything ``geargen synth`` computed for one design (internal units)."""

    design_name: str
    design_sha256: str
    length_unit: str
    inputs: SynthesisInputs
    synthesis: CentreSynthesis
    exact_min_backlash: LoopSolution
    placement: Placement
    modelled_backlash: tuple[float, float] = (math.nan, math.nan)
    placement_modelled: Placement | None = None
    errors: tuple[GearErrors, ...] | None = None
    budget: ErrorBudget | None = None
    exact_budget: ExactErrorBudget | None = None
    monte_carlo: MonteCarloResult | None = None
    monte_carlo_settings: MonteCarloSettings | None = None
    monte_carlo_seconds: float | None = None
    geometry_sensitivity: SensitivityTable | None = None
    tolerance_sensitivity: SensitivityTable | None = None
    resolved: dict | None = None  # geargen.model.Layout.to_dict() of the drive this synthesis placed

    @property
    def scale(self) -> float:
        """mm in one design length unit."""
        return LENGTH_SUFFIXES[self.length_unit]

    def length(self, value_mm):
        """A length (float or array, mm) in the design unit."""
        return value_mm / self.scale

    @property
    def exact_min_backlash_x1(self) -> float:
        return float(self.exact_min_backlash.carriage_x[0]) - self.synthesis.x2

    @property
    def exact_min_backlash_C1(self) -> float:
        return math.hypot(self.exact_min_backlash_x1, self.synthesis.y2)
