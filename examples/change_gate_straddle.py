"""A record whose soil changes 1 excitation period into the second 40-period window.

G = 30 MN/m^2 until t_c = 41/39 s, then 17.3 MN/m^2 (soil by Appendix B), 2 kHz, 2 % noise,
5 % drift, z positive up and in g with gravity kept, as a logger writes it. The change gate of
`oscidrum identify` (its 5 % are of the response's RMS) passes the window that straddles the
change (docs/identify.md, "What the gate misses"):

    python3 examples/change_gate_straddle.py straddle.csv
    oscidrum identify straddle.csv
"""
import sys

import oscidrum

G0 = 9.80665
path = sys.argv[1] if len(sys.argv) > 1 else "straddle.csv"
tc = 41 / 39.0
seg = tc / 8
n2 = round((2.2 - tc) / seg)
cases = ([oscidrum.Case(input="modulus", G=30e6)] * 8
         + [oscidrum.Case(input="modulus", G=17.3e6)] * n2)
r = oscidrum.synthetic_record(cases, duration=seg * len(cases), sample_rate=2000, noise=0.02,
                              drift=0.05, jitter=0.1, seed=3, speed=0.8)
with open(path, "w") as f:
    f.write("Time [s],Acc X [g],Acc Z [g]\n")
    for t, x, z in zip(r["t"], r["ddx_M"], r["ddz_M"]):
        f.write(f"{t:.7f},{x / G0:.6f},{-z / G0 + 1:.6f}\n")
