"""2-D tooth outlines as numpy arrays (exact involute and trochoid), no CAD kernel."""
