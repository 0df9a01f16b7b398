#!/usr/bin/env python3
"""Prints the indirect-lighting tables of docs/measured/indirect.md from their committed
records (docs/measured/indirect/: headline.csv for the first table, <scene>-N, -s, -R and
-Rl.csv for the sweeps of one axis).

Usage: scripts/indirect_tables.py headline|N|s|R|Rl [RECORDS_DIR]
"""
import os
import sys

import ldmrecords
from ldmrecords import value

HEADER = ("build ms | light G-buffer ms | tracing ms | splatting ms | direct ms | frame ms | M_lists MiB "
          "| M_photons MiB | photons stored | MSE single | ×noise | MSSIM single | MSE multi | MSSIM multi")
AXES = {"N": ("n_views", "N"), "s": ("splat_scale", "s = a"), "R": ("r_ldm", "R_LDM"), "Rl": ("r_light", "R_light")}


def cells(r):
    """The measured columns every table shows, in HEADER's order."""
    def ms(subpass):
        t = value(r, subpass + "_ms_median")
        return "%.1f" % (0 if t != t else t)  # a sub-pass a record lacks shows 0.0, as before
    return [ms("build"), ms("light_gbuffer"), ms("photon_tracing"), ms("splatting"), ms("direct"), ms("frame"),
            "%.2f" % (value(r, "m_lists_allocated") / 2**20), "%.2f" % (value(r, "m_photons_used") / 2**20),
            "{:,}".format(int(value(r, "photons_stored"))), "%.2e" % value(r, "mse"),
            "%.1f" % value(r, "mse_over_noise"), "%.3f" % value(r, "mssim"), "%.2e" % value(r, "multi_mse"),
            "%.3f" % value(r, "multi_mssim")]


def main(mode, folder):
    if mode == "headline":
        print("| scene | structure | status | " + HEADER + " |")
        print("|" + " --- |" * 3 + " ---: |" * 14)
        for r in ldmrecords.read(os.path.join(folder, "headline.csv")):
            print(f"| {r['scene']} | {r['structure']} | {r['status']} | " + " | ".join(cells(r)) + " |")
        return
    column, label = AXES[mode]
    print(f"| scene | {label} | " + HEADER + " |")
    print("|" + " --- |" * 2 + " ---: |" * 14)
    for scene in ("cornell", "atrium"):
        for r in ldmrecords.read(os.path.join(folder, f"{scene}-{mode}.csv")):
            print(f"| {scene} | {value(r, column):g} | " + " | ".join(cells(r)) + " |")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3) or sys.argv[1] not in ("headline", *AXES):
        sys.exit(__doc__.strip().split("\n\n")[1])
    main(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else
         os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "measured", "indirect"))
