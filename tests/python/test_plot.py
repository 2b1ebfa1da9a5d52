"""Plots: files written (PNG/SVG), axes and lines as expected, the CLI entry points."""

import subprocess
import sys

import numpy as np
import pytest

import oscidrum
from oscidrum import data, plot

PNG = b"\x89PNG\r\n\x1a\n"


def labels(fig):
    return [(ax.get_xlabel(), ax.get_ylabel()) for ax in fig.axes]


def test_accelerations_two_periods_with_phase_shading(slip_result):
    fig = plot.plot_accelerations(slip_result, labels=["G = 25"])
    (x1, y1), (x2, y2) = labels(fig)
    assert "m/s$^2$" in y1 and "x" in y1 and "z" in y2 and "T_{exc}" in x2
    ax = fig.axes[0]
    curve = ax.lines[0]
    tau = curve.get_xdata()
    assert tau[0] == 0.0 and 1.99 < tau[-1] < 2.0  # two periods, normalised by the period
    assert len(ax.patches) > 0  # slip phases shaded
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "G = 25" in legend and any("slip" in t for t in legend)


def test_several_cases_and_sources(slip_result, rolling_result, tmp_path):
    data.write_case_csv(rolling_result, tmp_path / "case.csv")
    fig = plot.plot_accelerations([slip_result, tmp_path / "case.csv"], labels=["a", "b"])
    assert sum(1 for line in fig.axes[0].lines if line.get_label() in ("a", "b")) == 2
    assert len(fig.axes[0].patches) == 0  # no shading for several cases by default


def test_figure_eight_and_delta_phi(rolling_result):
    fig = plot.plot_figure_eight(rolling_result)
    assert labels(fig)[0][0].startswith(r"$\ddot{x}_M$") and "z" in labels(fig)[0][1]
    x = fig.axes[0].lines[0].get_xdata()
    assert x[0] == x[-1]  # closed curve
    fig = plot.plot_delta_phi(rolling_result)
    assert [y for _, y in labels(fig)] == [plot.DELTA_LABEL, plot.PHI_LABEL]


def test_spectra_normalised(rolling_result):
    state = data.from_result(rolling_result)
    amp = plot.normalised_spectrum(state, "ddz_M", 10)
    assert amp.shape == (10,) and amp.max() == pytest.approx(1.0) and np.argmax(amp) == 1
    # from metrics and from the DFT of the samples: the same
    metrics = oscidrum.compute_metrics(rolling_result)
    metrics_state = data.from_result(rolling_result, metrics=metrics)
    assert np.allclose(plot.normalised_spectrum(metrics_state, "ddx_M"),
                       plot.normalised_spectrum(state, "ddx_M"), atol=1e-9)
    fig = plot.plot_spectra([rolling_result, rolling_result], labels=["a", "b"])
    assert len(fig.axes) == 2 and len(fig.axes[0].patches) == 20  # 10 harmonics x 2 cases
    assert "f_{exc}" in fig.axes[1].get_xlabel()


def test_sweep_labels_and_scaling():
    fig = plot.plot_sweep([5e6, 10e6], {"MMd = 0": [1.0, 2.0], "MMd = 0.05 M0": [2.0, 1.0]},
                          "soil.G", "area")
    ax = fig.axes[0]
    assert "MN/m$^2$" in ax.get_xlabel() and "m$^2$/s$^4$" in ax.get_ylabel()
    assert list(ax.lines[0].get_xdata()) == [5.0, 10.0]
    assert len(ax.lines) == 2


@pytest.mark.parametrize("fmt", ["png", "svg"])
def test_plot_case_files(slip_result, tmp_path, fmt):
    paths = plot.plot_case(slip_result, tmp_path, fmt)
    assert {p.stem for p in paths} == {"accelerations", "figure_eight", "spectra", "delta_phi",
                                       "forces"}
    for p in paths:
        assert p.suffix == "." + fmt and p.stat().st_size > 1000
        head = p.read_bytes()[:200]
        assert head.startswith(PNG) if fmt == "png" else b"<svg" in p.read_bytes()[:2000]


def test_csv_roundtrip_infers_the_window(slip_result, tmp_path):
    path = tmp_path / "case.csv"
    data.write_case_csv(slip_result, path)
    assert path.read_text().splitlines()[0] == data.HEADER
    state = data.read_case(path)
    assert state.frequency == pytest.approx(39.0, rel=1e-12)
    assert state.sample_periods == slip_result.sample_periods
    for name, _ in data.COLUMNS:
        assert np.array_equal(getattr(state.samples, name), getattr(slip_result.samples, name))


def run_module(*args):
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True,
                          timeout=120)


def test_module_entry_case(slip_result, tmp_path):
    csv = tmp_path / "case.csv"
    data.write_case_csv(slip_result, csv)
    out = tmp_path / "plots"
    p = run_module("oscidrum.plot", "case", "--csv", str(csv), "--json",
                   str(tmp_path / "missing.json"), "--out", str(out))
    assert p.returncode == 0, p.stderr
    files = sorted(f.name for f in out.iterdir())
    assert files == ["accelerations.png", "delta_phi.png", "figure_eight.png", "forces.png",
                     "spectra.png"]
    assert all((out / f).read_bytes().startswith(PNG) for f in files)
    p = run_module("oscidrum.plot", "case", "--csv", str(tmp_path / "nope.csv"), "--out",
                   str(out))
    assert p.returncode == 1 and "error" in p.stderr


def test_module_entry_sweep(tmp_path):
    # the CLI's sweep format: name[unit] headers, Table 2 G as soil.table2_G
    csv = tmp_path / "results.csv"
    csv.write_text("case[-],soil.table2_G[Pa],MMd_fraction[-],status[-],area[m^2/s^4]\n"
                   "0,5000000,0,steady_state,300\n1,10000000,0,steady_state,400\n"
                   "2,5000000,0.05,steady_state,310\n3,10000000,0.05,steady_state,420\n")
    out = tmp_path / "sweep"
    p = run_module("oscidrum.plot", "sweep", "--csv", str(csv), "--x", "soil.G", "--y", "area",
                   "--group", "MMd_fraction", "--out", str(out), "--format", "svg")
    assert p.returncode == 0, p.stderr
    svg = out / "area_vs_soil.G.svg"
    assert svg.exists() and b"<svg" in svg.read_bytes()[:2000]
    table, units = data.read_csv_columns(csv)
    fig = plot.plot_table(table, "soil.G", "area", group="MMd_fraction", units=units)
    assert len(fig.axes[0].lines) == 2
