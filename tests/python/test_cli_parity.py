"""Python and the C++ CLI give identical numbers for the same case (both call the same
library; the CSV writers must agree byte for byte)."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

import oscidrum
from oscidrum import data, paper


def effective(case):
    """The case's fields that matter (the CLI rejects keys without effect): the library's
    key_in_effect, which to_dict() follows."""
    values = case.to_dict(all=True)
    kept = {k: v for k, v in values.items() if oscidrum.key_in_effect(case, k)}
    assert kept == case.to_dict()
    return kept


def set_args(case):
    """--set KEY=VALUE for every effective field of the case (%.17g numbers: exact)."""
    args = []
    for key, value in effective(case).items():
        if isinstance(value, bool):
            text = "true" if value else "false"
        elif isinstance(value, float):
            text = "%.17g" % value
        else:
            text = str(value)
        args += ["--set", f"{key}={text}"]
    return args


CASES = {
    "stick_slip_G25_MMd": lambda: oscidrum.Case(soil=oscidrum.table2_soil(25e6),
                                                MMd=0.05 * 54947.0),
    "pure_rolling_G5_spiral": lambda: oscidrum.Case(
        soil=oscidrum.table2_soil(5e6), trough={"k": 0.002, "a": 0.601},
        **{"contact.pure_rolling": True, "numerics.samples_per_period": 256}),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_python_equals_cli(cli, tmp_path, name):
    case = CASES[name]()
    csv, summary = tmp_path / "cli.csv", tmp_path / "cli.json"
    p = subprocess.run([cli, "run", *set_args(case), "--csv", str(csv), "--json", str(summary)],
                       capture_output=True, text=True, timeout=120)
    if p.returncode != 0 and "steady" not in p.stdout + p.stderr:
        pytest.fail(f"oscidrum run failed ({p.returncode}): {p.stderr}")
    result = oscidrum.simulate(case)
    mine = tmp_path / "python.csv"
    data.write_case_csv(result, mine)
    assert mine.read_bytes() == csv.read_bytes()  # identical numbers, identical text
    state = data.read_case(csv, summary)
    for column, _ in data.COLUMNS:
        assert np.array_equal(getattr(state.samples, column), getattr(result.samples, column))
    info = json.loads(summary.read_text())
    assert info["status"] == result.status.name
    assert {k: info["parameters"][k] for k in effective(case)} == effective(case)
    metrics = oscidrum.compute_metrics(result, case=case)  # from the dense output, as `run`
    for key, value in metrics.to_dict().items():
        if math.isnan(value):  # undefined (a ratio to an absent fundamental): null in JSON
            assert info["metrics"][key] is None, key
        else:
            assert info["metrics"][key] == value, key


def test_cli_plot_calls_the_python_plots(cli, tmp_path):
    out = tmp_path / "plots"
    p = subprocess.run([cli, "run", "--G", "25", "--csv", str(tmp_path / "c.csv"), "--json",
                        str(tmp_path / "c.json"), "--plot", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    pngs = sorted(f.name for f in out.glob("*.png"))
    assert "accelerations.png" in pngs and "figure_eight.png" in pngs


def test_cli_sweep_equals_run_study_and_plots(cli, root, tmp_path):
    results = tmp_path / "results.csv"
    # Independent cases on both sides: the CLI chains continuation along G (its longest factor),
    # run_study along the input order, which agree to the steady-state tolerance only.
    p = subprocess.run([cli, "sweep", str(root / "examples" / "table2_sweep.toml"), "--out",
                        str(results), "--no-continuation"], capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    table, units = data.read_csv_columns(results)
    G = table[data.resolve_column(table, "soil.G")]
    cases = []
    for g, pure, fraction in zip(G, table["contact.pure_rolling"], table["MMd_fraction"]):
        case = oscidrum.Case(soil=oscidrum.table2_soil(float(g)))
        case.contact.pure_rolling = bool(pure)
        case.MMd = float(fraction) * case.roller.M0
        case.numerics.continuation = False
        cases.append(case)
    outcomes = oscidrum.run_study(cases)
    for name in ("area", "ddx_max", "ddz_max", "psi_xz", "phi_lag"):
        assert np.array_equal(table[name], [getattr(o.metrics, name) for o in outcomes]), name
    out = tmp_path / "plots"
    p = subprocess.run([sys.executable, "-m", "oscidrum.plot", "sweep", "--csv", str(results),
                        "--x", "soil.G", "--y", "area", "--group", "MMd_fraction", "--where",
                        "contact.pure_rolling=false", "--out", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert (out / "area_vs_soil.G.png").read_bytes().startswith(b"\x89PNG")
    from oscidrum import plot

    fig = plot.plot_table(table, "soil.G", "area", group=["contact.pure_rolling", "MMd_fraction"],
                          units=units)
    # A panel per regime (pure rolling, stick-slip), a curve per MMd_fraction in each.
    assert [len(ax.lines) for ax in fig.axes] == [2, 2]


def test_cli_validate_equals_bound_validate(cli, paper_rows, tmp_path):
    """`oscidrum validate` and oscidrum.validate give the same table; oscidrum.paper's
    validation.csv is byte-identical to `oscidrum validate --csv`."""
    if subprocess.run([cli, "validate", "--help"], capture_output=True).returncode != 0:
        pytest.skip("this CLI has no `validate` command")
    p = subprocess.run([cli, "validate", "--csv", str(tmp_path / "cli.csv"), "--format",
                        "markdown", "--quiet"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stdout.endswith(oscidrum.validation_markdown(paper_rows))
    paper.write_validation(tmp_path, paper_rows)
    assert (tmp_path / "cli.csv").read_bytes() == (tmp_path / "validation.csv").read_bytes()
