#!/usr/bin/env python3
"""Coverage of identify's 95 % intervals on records sampled in step with the excitation.

A logger whose sampling rate is a whole multiple M of the excitation frequency f samples every
period at the same phases; at even M, the harmonics of orders M/2, 3M/2, ... fold exactly onto
half the sampling rate (docs/identify.md, step 2). For each rate, 30 synthetic records (paper
roller, soil by Appendix B at G = 10 MN/m^2, f = 39 Hz, 0.5 % noise, 3 s) are identified and the
valid windows' estimates of G compared with the truth: their mean error and scatter, the mean
stated standard uncertainty u, the share of 95 % intervals that hold the truth, and the mean
reduced chi^2.

    PYTHONPATH=build/python /usr/bin/python3 bench/identify_in_step.py [RATE ...]

Default rates: 12, 14, 16, 18 and 20 samples per period (468-780 samples/s) and 630 samples/s
(not in step). About 12 s on one core.
"""
import sys
import warnings

import numpy as np

import oscidrum
import oscidrum.identify as identify

G = 10e6
rates = [float(a) for a in sys.argv[1:]] or [468.0, 546.0, 624.0, 702.0, 780.0, 630.0]
warnings.simplefilter("ignore")
print("rate [1/s]  windows  mean error  scatter  mean u  scatter/u  coverage  reduced chi^2")
for rate in rates:
    err, u, inside, chi2 = [], [], [], []
    for seed in range(1, 31):
        r = oscidrum.synthetic_record([oscidrum.Case(input="modulus", G=G)], duration=3,
                                      sample_rate=rate, noise=0.005, seed=seed)
        for w in identify.identify(r["t"], r["ddx_M"], r["ddz_M"]):
            if not w["valid"]:
                continue
            err.append(w["G"] / G - 1)
            u.append(w["G_u"] / G)
            inside.append(w["G_lo"] <= G <= w["G_hi"])
            chi2.append(w["reduced_chi2"])
    err, u = np.array(err), np.array(u)
    print("%10.0f  %7d  %+9.3f%%  %6.3f%%  %5.3f%%  %9.2f  %7.0f%%  %13.2f" % (
        rate, len(err), 100 * err.mean(), 100 * err.std(), 100 * u.mean(),
        err.std() / u.mean(), 100 * np.mean(inside), np.mean(chi2)), flush=True)
