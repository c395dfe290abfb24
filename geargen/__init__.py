"""geargen: parametric CAD for anti-backlash gear assemblies (Hale & Slocum, Precision Engineering 1994).

Importing the package is cheap: the CAD kernel is only loaded by ``geargen.cad``.
"""

__version__ = "0.1.0"
