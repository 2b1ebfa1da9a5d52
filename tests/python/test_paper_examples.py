"""The paper reproduction (python3 -m oscidrum.paper) and the examples run and write what they
promise; the report holds the library's validation rows."""

import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

import oscidrum
from oscidrum import paper
from oscidrum.data import read_table

ROOT = Path(__file__).resolve().parents[2]
FIGURES = ["fig07", "fig08a", "fig08b", "fig09a", "fig09b", "fig10a", "fig10b", "fig11", "fig12",
           "fig13a", "fig13b", "fig14", "fig15", "fig16", "fig17", "fig18", "fig19", "fig20",
           "fig21a", "fig21b", "fig22"]


def run(args, cwd, timeout=180):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, *args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env)


@pytest.fixture(scope="session")
def paper_out(tmp_path_factory):
    """`python3 -m oscidrum.paper` run once: (output folder, completed process)."""
    out = tmp_path_factory.mktemp("paper")
    return out, run(["-m", "oscidrum.paper", "--out", str(out), "--quiet"], out)


def sections(report):
    """{"## heading": text} of a Markdown report."""
    parts = re.split(r"^(## .*)$", report, flags=re.M)
    return dict(zip(parts[1::2], parts[2::2]))


def test_paper_reproduction(paper_out):
    out, p = paper_out
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == str(out / "report.md")
    for name in FIGURES:
        f = out / f"{name}.png"
        assert f.exists() and f.read_bytes().startswith(b"\x89PNG"), name
    for n in range(7, 23):
        assert list(out.glob(f"fig{n:02d}*.csv")), n
    report = (out / "report.md").read_text()
    heads = sections(report)
    for n in range(7, 23):
        assert f"## Fig. {n}" in heads
    assert "could not be drawn" not in report
    assert ("MODEL" + ".md") not in report  # cites only the paper and the project's docs
    for link in re.findall(r"\]\(([^)]+)\)", report):  # every figure and file linked exists
        assert (out / link).exists(), link
    cases = (out / "cases.csv").read_text().splitlines()
    assert len(cases) == 1 + sum(len(s.G) for s in oscidrum.paper_series())


def test_paper_report_holds_the_bound_validation(paper_out, paper_rows):
    """report.md, validation.md and validation.csv hold exactly the rows of oscidrum.validate;
    each row sits beside every figure its `figure` field names."""
    out, _ = paper_out
    table = oscidrum.validation_markdown(paper_rows)
    report = (out / "report.md").read_text()
    heads = sections(report)
    assert heads["## Validation table"].strip() == table.strip()
    assert table.splitlines()[-1] in report.split("\n\n")[2]  # the summary at the top
    assert (out / "validation.md").read_text() == paper.VALIDATION_TITLE + table
    csv_rows, units = read_table(out / "validation.csv")
    assert list(csv_rows) == list(paper.ROW_FIELDS)
    assert csv_rows["id"] == [r.id for r in paper_rows]
    for name in paper.ROW_FIELDS:
        want = [getattr(r, name) for r in paper_rows]
        if name in ("agrees", "checkable"):
            want = ["true" if v else "false" for v in want]
        assert csv_rows[name] == want, name
    for row in paper_rows:
        line = next(line for line in table.splitlines() if line.startswith(f"| {row.id} |"))
        figures = {n for n in paper.figures_of(row.figure) if 7 <= n <= 22}
        where = {f"## Fig. {n}" for n in figures} or {"## The whole study"}
        for head, text in heads.items():
            if head != "## Validation table":
                assert (line in text) == (head in where), (row.id, head)


def test_figures_of():
    assert paper.figures_of("Fig. 9a") == {9}
    assert paper.figures_of("Figs. 11, 14") == {11, 14}
    assert paper.figures_of("Figs. 13a, 16") == {13, 16}
    assert paper.figures_of("Sect. 3.4") == set()


def test_paper_exit_status(monkeypatch, tmp_path, capsys):
    """1 as soon as one checkable row disagrees; rows that are not checkable do not count."""
    def row(agrees, checkable=True):
        return SimpleNamespace(id="x", figure="Fig. 9a", paper="1", oscidrum="2", rule="=",
                               agrees=agrees, checkable=checkable)

    for rows, code in (([row(True), row(False, False)], 0), ([row(True), row(False)], 1)):
        fake = paper.Reproduction(tmp_path / "report.md", rows, [], 0.0)
        monkeypatch.setattr(paper, "reproduce", lambda *a, **k: fake)
        assert paper.main(["--out", str(tmp_path), "--quiet"]) == code
        assert fake.agrees == (code == 0)
    assert "does not agree: x (Fig. 9a)" in capsys.readouterr().err


@pytest.mark.parametrize("script", sorted(p.name for p in (ROOT / "examples").glob("*.py")))
def test_example_runs(script, tmp_path):
    p = run([str(ROOT / "examples" / script), str(tmp_path)], tmp_path)
    assert p.returncode == 0, p.stderr
    pngs = list(tmp_path.glob("*.png"))
    assert pngs and all(f.stat().st_size > 1000 for f in pngs)
