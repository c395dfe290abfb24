"""The only package that imports CadQuery/OCP: solids, assemblies, STEP/STL export."""

import gc as _gc


def _import_kernel() -> None:
    """Import the kernel's bindings with the garbage collector paused, then freeze what they made.

    Loading OCP creates ~230,000 tracked objects (its classes and their methods) at once; with the
    collector running, that import alone paid two full collections (~0.1-0.2 s of processor time
    in every build) and every later full collection would walk them all again. They live as long
    as the process: frozen, no collection looks at them."""
    import sys
    if "OCP.OCP" in sys.modules:
        return
    enabled = _gc.isenabled()
    _gc.disable()
    try:
        import OCP.OCP  # noqa: F401
    finally:
        _gc.freeze()
        if enabled:
            _gc.enable()


_import_kernel()
