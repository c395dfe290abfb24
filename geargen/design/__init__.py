"""Design files: loading TOML, keys with units, validated input dataclasses (stdlib + numpy only)."""
