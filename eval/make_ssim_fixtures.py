#!/usr/bin/python3
"""Writes the SSIM fixtures of tests/eval_metrics_test.cpp: three small image pairs and scikit-image's SSIM.

The C++ SSIM (eval/metrics.cpp, `ssim`) must agree with scikit-image's
    structural_similarity(test, reference, channel_axis=-1, gaussian_weights=True, sigma=1.5,
                          use_sample_covariance=False, data_range=1)
which is Wang et al. 2004's SSIM (11x11 Gaussian window, sigma 1.5, K1 = 0.01, K2 = 0.03) computed per channel
and averaged over the channels. This script makes the images, asks scikit-image, and writes into
tests/data/ssim/:
  base.f32, blurred.f32, shifted.f32, noisy.f32   32 x 24 RGB images, raw little-endian float32, row-major,
                                                  y down, R G B interleaved (9216 bytes each), values in [0, 1]
  ssim.json                                       the size, the pairs and scikit-image's SSIM of each pair
The pairs are (test, reference) = (blurred, base), (shifted, base), (noisy, base). Everything is
deterministic (numpy's legacy MT19937 generator with a fixed seed, hand-written blur and shift), so running
the script again rewrites the same bytes.

Usage: /usr/bin/python3 eval/make_ssim_fixtures.py [output_dir]   (default: tests/data/ssim)
Needs Debian's python3-numpy and python3-skimage.
"""
import json
import os
import sys

import numpy as np
import skimage
from skimage.metrics import structural_similarity

WIDTH, HEIGHT = 32, 24
SEED = 20240523


def make_base(rng):
    """A colour gradient with a ripple and per-pixel noise, clipped to [0, 1]."""
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH].astype(np.float64)
    u, v = x / (WIDTH - 1), y / (HEIGHT - 1)
    ripple = 0.15 * np.sin(2.0 * np.pi * (x / 8.0 + y / 11.0))
    image = np.stack([0.1 + 0.8 * u + ripple, 0.2 + 0.6 * v - ripple, 0.5 + 0.3 * (u - v)], axis=-1)
    image += rng.normal(0.0, 0.08, image.shape)
    return np.clip(image, 0.0, 1.0)


def blur_121(image):
    """A separable [1, 2, 1] / 4 blur, borders clamped (each row, then each column)."""
    def blur_axis(a, axis):
        n = a.shape[axis]
        lo = np.take(a, [0] + list(range(n - 1)), axis=axis)    # the neighbour before, clamped
        hi = np.take(a, list(range(1, n)) + [n - 1], axis=axis)  # the neighbour after, clamped
        return 0.25 * lo + 0.5 * a + 0.25 * hi
    return blur_axis(blur_axis(image, 1), 0)


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "tests", "data", "ssim")
    os.makedirs(out_dir, exist_ok=True)
    rng = np.random.RandomState(SEED)
    base = make_base(rng)
    images = {
        "base": base,
        "blurred": blur_121(base),
        "shifted": np.roll(base, shift=(1, 2), axis=(0, 1)),  # down 1 row, right 2 columns, wrapping
        "noisy": np.clip(base + rng.normal(0.0, 0.05, base.shape), 0.0, 1.0),
    }
    # Store as float32; SSIM is computed from exactly the stored values (widened to float64).
    stored = {}
    for name, image in images.items():
        data = image.astype("<f4")
        with open(os.path.join(out_dir, name + ".f32"), "wb") as f:
            f.write(data.tobytes(order="C"))
        stored[name] = data.astype(np.float64)

    pairs = []
    for test in ("blurred", "shifted", "noisy"):
        value = structural_similarity(stored[test], stored["base"], channel_axis=-1, gaussian_weights=True,
                                      sigma=1.5, use_sample_covariance=False, data_range=1.0)
        pairs.append({"test": test + ".f32", "reference": "base.f32", "ssim": float(value)})

    fixture = {
        "width": WIDTH,
        "height": HEIGHT,
        "format": "raw little-endian float32, row-major, y down, RGB interleaved",
        "skimage": "structural_similarity(test, reference, channel_axis=-1, gaussian_weights=True, sigma=1.5, "
                   "use_sample_covariance=False, data_range=1)",
        "skimage_version": skimage.__version__,
        "pairs": pairs,
    }
    with open(os.path.join(out_dir, "ssim.json"), "w") as f:
        f.write(json.dumps(fixture, indent=2) + "\n")


if __name__ == "__main__":
    main()
