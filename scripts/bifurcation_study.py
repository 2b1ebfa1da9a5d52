#!/usr/bin/env python3
"""The bifurcation diagrams of docs/bifurcations.md: branches of the paper's roller followed by
`oscidrum continue` in the driving torque MMd, in G (pure rolling at 58 Hz, where a Neimark-Sacker
pair bounds a range without steady state), on the log-spiral trough (a period doubling) and in f,
and the motion between the Neimark-Sacker points. Writes docs/img/branch_*.png and prints the
bifurcations, costs and verdicts that the page quotes.

    PYTHONPATH=build/python /usr/bin/python3 scripts/bifurcation_study.py [--cli build/apps/cli/oscidrum]
"""
import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

STUDIES = [
    ("branch_MMd", "MMd", "0", "14000", [], "ddx_max",
     "driving torque MMd (paper's roller, G = 25 MN/m^2 Table 2, mu = 0.5)"),
    ("branch_G_pure_rolling_58Hz", "soil.G", "30", "100",
     ["--pure-rolling", "--unilateral", "--set", "soil.input=modulus",
      "--set", "roller.unbalance=0.22877", "--set", "roller.f=58"], "ddz_max",
     "G in pure rolling at 58 Hz (unbalance 0.22877 kg m^2, soil by Appendix B)"),
    ("branch_G_log_spiral_25Hz", "soil.G", "100", "300",
     ["--set", "trough.k=0.002", "--set", "trough.a=0.601", "--set", "contact.mu=0.7",
      "--set", "roller.f=25", "--set", "roller.unbalance=0.22877", "--set", "soil.input=modulus"],
     "ddx_max", "G on the log-spiral trough k = 0.002, a = 0.601 m at 25 Hz, mu = 0.7"),
    ("branch_f", "roller.f", "10", "60",
     ["--set", "roller.unbalance=0.22877", "--set", "soil.input=modulus",
      "--set", "soil.G=80e6"], "area",
     "f with the unbalance (M0 grows with f^2), G = 80 MN/m^2 by Appendix B, mu = 0.5"),
]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default="build/apps/cli/oscidrum")
    ap.add_argument("--out", default="docs/img")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for name, key, lo, hi, extra, metric, what in STUDIES:
            csv, bif, js = (Path(tmp) / f"{name}.{s}" for s in ("csv", "bif.csv", "json"))
            cmd = [args.cli, "continue", "--param", key, "--from", lo, "--to", hi, *extra,
                   "--csv", str(csv), "--bifurcations", str(bif), "--json", str(js),
                   "--plot", str(out / f"{name}.png"), "--plot-metric", metric,
                   "--format", "none", "--quiet"]
            began = time.perf_counter()
            subprocess.run(cmd[:-7] + ["--format", "none", "--quiet"], check=True,
                           stdout=subprocess.DEVNULL)
            wall = time.perf_counter() - began
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            b = json.loads(js.read_text())
            print(f"## {what}\n`oscidrum continue --param {key} --from {lo} --to {hi} "
                  f"{' '.join(extra)}`".replace("  ", " "))
            print(f"{len(b['points'])} orbits, {b['period_maps']} period maps, "
                  f"{b['seconds']:.2f} s; end: {b['end']} ({b['message']}); the command, "
                  f"every branch included, without the plot: {wall:.2f} s")
            for child in b.get("children", []):
                print(f"  period-{child['multiplicity']} branch: {len(child['points'])} orbits, "
                      f"end: {child['end']}; bifurcations: "
                      f"{[(f['kind'], round(f['parameter'], 1)) for f in child['bifurcations']]}")
            for f in b["bifurcations"]:
                print(f"- {f['kind']} at {key} = {f['parameter']:.6g} +- {f['tolerance']:.2g}: "
                      f"{f['description']} (|multiplier| = "
                      f"{abs(complex(*f['multiplier'])):.6f})")
            print()
    # Beyond the last periodic orbit: the transient method between the Neimark-Sacker points.
    print("## the 58 Hz study between its Neimark-Sacker points (transient, max_periods 3000)")
    for G in ("45e6", "50e6", "63e6", "80e6"):
        run = subprocess.run([args.cli, "run", "--pure-rolling", "--unilateral", "--set",
                              "soil.input=modulus", "--set", "roller.unbalance=0.22877", "--set",
                              "roller.f=58", "--set", f"soil.G={G}", "--set",
                              "numerics.method=transient", "--set", "numerics.max_periods=3000",
                              "--format", "json"], capture_output=True, text=True)
        j = json.loads(run.stdout)
        d = j["diagnostics"]
        print(f"- G = {float(G) / 1e6:g} MN/m^2: {j['status']}, motion {d['motion']}, "
              f"lambda T = {d['lyapunov_exponent'] / 58.0:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
