"""A synthetic partial-occlusion scene with exact ground truth of every part.

:func:`make_occlusion_scene` draws, from a seed, one textured figure made of horizontal parts of
distinct colors that moves across a textured background and passes behind a static occluder
that hides one side of it (the lower or the upper half of a walking person; the lower or upper
part of a face) for a stretch of frames -- the situation of the part-based particle filter's
sequences (part-based-graphical-model-pf.txt section 5). Two layouts:

* ``"person"``: 2 parts, upper and lower halves of the figure's box (the paper's sequences 1-2);
* ``"face"``: 3 parts, top, middle and bottom thirds of a face-sized box (its sequence 3).

Ground truth is exact because the figure is drawn on the pixel grid: ``scene.boxes[k]`` is the
whole figure's box ``(x, y, w, h)`` at frame ``k`` (0-based) and ``scene.part_boxes[k, p]`` the
box of part ``p``; the parts tile the figure's box row-wise. ``scene.occluded_fraction[k, p]`` is
the fraction of part ``p``'s box that the occluder covers (the occluder is opaque and drawn over
everything inside its rectangle, so this is also the fraction of the box's pixels that show the
occluder: ``scene.mask(k)`` tells each pixel's owner). The figure keeps its vertical centre, so an
occluder edge on that centre line hides exactly half of the figure at every scale.

The figure's shape is a superellipse filling its box (the box is its exact bounding box), with
background pixels in the box corners, as a person's box has. Frames are rendered on demand
(``scene.frame(k)``, ``H x W x 3`` uint8 BGR); optional camera noise (Gaussian, per pixel,
seeded per frame) and a linear scale change of the figure over the scene.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional, Tuple

import colorsys

import numpy as np

from .synthetic import _smooth_noise

LAYOUTS = {
    # name: (part names, default size (w, h), default speed (px/frame))
    "person": (("upper", "lower"), (24, 64), 2.0),
    "face": (("top", "middle", "bottom"), (48, 60), 1.5),
}


@dataclass
class OcclusionScene:
    """A rendered-on-demand occlusion scene; see the module docstring."""

    width: int
    height: int
    layout: str
    part_names: Tuple[str, ...]
    boxes: np.ndarray              # (n_frames, 4) int64: x, y, w, h of the whole figure
    part_boxes: np.ndarray         # (n_frames, n_parts, 4) int64
    occluder: Tuple[int, int, int, int]   # x, y, w, h (static)
    occluded_fraction: np.ndarray  # (n_frames, n_parts) float64, fraction of each part box hidden
    seed: int
    noise_std: float
    _background: np.ndarray = field(repr=False)
    _occluder_image: np.ndarray = field(repr=False)
    _part_colors: np.ndarray = field(repr=False)    # (n_parts, 3) BGR
    _texture: np.ndarray = field(repr=False)         # value-noise grid over the unit square

    def __len__(self) -> int:
        return len(self.boxes)

    @property
    def n_parts(self) -> int:
        return len(self.part_names)

    def _figure(self, k: int):
        """(shape mask h x w, part index h x w, sprite h x w x 3) of the figure at frame k."""
        x, y, w, h = (int(v) for v in self.boxes[k])
        u = (np.arange(w) + 0.5) / w * 2 - 1
        v = (np.arange(h) + 0.5) / h * 2 - 1
        shape = (u[None, :] ** 4 + v[:, None] ** 4) <= 1.0
        part_of_row = np.zeros(h, np.int64)
        for p in range(self.n_parts):
            top = int(self.part_boxes[k, p, 1]) - y
            part_of_row[top:top + int(self.part_boxes[k, p, 3])] = p
        part = np.broadcast_to(part_of_row[:, None], (h, w))
        # The texture lives on the figure's own unit square, so it scales with the figure.
        texture = _sample_grid(self._texture, w, h)
        sprite = self._part_colors[part] * (1.0 + 0.3 * texture[..., None])
        return shape, part, sprite

    def mask(self, k: int) -> np.ndarray:
        """H x W int32 owner of each pixel at frame k: p + 1 for part p of the figure, -1 for the
        occluder, 0 for the background."""
        m = np.zeros((self.height, self.width), np.int32)
        x, y, w, h = (int(v) for v in self.boxes[k])
        shape, part, _ = self._figure(k)
        m[y:y + h, x:x + w][shape] = part[shape] + 1
        ox, oy, ow, oh = self.occluder
        m[oy:oy + oh, ox:ox + ow] = -1
        return m

    def frame(self, k: int) -> np.ndarray:
        """H x W x 3 uint8 BGR frame k (0-based)."""
        if not 0 <= k < len(self):
            raise IndexError(f"frame index {k} out of range [0, {len(self)})")
        img = self._background.copy()
        x, y, w, h = (int(v) for v in self.boxes[k])
        shape, _, sprite = self._figure(k)
        img[y:y + h, x:x + w][shape] = sprite[shape]
        ox, oy, ow, oh = self.occluder
        img[oy:oy + oh, ox:ox + ow] = self._occluder_image
        if self.noise_std > 0:
            img = img + np.random.default_rng([self.seed, k]).normal(0.0, self.noise_std, img.shape)
        return np.clip(img, 0, 255).astype(np.uint8)

    def occluded_frames(self, part: int, threshold: float = 0.5) -> np.ndarray:
        """0-based frame indices at which at least `threshold` of part `part`'s box is hidden."""
        return np.flatnonzero(self.occluded_fraction[:, part] >= threshold)


def _rect_overlap(a, b) -> int:
    """Pixel area of the intersection of two (x, y, w, h) rectangles."""
    w = min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])
    h = min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
    return max(w, 0) * max(h, 0)


def _hsv_color(hue: float, saturation: float, value: float) -> np.ndarray:
    """BGR float color (0-255) of a hue in degrees, saturation and value in [0, 1]."""
    r, g, b = colorsys.hsv_to_rgb(hue / 360.0, saturation, value)
    return 255.0 * np.array([b, g, r])


def _sample_grid(grid: np.ndarray, width: int, height: int) -> np.ndarray:
    """Bilinear samples of a value grid spanning the unit square, at the pixel centres of a
    height x width image."""
    gy = (np.arange(height) + 0.5) / height * (grid.shape[0] - 1)
    gx = (np.arange(width) + 0.5) / width * (grid.shape[1] - 1)
    y0 = np.minimum(gy.astype(int), grid.shape[0] - 2)
    x0 = np.minimum(gx.astype(int), grid.shape[1] - 2)
    fy, fx = (gy - y0)[:, None], (gx - x0)[None, :]
    return ((1 - fy) * ((1 - fx) * grid[y0][:, x0] + fx * grid[y0][:, x0 + 1]) +
            fy * ((1 - fx) * grid[y0 + 1][:, x0] + fx * grid[y0 + 1][:, x0 + 1]))


def make_occlusion_scene(layout: str = "person", *, width: int = 320, height: int = 240,
                         n_frames: Optional[int] = None, seed: int = 0, occlude: str = "lower",
                         size: Optional[Tuple[int, int]] = None, speed: Optional[float] = None,
                         hidden_frames: int = 20, scale_change: float = 0.0,
                         noise_std: float = 0.0) -> OcclusionScene:
    """A seeded occlusion scene (see the module docstring).

    layout: ``"person"`` (2 parts) or ``"face"`` (3 parts). occlude: ``"lower"`` hides the lower
    half of the figure (the occluder reaches from the figure's centre line to the image bottom),
    ``"upper"`` the upper half (from the image top to the centre line). size: the figure's (w, h)
    at frame 0 (layout default); speed: its horizontal speed in px/frame (left to right).
    hidden_frames: frames during which the occluder covers the occluded half's whole width (the
    occluder is ``w + speed * hidden_frames`` wide, centred in the image); before and after, the
    figure slides in and out over ``w / speed`` frames. n_frames: default, the figure walks from
    10 px off the left border to 10 px before the right one. scale_change: the figure's size is
    multiplied by ``1 + scale_change * k / (n_frames - 1)`` at frame k, about its centre.
    noise_std: camera noise (grey levels).
    """
    if layout not in LAYOUTS:
        raise ValueError(f"layout must be one of {sorted(LAYOUTS)}, got {layout!r}")
    if occlude not in ("lower", "upper"):
        raise ValueError(f"occlude must be 'lower' or 'upper', got {occlude!r}")
    names, default_size, default_speed = LAYOUTS[layout]
    w0, h0 = size if size is not None else default_size
    speed = default_speed if speed is None else float(speed)
    if w0 < 4 or h0 < 2 * len(names):
        raise ValueError(f"size must be at least (4, {2 * len(names)}), got {(w0, h0)}")
    if not speed > 0:
        raise ValueError(f"speed must be > 0, got {speed}")
    if hidden_frames < 0:
        raise ValueError(f"hidden_frames must be >= 0, got {hidden_frames}")
    if not -0.5 < scale_change < 1.0:
        raise ValueError(f"scale_change must be in (-0.5, 1), got {scale_change}")
    if noise_std < 0:
        raise ValueError(f"noise_std must be >= 0, got {noise_std}")
    grown_w, grown_h = w0 * (1 + max(scale_change, 0)), h0 * (1 + max(scale_change, 0))
    if grown_w + 20 > width or grown_h + 4 > height:
        raise ValueError(f"a {w0} x {h0} figure (scale_change {scale_change}) does not fit a "
                         f"{width} x {height} image")
    if n_frames is None:
        n_frames = int((width - 20 - grown_w) / speed)
    if n_frames < 2:
        raise ValueError(f"n_frames must be >= 2, got {n_frames}")

    # Geometry, exact on the pixel grid.
    cx0, cy = 10 + w0 / 2, height / 2
    k = np.arange(n_frames)
    scale = 1 + scale_change * k / (n_frames - 1)
    ws = np.maximum(np.rint(w0 * scale), 4).astype(np.int64)
    hs = np.maximum(np.rint(h0 * scale), 2 * len(names)).astype(np.int64)
    xs = np.rint(cx0 + speed * k - ws / 2).astype(np.int64)
    ys = np.rint(cy - hs / 2).astype(np.int64)
    if xs.min() < 0 or (xs + ws).max() > width:
        raise ValueError(f"n_frames {n_frames} at speed {speed} takes the figure out of the image")
    boxes = np.stack([xs, ys, ws, hs], axis=1)
    part_boxes = np.zeros((n_frames, len(names), 4), np.int64)
    for i in range(n_frames):
        # Part p covers rows [round(h p / P), round(h (p + 1) / P)) of the figure's box.
        edges = np.rint(hs[i] * np.arange(len(names) + 1) / len(names)).astype(np.int64)
        for p in range(len(names)):
            part_boxes[i, p] = (xs[i], ys[i] + edges[p], ws[i], edges[p + 1] - edges[p])

    occluder_w = int(round(w0 + speed * hidden_frames))
    ox = int(round(width / 2 - occluder_w / 2))
    centre_row = int(round(cy))
    occluder = (ox, centre_row, occluder_w, height - centre_row) if occlude == "lower" else \
        (ox, 0, occluder_w, centre_row)
    fraction = np.array([[_rect_overlap(b, occluder) / (b[2] * b[3]) for b in part_boxes[i]]
                         for i in range(n_frames)])

    rng = np.random.default_rng(seed)
    # Background: textured, low-saturation greens and greys, so the figure's colors stand out.
    bg = 110 + 45 * _smooth_noise(rng, height, width, 20)[..., None] + \
        20 * _smooth_noise(rng, height, width, 4)[..., None]
    background = np.clip(bg * rng.uniform(0.85, 1.15, 3)[None, None, :], 0, 255)
    # Parts: saturated colors with hues spread around the circle, from a random start; the
    # occluder: a textured brown-grey of its own.
    hue0 = rng.uniform(0, 360)
    n = len(names)
    hues = (hue0 + 360 * np.arange(n) / n + rng.uniform(-15, 15, n)) % 360
    part_colors = np.stack([_hsv_color(h, rng.uniform(0.6, 0.9), rng.uniform(0.55, 0.85))
                             for h in hues])
    occluder_texture = _smooth_noise(rng, occluder[3], occluder[2], 6)
    occluder_image = (_hsv_color(30.0, 0.3, 0.45)[None, None, :]
                      * (1 + 0.25 * occluder_texture[..., None]))
    texture = rng.uniform(-1, 1, (9, 7))  # 9 x 7 cells over the figure: a coarse pattern
    return OcclusionScene(width, height, layout, names, boxes, part_boxes, occluder, fraction, seed,
                          float(noise_std), background, occluder_image, part_colors, texture)
