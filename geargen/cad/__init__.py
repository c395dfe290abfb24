"""The only package that imports CadQuery/OCP: solids, assemblies, STEP/STL export."""
