"""Measured data: fitting the declared model, diagnosing residuals, adding effects (numpy/scipy).

Public API (``geargen fit`` is :func:`geargen.commands.fit.fit_files` on top of these):

- :func:`geargen.fit.measurement.read_measurement` ``(csv_path) -> Measurement``: NAME.csv and its
  sidecar NAME.toml, validated (contracts/measurements.md); :func:`write_measurement` the reverse.
- :func:`geargen.fit.selection.diagnose` ``(measurement, rule=SelectionRule()) -> Diagnosis``: noise
  estimate, nominal and declared fits, effects added one (or a pair) at a time, residual and
  plausibility tests, the datasheet figures; ``Diagnosis.to_json()`` is the contract's report.
- :mod:`geargen.fit.orders` shaft and mesh orders; :mod:`geargen.fit.periodogram` the least-squares
  order spectrum; :mod:`geargen.fit.noise` the model-free noise level; :mod:`geargen.fit.effects`
  the effect library; :mod:`geargen.fit.model` the declared models and joint least squares
  (:mod:`geargen.fit.transmission` that of a transmission-error record); :mod:`geargen.fit.datasheet`
  the model-free datasheet figures (hysteresis loss, lost motion, K1/K2/K3, transmission accuracy).
- :mod:`geargen.fit.simulate` the bench simulator (truth model -> Measurement) used by tests and bench.
- :func:`geargen.fit.reporting.report_input` turns a Diagnosis into the report layer's input
  (:mod:`geargen.report.fit` writes the Markdown and plots).
"""
