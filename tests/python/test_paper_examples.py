"""The paper reproduction and the examples run and write what they promise."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FIGURES = ["fig07", "fig08a", "fig08b", "fig09a", "fig09b", "fig10a", "fig10b", "fig11", "fig12",
           "fig13a", "fig13b", "fig14", "fig15", "fig16", "fig17", "fig18", "fig19", "fig20",
           "fig21a", "fig21b", "fig22"]


def run(args, cwd, timeout=180):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, *args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env)


def test_paper_reproduction(tmp_path):
    (tmp_path / "validation.md").write_text("# validation\n")
    p = run(["-m", "oscidrum.paper", "--out", str(tmp_path), "--quiet"], tmp_path)
    assert p.returncode == 0, p.stderr
    for name in FIGURES:
        f = tmp_path / f"{name}.png"
        assert f.exists() and f.read_bytes().startswith(b"\x89PNG"), name
    for n in range(7, 23):
        assert list(tmp_path.glob(f"fig{n:02d}*.csv")), n
    report = (tmp_path / "report.md").read_text()
    for n in range(7, 23):
        assert f"## Fig. {n}" in report
    assert "(validation.md)" in report and "could not be drawn" not in report
    assert "| the paper (MODEL.md §8) | computed here | verdict |" in report
    cases = (tmp_path / "cases.csv").read_text().splitlines()
    assert len(cases) == 1 + 14 * 7 + 1


@pytest.mark.parametrize("script", sorted(p.name for p in (ROOT / "examples").glob("*.py")))
def test_example_runs(script, tmp_path):
    p = run([str(ROOT / "examples" / script), str(tmp_path)], tmp_path)
    assert p.returncode == 0, p.stderr
    pngs = list(tmp_path.glob("*.png"))
    assert pngs and all(f.stat().st_size > 1000 for f in pngs)
