"""Measured data: fitting the declared model, diagnosing residuals, adding effects (numpy/scipy)."""
