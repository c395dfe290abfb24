"""The rendered view of an assembly as a figure: the rasterised picture, part labels on leader
lines, a scale bar in the design's length unit and an axis triad.

Input is a rasterised view read by attribute (``geargen.cad.render.RenderedView``: image, which
part each pixel shows, the view's extent in mm and its basis); this module only draws it
(matplotlib, Agg canvas, no pyplot), so the report layer never loads the CAD kernel.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from geargen.units import LENGTH_SUFFIXES

MIN_LABEL_PIXELS = 150  # parts showing fewer pixels than this are too small to point at
UNLABELLED_KINDS = ("bearing", "shaft")  # many alike and named in the parts table: labels would crowd the view


def nice_length(limit: float) -> float:
    """The largest 1, 2 or 5 times a power of ten not above ``limit`` (> 0)."""
    power = 10.0 ** math.floor(math.log10(limit))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= limit * (1 + 1e-12))


def part_anchors(view, min_pixels: int = MIN_LABEL_PIXELS) -> list[tuple[str, tuple[float, float]]]:
    """One anchor per part name shown on at least ``min_pixels`` pixels, in view coordinates (mm):
    the visible pixel of that part nearest the centroid of its visible pixels (on the part even
    when the part is a ring)."""
    index = view.part_index.ravel()
    shown = np.flatnonzero(index >= 0)
    part_of = index[shown]
    shown = shown[np.argsort(part_of, kind="stable")]  # pixels grouped by part, one pass over the image
    counts = np.bincount(part_of)  # each part's run in that order: no second sort
    parts = np.flatnonzero(counts)
    counts = counts[parts]
    starts = np.cumsum(counts) - counts
    width = view.part_index.shape[1]
    out = []
    for k, start, count in zip(parts, starts, counts):
        if count < min_pixels:
            continue
        rows, cols = np.divmod(shown[start:start + count], width)
        i = int(np.argmin((rows - rows.mean()) ** 2 + (cols - cols.mean()) ** 2))
        x, y = view.to_view(rows[i:i + 1], cols[i:i + 1])[0]
        out.append((view.names[k], (float(x), float(y))))
    return out


def view_figure(view, length_unit: str = "mm", labels: list[tuple[str, str]] | None = None, dpi: int = 110):
    """The figure of ``view`` (``RenderedView``). ``labels``: ``(part name, text)`` of the parts to
    label (default: every part large enough, by its name); each label sits on a leader line from
    a visible pixel of its part, placed by :func:`geargen.report.labels.place_labels` clear of
    the other labels and, where it can, of the picture. By default every part large enough is
    labelled, except the kinds in :data:`UNLABELLED_KINDS`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from geargen.report.labels import Obstacles, place_labels, text_boxes

    h, w = view.image.shape[:2]
    fig = Figure(figsize=(w / dpi, h / dpi + (0.3 if view.title else 0.0)), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, h / (h + (0.3 * dpi if view.title else 0.0))))
    left, right, bottom, top = view.extent
    # the picture as the bytes matplotlib makes of a float RGB image at each draw (PNG, then SVG), made
    # once: 8-bit RGBA, alpha 255, each channel truncated as matplotlib truncates (value * 255); it
    # resamples 8-bit images as float32 k / 255, which gives back the same k (every k of 0..255)
    rgba = np.empty((h, w, 4), np.uint8)
    rgba[..., :3] = view.image * 255
    rgba[..., 3] = 255
    ax.add_image(_picture(ax, rgba, view.extent))
    ax.set_xlim(left, right)
    ax.set_ylim(bottom, top)
    ax.set_aspect("equal")
    ax.axis("off")
    if view.title:
        fig.suptitle(view.title, fontsize=11)
    width_mm = right - left
    scale = LENGTH_SUFFIXES[length_unit]
    # scale bar: a round length near a fifth of the picture, bottom left
    bar = nice_length(0.2 * width_mm / scale)
    x0, y0 = left + 0.03 * width_mm, bottom + 0.04 * (top - bottom)
    ax.plot([x0, x0 + bar * scale], [y0, y0], color="k", lw=2.5, solid_capstyle="butt")
    ax.text(x0 + bar * scale / 2, y0 + 0.012 * width_mm, f"{bar:g} {length_unit}", ha="center", va="bottom",
            fontsize=8)
    # axis triad: the model's x, y, z seen along the view, bottom right
    origin = np.array([right - 0.07 * width_mm, bottom + 0.09 * (top - bottom)])
    arm = 0.045 * width_mm
    for axis, colour, name in ((0, "tab:red", "x"), (1, "tab:green", "y"), (2, "tab:blue", "z")):
        d = view.basis[:2, axis] * arm  # the model axis' components along the view's right and up
        ax.annotate("", origin + d, origin, arrowprops=dict(arrowstyle="-|>", color=colour, lw=1.2, shrinkA=0,
                                                             shrinkB=0))
        ax.text(*(origin + 1.25 * d), name, color=colour, fontsize=8, ha="center", va="center")
    ax.apply_aspect()  # the axes' final box: text extents and data-to-pixel transforms are exact from here
    taken = [box for _, box in text_boxes(fig)]
    anchors = dict(part_anchors(view))
    kinds = dict(zip(view.names, view.kinds))
    wanted = labels if labels is not None else [(n, n) for n in anchors if kinds.get(n) not in UNLABELLED_KINDS]
    todo = [(text, anchors[name], dict(fontsize=7, color="0.1",
                                       bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="0.6", lw=0.4, alpha=0.85)))
            for name, text in wanted if name in anchors]
    covered = view.part_index >= 0
    obstacles = Obstacles(boxes=_picture_boxes(view, covered))
    place_labels(ax, todo, obstacles, placed=taken, leader_from_ring=1)
    return fig


def _picture(ax, rgba: np.ndarray, extent):
    """The picture ``rgba`` (8-bit, opaque) as the image ``ax.imshow(rgba, extent=extent,
    interpolation="nearest", origin="upper")`` makes, drawn without resampling where each of its
    pixels falls on one pixel of the output (:func:`_one_pixel_image`)."""
    image = _one_pixel_image()(ax, interpolation="nearest", origin="upper", extent=extent)
    image.set_data(rgba)
    image.set_clip_path(ax.patch)
    return image


@functools.cache
def _one_pixel_image():
    """An ``AxesImage`` drawn as its rows bottom to top where its box lies on whole output pixels,
    one image pixel on one output pixel (the view figure is sized so, for the PNG and the SVG alike).

    matplotlib resamples an image at each draw (to float, resampled, back to 8 bits: ~15-20 ms for
    the view, once for the PNG and once for the SVG); nearest-neighbour resampling onto the same
    pixels gives the image's rows bottom to top, bit for bit, for an opaque 8-bit image (no alpha
    to premultiply; each k / 255 goes back to k). The output's pixels are rounded as matplotlib's
    ``_ImageBase._make_image`` rounds them, so the image is placed at the same (x, y), signed zeros
    included. Any other box (another dpi, a moved or clipped picture, a translucent one) is
    resampled by matplotlib as before."""
    from matplotlib.image import AxesImage
    from matplotlib.transforms import Affine2D, Bbox, TransformedBbox

    class OnePixelImage(AxesImage):
        def make_image(self, renderer, magnification=1.0, unsampled=False):
            if not unsampled:
                same = self._rows_flipped(magnification)
                if same is not None:
                    return same
            return super().make_image(renderer, magnification, unsampled)

        def _rows_flipped(self, magnification: float):
            picture = self.get_array()
            if (self.get_interpolation() != "nearest" or self.origin != "upper" or picture.dtype != np.uint8
                    or picture.ndim != 3 or picture.shape[2] != 4 or self.get_alpha() is not None
                    or not (picture[..., 3] == 255).all()):
                return None
            h, w = picture.shape[:2]
            x1, x2, y1, y2 = self.get_extent()
            box = TransformedBbox(Bbox([[x1, y1], [x2, y2]]), self.get_transform())
            clip = ((self.get_clip_box() or self.axes.bbox) if self.get_clip_on()
                    else self.get_figure(root=True).bbox)
            clipped = Bbox.intersection(box, clip)
            if clipped is None:
                return None
            e = clipped.extents * magnification
            # the output's pixels as _make_image rounds them ("round half up / half down")
            pixels = np.array([np.floor(e[0] + 0.5), np.ceil(e[1] - 0.5 - 1e-8),
                               np.floor(e[2] + 0.5 + 1e-8), np.ceil(e[3] - 0.5)])
            # the whole picture (not clipped) one pixel to a pixel, its edges on the pixels' edges
            if (pixels[2] - pixels[0] != w or pixels[3] - pixels[1] != h
                    or np.any(np.abs(box.extents * magnification - pixels) > 1e-6)):
                return None
            flip = Affine2D().translate(0, -h).scale(1, -1)  # image rows, top first, onto output pixels
            return np.ascontiguousarray(picture[::-1]), pixels[0] / magnification, pixels[1] / magnification, flip

    return OnePixelImage


def _picture_boxes(view, covered: np.ndarray, cells: int = 24) -> list[tuple[float, float, float, float]]:
    """The picture's footprint as boxes (mm) of a coarse grid: cells mostly covered by parts."""
    h, w = covered.shape
    s = view.mm_per_pixel
    left, top = view.extent[0], view.extent[3]
    step = max(h, w) // cells or 1
    out = []
    for r in range(0, h, step):
        for c in range(0, w, step):
            if covered[r:r + step, c:c + step].mean() > 0.5:
                out.append((left + c * s, top - (r + step) * s, left + (c + step) * s, top - r * s))
    return out


__all__ = ["view_figure", "part_anchors", "nice_length"]
