#!/usr/bin/env python3
"""Independent SSIM oracle for tests/metrics: scikit-image's structural_similarity.

Usage: skimage_ssim.py REFERENCE.raw TEST.raw WIDTH HEIGHT CHANNELS EXPOSURE [X,Y ...]

Each .raw file holds WIDTH*HEIGHT*CHANNELS little-endian float32 values, rows top to bottom,
channels interleaved (ldm::Image's layout). Both images are converted to float64, multiplied
by EXPOSURE and clipped to [0, 1], then compared with the settings that reproduce Wang et al.
2004 (Gaussian window, sigma 1.5, population covariances, data range 1).

Prints one line "mssim VALUE", one line "channel C VALUE" per channel, and one line
"pixel X Y VALUE" per requested pixel (the SSIM map averaged over channels). Values are
printed with repr(), which round-trips doubles exactly. Exits with status 2 and a message
starting "MISSING_PYTHON_MODULES" if numpy, scipy or scikit-image cannot be imported.
"""
import sys

try:
    import numpy as np
    import scipy  # noqa: F401  (skimage's SSIM filters with scipy.ndimage)
    from skimage.metrics import structural_similarity
except ImportError as error:
    print(f"MISSING_PYTHON_MODULES: {error}. Install the Debian packages python3-numpy, "
          "python3-scipy and python3-skimage (scripts/setup.sh does).")
    sys.exit(2)


def load(path, width, height, channels, exposure):
    values = np.fromfile(path, dtype="<f4")
    expected = width * height * channels
    if values.size != expected:
        sys.exit(f"{path}: {values.size} float32 values, expected {expected}")
    image = values.astype(np.float64).reshape(height, width, channels)
    image = np.clip(image * exposure, 0.0, 1.0)
    return image[:, :, 0] if channels == 1 else image


def main(argv):
    if len(argv) < 7:
        sys.exit(__doc__)
    reference_path, test_path = argv[1], argv[2]
    width, height, channels = int(argv[3]), int(argv[4]), int(argv[5])
    exposure = float(argv[6])
    reference = load(reference_path, width, height, channels, exposure)
    test = load(test_path, width, height, channels, exposure)

    common = dict(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                  data_range=1.0, full=True)
    if channels == 1:
        mssim, ssim_map = structural_similarity(reference, test, **common)
        per_channel = [mssim]
        mean_map = ssim_map
    else:
        mssim, ssim_map = structural_similarity(reference, test, channel_axis=-1, **common)
        per_channel = [
            structural_similarity(reference[:, :, c], test[:, :, c], **common)[0]
            for c in range(channels)
        ]
        mean_map = ssim_map.mean(axis=-1)

    print(f"mssim {float(mssim)!r}")
    for c, value in enumerate(per_channel):
        print(f"channel {c} {float(value)!r}")
    for pair in argv[7:]:
        x, y = (int(v) for v in pair.split(","))
        print(f"pixel {x} {y} {float(mean_map[y, x])!r}")


if __name__ == "__main__":
    main(sys.argv)
