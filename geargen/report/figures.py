"""Writing matplotlib figures: one place that creates the folder, saves and frees the figure."""

from __future__ import annotations

from pathlib import Path


def save_png(fig, path, dpi: int = 110) -> Path:
    """Save ``fig`` as PNG at ``path`` (folders created) and close it, so long runs do not leak figures."""
    import matplotlib.pyplot as plt

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path
