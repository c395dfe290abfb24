"""Writing matplotlib figures: one place that creates the folder, saves and frees the figure."""

from __future__ import annotations

from pathlib import Path

from geargen.outputs import atomic_path

FIGURE_FORMATS = ("png", "svg")
#: zlib level of the figures' PNG files: 3 encodes ~30 % faster than PIL's default 6 (the filtering
#: of the rows, the same at every level, is most of what is left); the same pixels, files within
#: about +12 % (a rendered view) and -2 % (the layout drawing's lines and text)
PNG_COMPRESS_LEVEL = 3


def write_figure(fig, path, **savefig) -> Path:
    """``fig.savefig`` to ``path`` through :func:`geargen.outputs.atomic_path` (atomic, kept inside
    the output folder being written, a full disk said as one); ``savefig``: its keyword arguments."""
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, **savefig)
    return path


def save_png(fig, path, dpi: int = 110) -> Path:
    """Save ``fig`` as PNG at ``path`` (folders created) and close it, so long runs do not leak figures."""
    import matplotlib.pyplot as plt

    path = write_figure(fig, path, dpi=dpi)
    plt.close(fig)
    return path


def save_figure(fig, folder, name: str, dpi: int = 110) -> dict[str, Path]:
    """Save ``fig`` (a matplotlib ``Figure`` on its own canvas, no pyplot) as ``folder/name.png``
    and ``folder/name.svg`` (folder created), white background; returns ``{format: path}``.

    The SVG keeps lines and text as vectors (a reviewer can reuse or restyle them); raster
    content of the figure (a rendered view) is embedded in it as an image."""
    import matplotlib

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    out = {}
    # SVG text stays text (editable, searchable); a fixed salt and no date keep the SVG the same run to run
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "geargen"}):
        for fmt in FIGURE_FORMATS:
            out[fmt] = write_figure(fig, folder / f"{name}.{fmt}", format=fmt, dpi=dpi, facecolor="white",
                                    metadata={"Date": None} if fmt == "svg" else None,
                                    **({"pil_kwargs": {"compress_level": PNG_COMPRESS_LEVEL}} if fmt == "png" else {}))
    return out


__all__ = ["FIGURE_FORMATS", "write_figure", "save_png", "save_figure"]
