#!/usr/bin/env python3
"""Prints the energy tables of docs/measured/indirect.md (issue 20) from the records.csv of
docs/measured/closed-sphere-energy/ or docs/measured/spot-bounce-floor/: per configuration,
the image mean over the single-bounce reference's (mean_ratio, +- 2 standard errors from the
reference's noise), the error over the reference's noise, the share of the MSE that is the
mean offset, and the flux audit: where the emitted flux went (fractions of flux_emitted) and
what of the stored flux the splats deposit on the surfaces the image shows. With
--sphere-radius R (closed-sphere): the ideal sphere's flux on the visible surfaces,
rho Phi1 * visible_area / (4 pi R^2) (its irradiance is uniform), and the stored and
deposited flux over it.

usage: scripts/indirect_energy_table.py RECORDS_CSV [--sphere-radius R] [KEY=VALUE ...]
  KEY=VALUE: the base point's columns where they differ from N=32, R_LDM=64, R_light=64, s=4"""
import math
import sys
import ldmrecords
from ldmrecords import value

BASE = {"n_views": "32", "r_ldm": "64", "r_light": "64", "splat_scale": "4"}


def varied(r, base):
    out = [f"{k}={r[k]}" for k in base if k in r and r[k] != base[k]]
    return ", ".join(out) or "base"


def main(path, base, radius):
    rows = ldmrecords.with_status(ldmrecords.read(path), "ok", "lossy")
    print("| configuration | emission | mean ratio ± 2 SE | MSE / noise | bias² / MSE | emitted / ρΦ₁ "
          "| stored | escaped | outside | hidden | backside | deposited / stored | unseen | clipped by a | outside quad | area gain |"
          + (" stored / ideal | deposited / ideal |" if radius else ""))
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
          + (" ---: | ---: |" if radius else ""))
    for r in rows:
        e = value(r, "flux_emitted")
        s = value(r, "flux_stored")
        cells = [varied(r, base), r.get("emission", ""),
                 f"{value(r, 'mean_ratio'):.4f} ± {2 * value(r, 'mean_ratio_se'):.4f}",
                 f"{value(r, 'mse_over_noise'):.1f}", f"{value(r, 'bias_share'):.2f}",
                 f"{e / value(r, 'flux_reflected'):.3f}"]
        cells += [f"{value(r, k) / e:.3f}" for k in ("flux_stored", "flux_escaped", "flux_culled_outside",
                                                  "flux_culled_hidden", "flux_culled_backside")]
        cells += [f"{value(r, 'flux_deposited') / s:.3f}"]
        cells += [f"{value(r, k) / s:.3f}" for k in ("flux_splat_unseen", "flux_splat_clipped",
                                                  "flux_splat_outside_quad", "flux_splat_surface_area")]
        if radius:
            ideal = value(r, "flux_reflected") * value(r, "visible_area") / (4 * math.pi * radius * radius)
            cells += [f"{s / ideal:.3f}", f"{value(r, 'flux_deposited') / ideal:.3f}"]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    base = dict(BASE)
    radius = 0.0
    for arg in sys.argv[2:]:
        if arg.startswith("--sphere-radius"):
            radius = float(arg.split("=", 1)[1])
        else:  # overrides of the base point, key=value
            base.update([arg.split("=", 1)])
    main(sys.argv[1], base, radius)
