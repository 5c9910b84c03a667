"""Synthetic surveillance scenes with exact ground truth, for testing trackers end to end.

:func:`make_scene` draws, from a seed, people-sized textured blobs that enter from the left or
right edge at staggered times, walk across (so they cross each other) and leave, over a textured
background, with sensor noise and a slow global illumination change. Frames are rendered on
demand (``scene.frame(k)``, ``H x W x 3`` uint8 BGR), so long scenes cost no memory. Ground truth:
``scene.gt_rows()`` (MOTChallenge rows, 1-based frames, boxes clipped to the image) and
``scene.mask(k)`` (an ``H x W`` int32 map of the visible person ids, 0 for background).

:func:`render_y` turns a mask into a plausible background-subtraction output ``y`` (float32 in
[0, 1], near 1 for background, low inside people, with noise and speckle), so that a
track-before-detect filter can be tested without a background model.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional, Tuple

import numpy as np


@dataclass
class Person:
    id: int
    enter: int                 # first frame index (0-based) of the trajectory
    x0: float                  # left edge at `enter`
    y0: float                  # top edge at `enter`
    vx: float                  # pixels per frame
    vy: float
    w: int
    h: int
    colour: np.ndarray         # BGR base colour, float
    texture: np.ndarray        # h x w float texture in [-1, 1]

    def box(self, k: int) -> Tuple[int, int, int, int]:
        """(x, y, w, h) at frame k, on the pixel grid (the sprite is drawn exactly there)."""
        t = k - self.enter
        return (int(round(self.x0 + self.vx * t)), int(round(self.y0 + self.vy * t)),
                self.w, self.h)


@dataclass
class SyntheticScene:
    width: int
    height: int
    n_frames: int
    people: List[Person]
    seed: int
    noise_std: float = 3.0
    illumination_amplitude: float = 0.08
    min_visible: float = 0.25
    _background: np.ndarray = field(default=None, repr=False)

    def __len__(self) -> int:
        return self.n_frames

    def _shape_mask(self, p: Person) -> np.ndarray:
        # A superellipse |u|^4 + |v|^4 <= 1 filling the box: roughly person-shaped, and its
        # bounding box is exactly the person's box.
        u = (np.arange(p.w) + 0.5) / p.w * 2 - 1
        v = (np.arange(p.h) + 0.5) / p.h * 2 - 1
        return (u[None, :] ** 4 + v[:, None] ** 4) <= 1.0

    def _visible(self, k: int):
        """(person, box (x, y, w, h), clipped corners (x0, y0, x1, y1)) of the people present at
        frame k with some part inside the image."""
        for p in self.people:
            if k < p.enter:
                continue
            x, y, w, h = p.box(k)
            x0, y0 = max(x, 0), max(y, 0)
            x1, y1 = min(x + w, self.width), min(y + h, self.height)
            if x1 > x0 and y1 > y0:
                yield p, (x, y, w, h), (x0, y0, x1, y1)

    def _placements(self, k: int):
        """(person, visible slice of box, slice of sprite) for the people present at frame k,
        far (small bottom y) first so nearer people are drawn over them."""
        out = []
        for p, (xi, yi, w, h), (x0, y0, x1, y1) in self._visible(k):
            out.append((yi + h, p, (slice(y0, y1), slice(x0, x1)),
                        (slice(y0 - yi, y1 - yi), slice(x0 - xi, x1 - xi))))
        out.sort(key=lambda item: item[0])
        return [item[1:] for item in out]

    def mask(self, k: int) -> np.ndarray:
        """H x W int32: the id of the person visible at each pixel, 0 for background."""
        m = np.zeros((self.height, self.width), np.int32)
        for p, dst, src in self._placements(k):
            shape = self._shape_mask(p)[src]
            m[dst][shape] = p.id
        return m

    def frame(self, k: int) -> np.ndarray:
        """H x W x 3 uint8 BGR frame k (0-based)."""
        if not 0 <= k < self.n_frames:
            raise IndexError(f"frame index {k} out of range [0, {self.n_frames})")
        img = self._background.copy()
        for p, dst, src in self._placements(k):
            shape = self._shape_mask(p)[src]
            sprite = p.colour[None, None, :] * (1.0 + 0.35 * p.texture[src][..., None])
            img[dst][shape] = sprite[shape]
        gain = 1.0 + self.illumination_amplitude * np.sin(2 * np.pi * k / max(self.n_frames, 1))
        rng = np.random.default_rng([self.seed, k])
        img = img * gain + rng.normal(0.0, self.noise_std, img.shape)
        return np.clip(img, 0, 255).astype(np.uint8)

    def boxes(self, k: int) -> np.ndarray:
        """Ground-truth rows (id, x, y, w, h) of frame k: boxes clipped to the image, for the
        people with at least `min_visible` of their box inside the image."""
        rows = []
        for p, (_, _, w, h), (x0, y0, x1, y1) in self._visible(k):
            if (x1 - x0) * (y1 - y0) >= self.min_visible * w * h:
                rows.append((p.id, x0, y0, x1 - x0, y1 - y0))  # clipped to the image
        return np.asarray(rows, np.float64).reshape(-1, 5)

    def gt_rows(self) -> np.ndarray:
        """MOTChallenge ground truth of the whole scene: (frame, id, x, y, w, h, 1, -1, -1, -1)."""
        rows = []
        for k in range(self.n_frames):
            for r in self.boxes(k):
                rows.append((k + 1, *r, 1, -1, -1, -1))
        return np.asarray(rows, np.float64).reshape(-1, 10)

    def count(self, k: int) -> int:
        """Number of ground-truth people in frame k."""
        return len(self.boxes(k))


def _smooth_noise(rng: np.random.Generator, height: int, width: int, cell: int) -> np.ndarray:
    """Value noise in [-1, 1]: a coarse random grid, bilinearly upsampled."""
    gh, gw = height // cell + 2, width // cell + 2
    grid = rng.uniform(-1, 1, (gh, gw))
    yy = np.arange(height) / cell
    xx = np.arange(width) / cell
    y0, x0 = yy.astype(int), xx.astype(int)
    fy, fx = (yy - y0)[:, None], (xx - x0)[None, :]
    g = grid
    return ((1 - fy) * ((1 - fx) * g[y0][:, x0] + fx * g[y0][:, x0 + 1]) +
            fy * ((1 - fx) * g[y0 + 1][:, x0] + fx * g[y0 + 1][:, x0 + 1]))


def make_scene(width: int = 320, height: int = 240, n_frames: int = 150, n_people: int = 5,
               seed: int = 0, size: Tuple[Tuple[int, int], Tuple[int, int]] = ((14, 24), (36, 60)),
               speed: Tuple[float, float] = (1.0, 2.5), noise_std: float = 3.0,
               illumination_amplitude: float = 0.08, min_visible: float = 0.25,
               enter_within: Optional[int] = None) -> SyntheticScene:
    """A seeded scene of `n_people` people crossing a `width` x `height` image.

    `size` gives the ranges of box widths and heights, `speed` the range of horizontal speeds
    (px/frame). People enter from a random side at times spread over the first
    `enter_within` frames (default: the first 60% of the scene), at a random height, walking
    with a small vertical drift; they leave when they have crossed the image.
    """
    if width < 16 or height < 16:
        raise ValueError(f"width and height must be >= 16, got {width} x {height}")
    if n_frames < 1 or n_people < 0:
        raise ValueError(f"n_frames must be >= 1 and n_people >= 0, got {n_frames}, {n_people}")
    rng = np.random.default_rng(seed)
    bg = 110 + 50 * _smooth_noise(rng, height, width, 24)[..., None] + \
        15 * _smooth_noise(rng, height, width, 5)[..., None]
    tint = rng.uniform(0.8, 1.2, 3)
    background = np.clip(bg * tint[None, None, :], 0, 255)
    enter_within = int(0.6 * n_frames) if enter_within is None else enter_within
    starts = np.sort(rng.integers(0, max(enter_within, 1), n_people))
    # One lane (height of the feet) per person, spread over the image and shuffled, so people
    # cross and partly occlude each other without walking on top of each other all the way.
    lanes = rng.permutation(np.linspace(0.2 * height, 0.95 * height, max(n_people, 1)))
    people = []
    for i, start in enumerate(starts):
        w = int(rng.integers(size[0][0], size[0][1] + 1))
        h = int(rng.integers(size[1][0], size[1][1] + 1))
        v = rng.uniform(*speed)
        from_left = bool(rng.integers(0, 2))
        x0 = -w + 1.0 if from_left else width - 1.0
        y0 = float(np.clip(lanes[i] - h + rng.uniform(-0.02, 0.02) * height, 0, height - h))
        vy = rng.uniform(-0.15, 0.15)
        # Keep the walk inside the image vertically over the crossing.
        duration = (width + w) / v
        vy = float(np.clip(vy, (0.02 * height - y0) / duration, (0.98 * height - h - y0) / duration))
        colour = rng.uniform(20, 235, 3)
        # Distinct from the background on average: push away from the mean background level.
        colour = np.where(np.abs(colour - 110) < 40, colour + np.sign(colour - 110 + 1e-9) * 60, colour)
        texture = _smooth_noise(rng, h, w, 6)
        people.append(Person(i + 1, int(start), x0, y0, v if from_left else -v, vy, w, h,
                             np.clip(colour, 0, 255), texture))
    return SyntheticScene(width, height, n_frames, people, seed, noise_std,
                          illumination_amplitude, min_visible, background)


def render_y(mask: np.ndarray, rng: np.random.Generator, background: float = 0.95,
             foreground: float = 0.15, noise_std: float = 0.05,
             speckle: float = 0.002) -> np.ndarray:
    """A plausible background-subtraction output for a mask (nonzero = person).

    Background pixels are `background` and person pixels `foreground`, plus Gaussian noise of
    `noise_std`; a fraction `speckle` of the background pixels are false-foreground specks
    (value uniform in [0, 0.3]). Returns H x W float32 clipped to [0, 1].
    """
    mask = np.asarray(mask)
    y = np.where(mask != 0, np.float32(foreground), np.float32(background))
    y += np.float32(noise_std) * rng.standard_normal(y.shape, dtype=np.float32)
    if speckle > 0:
        specks = (rng.random(y.shape) < speckle) & (mask == 0)
        y[specks] = rng.uniform(0.0, 0.3, int(specks.sum()))
    return np.clip(y, 0.0, 1.0)
