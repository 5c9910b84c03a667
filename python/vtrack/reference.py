"""Slow, literal NumPy transcriptions of the papers' equations, in float64.

They are the independent yardstick the tests compare the C++ implementations with, and the
"NumPy" row of the benchmarks. Not meant for production use.
"""

from __future__ import annotations

from typing import List, Sequence, Tuple

import numpy as np

__all__ = ["rgi_float64", "KdeBackgroundReference"]


def rgi_float64(frame: np.ndarray) -> np.ndarray:
    """rgI of an H x W x 3 uint8 BGR frame (mb-tbd paper eqs. 6-8), float64 H x W x 3.

    r = R / S, g = G / S, I = S / 765 with S = R + G + B; black pixels get r = g = 1/3
    (the conventions of vtrack.image.bgr_to_rgi).
    """
    bgr = frame.astype(np.float64)
    s = bgr.sum(axis=2)
    safe = np.where(s > 0, s, 1.0)
    r = np.where(s > 0, bgr[..., 2] / safe, 1.0 / 3.0)
    g = np.where(s > 0, bgr[..., 1] / safe, 1.0 / 3.0)
    return np.stack([r, g, s / 765.0], axis=2)


class KdeBackgroundReference:
    """Eq. (10) of the mb-tbd paper, written out directly.

    Frame k (counted from 0) is stored as a sample when k % period == 0; the stack keeps the
    newest ``n_samples``; y(k) is the mean over the stack of
    prod_d exp(-(d(k) - d_sample)^2 / (2 sigma_d^2)), d in (r, g, I). No closing.
    """

    def __init__(self, n_samples: int, period: int, bandwidth: Sequence[float]):
        self.n_samples = n_samples
        self.period = period
        self.sigma = np.asarray(bandwidth, dtype=np.float64)
        self.samples: List[Tuple[int, np.ndarray]] = []  # (frame index, rgI), oldest first
        self.frame_index = 0

    @property
    def sample_frames(self) -> List[int]:
        return [k for k, _ in self.samples]

    def apply(self, frame: np.ndarray) -> np.ndarray:
        rgi = rgi_float64(frame)
        if self.frame_index % self.period == 0:
            self.samples.append((self.frame_index, rgi))
            if len(self.samples) > self.n_samples:
                self.samples.pop(0)
        y = np.zeros(rgi.shape[:2])
        for _, sample in self.samples:
            exponent = ((rgi - sample) ** 2 / (2.0 * self.sigma**2)).sum(axis=2)
            y += np.exp(-exponent)
        self.frame_index += 1
        return y / len(self.samples)
