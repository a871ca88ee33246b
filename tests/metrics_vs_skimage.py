#!/usr/bin/env python3
"""PSNR, SSIM and Pearson of image pairs with scikit-image / SciPy, for test_metrics_reference.

Usage: metrics_vs_skimage.py DIR. DIR/cases.txt has one line per case,
"NAME WIDTH HEIGHT CHANNELS", and for each case the little-endian float32 files (rows first,
channels interleaved) NAME.test.f32 / NAME.ref.f32 (linear values) and NAME.test-display.f32 /
NAME.ref-display.f32 (the values SSIM and Pearson see: display values in [0, 1] for RGB,
the linear values for 1-channel layers). Prints "NAME METRIC VALUE" lines.

The calls below are the correspondence documented in docs/reference.md ("Checked against
reference code"); test_metrics_reference.cpp compares the printed values with voxgi's.
"""
import sys
from pathlib import Path

import numpy as np
import scipy.stats
from skimage.metrics import peak_signal_noise_ratio, structural_similarity

# voxgi's SSIM window: 11x11 Gaussian, sigma 1.5 (skimage's truncate 3.5 gives radius 5).
RADIUS = 5


def load(path, width, height, channels):
    # float32 -> float64 is exact; skimage then filters in double precision, as voxgi does.
    a = np.fromfile(path, dtype="<f4").astype(np.float64)
    return a.reshape(height, width, channels) if channels > 1 else a.reshape(height, width)


def ssim(test, ref, data_range, channels):
    # voxgi clamps windows at the edges and averages every pixel; skimage filters with mirrored
    # edges and averages only pixels RADIUS or more from the border. Padding both images by
    # RADIUS repeated edge pixels makes skimage's cropped mean exactly voxgi's full mean.
    pad = ((RADIUS, RADIUS), (RADIUS, RADIUS)) + (((0, 0),) if channels > 1 else ())
    return structural_similarity(np.pad(test, pad, mode="edge"), np.pad(ref, pad, mode="edge"),
                                 gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                 K1=0.01, K2=0.03, data_range=data_range,
                                 channel_axis=2 if channels > 1 else None)


def main():
    root = Path(sys.argv[1])
    for line in (root / "cases.txt").read_text().splitlines():
        name, width, height, channels = line.split()
        width, height, channels = int(width), int(height), int(channels)
        test = load(root / f"{name}.test.f32", width, height, channels)
        ref = load(root / f"{name}.ref.f32", width, height, channels)
        test_d = load(root / f"{name}.test-display.f32", width, height, channels)
        ref_d = load(root / f"{name}.ref-display.f32", width, height, channels)

        # PSNR on linear values, peak = the reference's largest value (1 when it is <= 0).
        peak = ref.max() if ref.max() > 0 else 1.0
        psnr = peak_signal_noise_ratio(ref, test, data_range=peak)
        # SSIM: L = 1 on display values; the reference's range on 1-channel linear values.
        span = ref.max() - ref.min()
        ssim_value = ssim(test_d, ref_d, 1.0 if channels == 3 else (span if span > 0 else 1.0), channels)
        # Pearson: pooled over all channels, on 8-bit display units for RGB (a scale, so the
        # correlation is the same; kept to mirror voxgi's inputs). skimage 0.19 has no Pearson
        # (measure.pearson_corr_coeff came in 0.20), SciPy's is the reference here.
        scale = 255.0 if channels == 3 else 1.0
        pearson = scipy.stats.pearsonr((scale * test_d).ravel(), (scale * ref_d).ravel())[0]

        for metric, value in (("psnr", psnr), ("ssim", ssim_value), ("pearson", pearson)):
            print(f"{name} {metric} {value:.12g}")


if __name__ == "__main__":
    main()
