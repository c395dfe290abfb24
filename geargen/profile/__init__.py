"""2-D tooth outlines as numpy arrays (exact involute and trochoid), no CAD kernel: the outline of
one tooth (:mod:`geargen.profile.tooth`), its segments (:mod:`geargen.profile.segments`), internal
gears (:mod:`geargen.profile.internal`), B-spline fits and tessellation."""
