"""Pure math: involute geometry, centre synthesis, stiffness, tolerances (numpy/scipy, no CAD kernel)."""
