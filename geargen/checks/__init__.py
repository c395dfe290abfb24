"""Geometric mesh checks: exact 2-D profiles (pure) and sections of exported solids (CAD)."""
