"""Plots: files written (PNG/SVG), axes and lines as expected, the CLI entry points."""

import os
import re
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

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
    assert [y for _, y in labels(fig)] == [plot.DELTA_LABEL, plot.PHI_LABEL + " (drift removed)"]


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
    # A bad n_max is a bad call: -1 raised IndexError, 2.5 TypeError.
    for bad in (-1, 0, 2.5, True, "3"):
        with pytest.raises(oscidrum.Error, match=r"n_max must be an integer >= 1"):
            plot.plot_spectra(rolling_result, n_max=bad)


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
    # A --json that does not exist: the figures from the CSV alone, and a word that it is so.
    assert "warning: --json" in p.stderr and "missing.json" in p.stderr
    files = sorted(f.name for f in out.iterdir())
    assert files == ["accelerations.png", "delta_phi.png", "figure_eight.png", "forces.png",
                     "spectra.png"]
    assert all((out / f).read_bytes().startswith(PNG) for f in files)
    p = run_module("oscidrum.plot", "case", "--csv", str(tmp_path / "nope.csv"), "--out",
                   str(out))
    assert p.returncode == 3 and "error" in p.stderr  # EXIT_EXPLAINED
    # --periods must be a positive number of periods (0 drew empty time plots).
    for bad in ("0", "-1", "nan", "inf", "two"):
        p = run_module("oscidrum.plot", "case", "--csv", str(csv), "--out", str(out), "--periods",
                       bad)
        assert p.returncode == 2 and "--periods" in p.stderr, (bad, p.stderr)


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


def test_a_where_that_keeps_no_row_is_refused(tmp_path):
    # --where MMd_fraction=0.9 on a study of 0 and 0.05 drew an empty plot and exited 0.
    csv = tmp_path / "results.csv"
    csv.write_text("case[-],soil.table2_G[Pa],MMd_fraction[-],status[-],area[m^2/s^4]\n"
                   "0,5000000,0,steady_state,300\n1,10000000,0,steady_state,400\n"
                   "2,5000000,0.05,steady_state,310\n3,10000000,0.05,steady_state,420\n")
    out = tmp_path / "sweep"
    p = run_module("oscidrum.plot", "sweep", "--csv", str(csv), "--x", "soil.G", "--y", "area",
                   "--group", "MMd_fraction", "--where", "MMd_fraction=0.9", "--out", str(out))
    assert p.returncode == 3 and p.stdout == "", p  # EXIT_EXPLAINED, as its other errors
    assert p.stderr == ("oscidrum.plot: error: where: no row has MMd_fraction = 0.9; "
                        "MMd_fraction holds 0, 0.05\n")
    assert not out.exists()
    table, units = data.read_csv_columns(csv)
    with pytest.raises(oscidrum.Error, match=r"no row has MMd_fraction = 0\.9; MMd_fraction "
                       r"holds 0, 0\.05$"):
        plot.plot_table(table, "soil.G", "area", group="MMd_fraction", where={"MMd_fraction": 0.9})
    with pytest.raises(oscidrum.Error, match=r"no row has soil.table2_G = 7e\+06 among the rows "
                       r"kept so far; soil.table2_G holds 5e\+06, 1e\+07$"):
        plot.plot_map(table, "soil.G", "MMd_fraction", where={"MMd_fraction": 0.05, "G": 7e6})
    fig = plot.plot_table(table, "soil.G", "area", where={"MMd_fraction": 0.05})
    assert len(fig.axes[0].lines) == 1


def test_plot_table_takes_a_dataframe():
    # A StudyResult.to_dataframe() raised pandas' "truth value of a DataFrame is ambiguous".
    pd = pytest.importorskip("pandas")
    df = pd.DataFrame({"soil.input": ["modulus"] * 4, "soil.G": [5e6, 10e6, 5e6, 10e6],
                       "contact.mu": [0.4, 0.4, 0.5, 0.5], "status": ["steady_state"] * 4,
                       "area": [300.0, 400.0, 310.0, 420.0]})
    assert len(plot.plot_table(df, "soil.G", "area", group="contact.mu").axes[0].lines) == 2
    assert len(plot.plot_table(df, "soil.G", "area",
                               where={"contact.mu": 0.4}).axes[0].lines) == 1
    with pytest.raises(oscidrum.Error, match="differ in contact.mu"):
        plot.plot_table(df, "soil.G", "area")  # the text column soil.input is read as choices
    assert len(plot.plot_map(df, "soil.G", "contact.mu").axes[0].collections) == 1
    with pytest.raises(oscidrum.Error, match=r"^plot_table: the table must be a \{column: "
                       r"values\} mapping .* or a pandas DataFrame .*; got list$"):
        plot.plot_table([1, 2], "soil.G", "area")


# ---- plots that explain themselves -----------------------------------------------------------

def _data_boxes(ax):
    """Display-space points of every line (NaN at its gaps) with their box, and the boxes of
    the bars, of an Axes."""
    from matplotlib.transforms import Bbox
    boxes = []
    for line in ax.lines:
        xy = np.column_stack([line.get_xdata(), line.get_ydata()]).astype(float)
        finite = np.isfinite(xy).all(axis=1)
        if not finite.any() or line.get_transform() != ax.transData:
            continue  # axhline/axvline span the axes in axes coordinates: not data
        pts = ax.transData.transform(xy)
        ok = pts[finite]
        boxes.append((pts, Bbox.from_extents(*ok.min(axis=0), *ok.max(axis=0))))
    for patch in ax.patches:
        if patch.get_transform() == ax.transData:  # bars, not the shading spans
            box = patch.get_window_extent()
            boxes.append((None, box))
    return boxes


def assert_legends_hide_no_data(fig):
    """No legend covers data: each legend's box against every plotted point, every segment
    between two points (a legend inside the axes sits where no curve passes) and every bar."""
    from matplotlib.path import Path
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legends = [(ax, ax.get_legend()) for ax in fig.axes if ax.get_legend() is not None]
    assert legends, "the figure has no legend to check"
    for _, legend in legends:
        box = legend.get_window_extent(renderer)
        for ax in fig.axes:
            for pts, extent in _data_boxes(ax):
                if pts is None:
                    assert not box.overlaps(extent), "a legend covers a bar"
                    continue
                inside = ((pts[:, 0] > box.x0) & (pts[:, 0] < box.x1) &
                          (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1))
                assert not inside.any(), f"a legend covers {inside.sum()} data points"
                crossing = [k for k in range(len(pts) - 1)
                            if np.isfinite(pts[k:k + 2]).all() and
                            Path(pts[k:k + 2]).intersects_bbox(box, filled=False)]
                assert not crossing, f"a curve crosses a legend ({len(crossing)} segments)"


def _four_soils(pure_rolling, MMd_fraction=0.0):
    """The paper's Figs. 13a, 17, 18: four Table 2 soils, as (result, case) pairs."""
    pairs = []
    for G in (5e6, 25e6, 50e6, 70e6):
        case = oscidrum.Case(soil=oscidrum.table2_soil(G))
        case.contact.pure_rolling = pure_rolling
        case.MMd = MMd_fraction * case.roller.M0
        pairs.append((oscidrum.simulate(case), case))
    return pairs


@pytest.fixture(scope="module")
def stick_slip_four():
    return _four_soils(False)


@pytest.fixture(scope="module")
def stick_slip_driven_four():
    return _four_soils(False, 0.05)


def test_titles_name_the_case_instead_of_case_1(slip_result, slip_case):
    fig = plot.plot_accelerations((slip_result, slip_case))
    title = fig._suptitle.get_text()
    for part in ("G = 25 MN/m$^2$", "Table 2 soil", r"$\mu$ = 0.5", "$M_{Md}$ = 0.05 $M_0$",
                 "R = 0.606 m", "f = 39 Hz"):
        assert part in title, (part, title)
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert not any(t.startswith("case ") for t in legend), legend
    # Several cases: what they share in the title, what differs in the legend.
    rolling = oscidrum.Case(soil=oscidrum.table2_soil(5e6))
    rolling.contact.pure_rolling = True
    fig = plot.plot_figure_eight([(slip_result, slip_case),
                                  (oscidrum.simulate(rolling), rolling)])
    title = fig._suptitle.get_text()
    assert "R = 0.606 m" in title and "G =" not in title
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert any("G = 5 MN/m$^2$" in t and "pure rolling" in t for t in legend), legend
    # From the CLI's files: the JSON summary gives the parameters.
    assert plot.case_caption(data.from_result(slip_result)) == "f = 39 Hz"


@pytest.mark.parametrize("kind", ["fig13a", "fig17", "fig18"])
def test_legends_hide_no_data(kind, request):
    if kind == "fig13a":
        fig = plot.plot_figure_eight(_four_soils(True))
    elif kind == "fig17":
        fig = plot.plot_accelerations(request.getfixturevalue("stick_slip_four"))
    else:
        fig = plot.plot_accelerations(request.getfixturevalue("stick_slip_driven_four"))
    assert_legends_hide_no_data(fig)
    assert fig._suptitle is not None and "f = 39 Hz" in fig._suptitle.get_text()


def test_every_single_case_figure_keeps_its_legend_off_the_data(slip_result, slip_case):
    pair = (slip_result, slip_case)
    for fn in (plot.plot_accelerations, plot.plot_delta_phi, plot.plot_forces,
               plot.plot_figure_eight, plot.plot_spectra, plot.plot_torque_phi):
        assert_legends_hide_no_data(fn([pair, pair], labels=["a", "b"]))


def test_phi_is_drawn_without_its_drift(slip_result):
    phi = np.asarray(slip_result.samples.phi)
    period = len(phi) // slip_result.sample_periods
    drift = phi[period] - phi[0]  # MMd = 0.05 M0: the drum turns on by slip every period
    assert drift > 0.5 * np.ptp(phi[:period] - np.linspace(0, drift, period, endpoint=False))
    fig = plot.plot_delta_phi(slip_result)
    drawn = np.asarray(fig.axes[1].lines[0].get_ydata())
    assert abs(drawn[period] - drawn[0]) < 1e-6 * drift  # periodic: the drift is gone
    assert abs(np.mean(drawn)) < 1e-6 * drift  # and the mean
    assert np.ptp(drawn) < 0.5 * np.ptp(phi)  # so the oscillation fills the panel
    assert "drift removed" in fig.axes[1].get_ylabel()


def test_figure_eight_shows_travel_slip_and_area(slip_result, slip_case):
    fig = plot.plot_figure_eight((slip_result, slip_case))
    ax = fig.axes[0]
    arrows = [c for c in ax.texts if getattr(c, "arrow_patch", None) is not None]
    assert len(arrows) == 6
    # The arrows follow the samples' order (the direction of travel).
    x = np.asarray(slip_result.samples.ddx_M)
    z = np.asarray(slip_result.samples.ddz_M)
    a = arrows[0]
    i = int(np.argmin(np.hypot(x - a.xyann[0], z - a.xyann[1])))
    assert np.hypot(x[i + 1] - a.xy[0], z[i + 1] - a.xy[1]) < np.hypot(x[i - 1] - a.xy[0],
                                                                       z[i - 1] - a.xy[1])
    bands = [line for line in ax.lines if line.get_linewidth() >= 5]
    assert len(bands) == 2  # slip+ and slip- (the stick parts are the bare line)
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    area = oscidrum.compute_metrics(slip_result).area
    assert f"area {area:.4g}" in legend and "slip+" in legend and "slip-" in legend


def test_many_groups_get_a_colour_map_and_bar():
    mu = np.round(np.linspace(0.2, 0.8, 13), 2)
    G = np.array([5e6, 25e6, 50e6])
    table = {"case": np.arange(39.0), "contact.mu": np.repeat(mu, 3),
             "soil.table2_G": np.tile(G, 13), "area": np.arange(39.0)}
    fig = plot.plot_table(table, "soil.G", "area", group="contact.mu")
    assert len(fig.axes) == 2  # the plot and its colour bar
    assert fig.axes[0].get_legend() is None
    assert "friction coefficient" in fig.axes[1].get_ylabel()
    colours = {tuple(line.get_color()) for line in fig.axes[0].lines}
    assert len(colours) == 13  # no style reused
    fig = plot.plot_table(table, "soil.G", "area", group="contact.mu",
                          where={"contact.mu": 0.25})
    assert len(fig.axes) == 1 and len(fig.axes[0].lines) == 1


def test_plot_map_heat_map_of_any_metric():
    table = {"case": np.arange(6.0), "roller.f": np.repeat([30.0, 39.0, 45.0], 2),
             "soil.table2_G": np.tile([5e6, 25e6], 3),
             "status": np.full(6, np.nan), "ddx_max": np.array([1.0, 2.0, 3.0, np.nan, 5.0, 6.0])}
    fig = plot.plot_map(table, "soil.G", "roller.f", "ddx_max")
    ax, bar = fig.axes
    mesh = ax.collections[0]
    grid = np.ma.asarray(mesh.get_array()).reshape(3, 2)  # rows: f, columns: G
    assert grid.shape == (3, 2) and grid[1, 1] is np.ma.masked  # the failed case stays blank
    assert grid[2, 0] == 5.0 and grid[0, 1] == 2.0
    assert "MN/m$^2$" in ax.get_xlabel() and "Hz" in ax.get_ylabel()
    assert "peak" in bar.get_ylabel()
    assert sorted(t.get_text() for t in ax.texts) == ["1", "2", "3", "5", "6"]
    assert ax.get_title() == "blank: 1 of 6 cells without ddx_max (not a steady state)"
    # A study with two swept keys: plot_study draws the map.
    fig = plot.plot_study(table, "ddx_max")
    assert len(fig.axes[0].collections) == 1
    # No case with a value: an empty map with a colour bar of -0.1 ... 0.1 was drawn.
    failed = dict(table, ddx_max=np.full(6, np.nan))
    with pytest.raises(ValueError, match="no case of the study has a value of ddx_max"):
        plot.plot_study(failed, "ddx_max")


def test_failed_cases_of_a_sweep_leave_noted_gaps_inside_the_axis():
    # The failed case at the end of the range was outside the x axis and not said.
    table = {"case": np.arange(3.0), "MMd_fraction": np.array([0.0, 0.1, 0.3]),
             "status": np.full(3, np.nan), "area": np.array([22.8, 21.0, np.nan])}
    fig = plot.plot_study(table, "area")
    ax = fig.axes[0]
    assert ax.get_xlim()[1] > 0.3
    assert [t.get_text() for t in ax.texts] == [
        "1 of 3 cases without area (not a steady state): gaps"]


def test_every_plot_function_accepts_ax(slip_result):
    from matplotlib.axes import Axes
    fig, axes = plot.new_figure(2, 1)
    for fn in (plot.plot_accelerations, plot.plot_delta_phi, plot.plot_forces,
               plot.plot_spectra):
        assert list(fn(slip_result, ax=axes)) == list(axes)
    one = plot.new_figure(1, 1)[1]
    for fn in (plot.plot_figure_eight, plot.plot_torque_phi):
        assert fn(slip_result, ax=one) is one
    assert plot.plot_sweep([1.0, 2.0], {"a": [1.0, 2.0]}, ax=one) is one
    table = {"soil.G": np.array([5e6, 5e6, 25e6, 25e6]), "contact.mu": np.array([0.3, 0.5] * 2),
             "area": np.arange(4.0)}
    assert plot.plot_table(table, "soil.G", "area", group="contact.mu", ax=one) is one
    assert isinstance(plot.plot_map(table, "soil.G", "contact.mu", "area", ax=one), Axes)
    with pytest.raises(ValueError, match="2 Axes"):
        plot.plot_accelerations(slip_result, ax=one)


def test_module_entry_map_and_study(tmp_path):
    csv = tmp_path / "results.csv"
    csv.write_text("case[-],roller.f[Hz],soil.table2_G[Pa],status[-],area[m^2/s^4]\n"
                   "0,30,5000000,steady_state,30\n1,30,25000000,steady_state,20\n"
                   "2,39,5000000,steady_state,37\n3,39,25000000,steady_state,23\n")
    p = run_module("oscidrum.plot", "map", "--csv", str(csv), "--x", "soil.G", "--y",
                   "roller.f", "--out", str(tmp_path / "map.png"))
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "map.png").read_bytes().startswith(PNG)
    p = run_module("oscidrum.plot", "study", "--csv", str(csv), "--out",
                   str(tmp_path / "study.svg"))
    assert p.returncode == 0, p.stderr
    assert b"<svg" in (tmp_path / "study.svg").read_bytes()[:2000]


# ---- the CLI's plots and its Python interpreter ----------------------------------------------

def _cli_env(**extra):
    env = dict(os.environ)
    env.update(extra)
    return env


def test_cli_sweep_plot_draws_a_heat_map(cli, root, tmp_path):
    study = tmp_path / "study.toml"
    study.write_text("[roller]\nunbalance = 0.22877\n[sweep]\n"
                     "\"roller.f\" = { start = 30, stop = 40, step = 5 }\n"
                     "\"soil.table2_G\" = [10e6, 25e6]\n")
    out = tmp_path / "study.png"
    p = subprocess.run([cli, "sweep", str(study), "--out", str(tmp_path / "r.csv"), "--quiet",
                        "--plot", str(out)], capture_output=True, text=True, timeout=300,
                       env=_cli_env(OSCIDRUM_PYTHON=sys.executable))
    assert p.returncode == 0, p.stdout + p.stderr
    assert "warning" not in p.stderr  # the unbalance makes M0 follow f
    assert out.read_bytes().startswith(PNG)
    p = subprocess.run([cli, "sweep", str(study), "--plot", str(out)], capture_output=True,
                       text=True, timeout=60)
    assert p.returncode == 2 and "--plot" in p.stderr and "needs --out" in p.stderr


def test_cli_python_is_not_taken_from_path(cli, tmp_path):
    """A `python3` on PATH without the package (here: one that always fails) does not matter;
    $OSCIDRUM_PYTHON, when set, is used and named in the error."""
    fake = tmp_path / "bin"
    fake.mkdir()
    (fake / "python3").write_text("#!/bin/sh\nexit 7\n")
    (fake / "python3").chmod(0o755)
    env = _cli_env(PATH=f"{fake}:{os.environ.get('PATH', '')}")
    env.pop("OSCIDRUM_PYTHON", None)
    p = subprocess.run([cli, "run", "--quiet", "--plot", str(tmp_path / "plots")],
                       capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    assert (tmp_path / "plots" / "figure_eight.png").read_bytes().startswith(PNG)
    env["OSCIDRUM_PYTHON"] = str(tmp_path / "no" / "python")
    p = subprocess.run([cli, "run", "--quiet", "--plot", str(tmp_path / "plots2")],
                       capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 1
    assert str(tmp_path / "no" / "python") in p.stderr and "OSCIDRUM_PYTHON" in p.stderr


# ---- legends in the user's figure, legend=, study panels, spectra in m/s^2 (issue 25) ---------

def _user_figure(n):
    """A small figure of the user's own, without a layout engine (as plt.subplots makes)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(4.0, 3.0))
    FigureCanvasAgg(fig)
    axes = fig.subplots(n, 1, sharex=n > 1)
    return fig, axes


@pytest.mark.parametrize("name", ["plot_accelerations", "plot_delta_phi", "plot_forces",
                                  "plot_spectra", "plot_figure_eight", "plot_torque_phi"])
def test_legend_in_a_small_user_figure_is_not_clipped_nor_on_the_x_label(slip_result, slip_case,
                                                                        tmp_path, name):
    fn = getattr(plot, name)
    fig, axes = _user_figure(1 if name in ("plot_figure_eight", "plot_torque_phi") else 2)
    fn([(slip_result, slip_case), (slip_result, slip_case)], labels=["a", "b"], ax=axes)
    fig.savefig(tmp_path / "user.png")  # default bbox: what lies outside the figure is lost
    renderer = fig.canvas.get_renderer()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert legends
    page = fig.bbox
    for legend in legends:
        box = legend.get_window_extent(renderer)
        assert (box.x0 >= page.x0 and box.x1 <= page.x1 and box.y0 >= page.y0 and
                box.y1 <= page.y1), (name, box, page)
        for ax in fig.axes:
            label = ax.xaxis.label
            if label.get_text():
                assert not box.overlaps(label.get_window_extent(renderer)), name


def test_legend_argument_chooses_the_place(slip_result, slip_case):
    pair = (slip_result, slip_case)
    fig = plot.plot_accelerations(pair, legend=None)
    assert all(ax.get_legend() is None for ax in fig.axes)
    fig = plot.plot_figure_eight(pair, legend=False)
    assert fig.axes[0].get_legend() is None
    for place in ("outside", "below", "upper left", "best"):
        fig = plot.plot_figure_eight(pair, legend=place)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        ax = fig.axes[0]
        box = ax.get_legend().get_window_extent(renderer)
        frame = ax.get_window_extent(renderer)
        if place == "outside":
            assert box.x0 >= frame.x1
        elif place == "below":
            assert box.y1 <= ax.xaxis.label.get_window_extent(renderer).y0
        else:
            assert frame.contains(box.x0, box.y0) and frame.contains(box.x1, box.y1)
            if place == "upper left":
                assert box.x0 - frame.x0 < 0.1 * frame.width
                assert frame.y1 - box.y1 < 0.1 * frame.height
    with pytest.raises(ValueError, match="legend must be one of"):
        plot.plot_spectra(pair, legend="nowhere")


def _paper_like_study():
    """The table of examples/table2_sweep.toml in short: G x {pure rolling, mu = 0.5} x MMd/M0,
    with areas of the paper's orders (pure rolling some hundreds, stick-slip some tens)."""
    G = np.array([5e6, 25e6, 50e6, 70e6])
    rows = {"case": [], "soil.table2_G": [], "contact.pure_rolling": [], "MMd_fraction": [],
            "status": [], "area": []}
    areas = {(1.0, 0.0): [309, 537, 271, 61], (1.0, 0.05): [315, 692, 729, 323],
             (0.0, 0.0): [37, 23, 14, 9], (0.0, 0.05): [41, 42, 54, 38]}
    for i, g in enumerate(G):
        for pure in (1.0, 0.0):
            for fraction in (0.0, 0.05):
                rows["case"].append(len(rows["case"]))
                rows["soil.table2_G"].append(g)
                rows["contact.pure_rolling"].append(pure)
                rows["MMd_fraction"].append(fraction)
                rows["status"].append(np.nan)
                rows["area"].append(areas[(pure, fraction)][i])
    return {k: np.asarray(v, dtype=float) for k, v in rows.items()}


def test_study_plot_has_human_labels_a_compact_legend_and_a_panel_per_regime():
    table = _paper_like_study()
    fig = plot.plot_study(table, "area")
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    panels = [ax for ax in fig.axes if ax.lines]
    assert [ax.get_title() for ax in panels] == ["pure rolling", "stick-slip"]
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert len(legends) == 1
    texts = [t.get_text() for t in legends[0].get_texts()]
    assert texts == ["$M_{Md}/M_0$ = 0", "$M_{Md}/M_0$ = 0.05"], texts
    for text in texts:
        assert not re.search(r"[A-Za-z]\.[A-Za-z]|_fraction|pure_rolling", text), text
    assert legends[0].get_window_extent(renderer).width < 0.2 * fig.bbox.width
    # Stick-slip is not squashed against pure rolling: its curves fill most of their panel.
    for ax in panels:
        lo, hi = ax.get_ylim()
        ys = np.concatenate([line.get_ydata() for line in ax.lines])
        assert np.ptp(ys) > 0.6 * (hi - lo), ax.get_title()
    assert "shear modulus $G$ [MN/m$^2$]" == panels[0].get_xlabel()
    # In one given Axes: no panels, the regime in the labels, a log scale for both.
    one = plot.new_figure(1, 1)[1]
    plot.plot_study(table, "area", ax=one)
    labels = [t.get_text() for t in one.get_legend().get_texts()]
    assert "pure rolling, $M_{Md}/M_0$ = 0.05" in labels and "stick-slip, $M_{Md}/M_0$ = 0" in labels
    assert one.get_yscale() == "log"


def test_value_labels_come_from_the_parameter_table():
    assert plot.value_label("soil.table2_G[Pa]", 25e6) == "$G$ = 25 MN/m$^2$"
    assert plot.value_label("contact.pure_rolling", 1.0) == "pure rolling"
    assert plot.value_label("contact.pure_rolling", 0.0) == "stick-slip"
    assert plot.value_label("roller.f", 39.0) == "$f$ = 39 Hz"
    assert plot.value_label("soil.input", 1.0) == "how the soil is given = modulus"
    field = oscidrum.find_field("soil.ksh")  # unit and scale from the table, not from plot.py
    assert plot.axis_label("soil.ksh")[1] == 1.0 / field.display_scale
    assert field.display_unit.replace("^", "") in plot.axis_label("soil.ksh")[0]


def test_spectra_in_metres_per_second_squared_are_the_harmonic_amplitudes(slip_result):
    metrics = oscidrum.compute_metrics(slip_result)
    state = data.from_result(slip_result, metrics=metrics)
    fig = plot.plot_spectra(state, units="m/s^2")
    for ax, amplitudes in zip(fig.axes, (metrics.ddx_amplitude, metrics.ddz_amplitude)):
        heights = [bar.get_height() for bar in ax.patches]
        assert np.array_equal(heights, np.asarray(amplitudes)[1:11])
        assert "m/s$^2$" in ax.get_ylabel() and "A_{max}" not in ax.get_ylabel()
    # From the samples alone (the DFT): the same amplitudes.
    fig = plot.plot_spectra(slip_result, units="m/s^2")
    heights = [bar.get_height() for bar in fig.axes[0].patches]
    assert np.allclose(heights, np.asarray(metrics.ddx_amplitude)[1:11],
                       atol=1e-9 * metrics.ddx_amplitude[1])
    # Both: A_n on the left, A_n / max A_n on the right.
    fig = plot.plot_spectra(state, units="both")
    ax = fig.axes[0]
    right = [c for c in ax.get_children() if type(c).__name__ == "SecondaryAxis"]
    assert len(right) == 1 and "A_{max}" in right[0].get_ylabel()
    assert np.array_equal([b.get_height() for b in ax.patches],
                          np.asarray(metrics.ddx_amplitude)[1:11])
    with pytest.raises(ValueError, match="one case"):
        plot.plot_spectra([state, state], units="both")
    with pytest.raises(ValueError, match="units must be one of"):
        plot.plot_spectra(state, units="dB")


def test_module_entry_case_draws_spectra_in_chosen_units(slip_result, tmp_path):
    csv = tmp_path / "case.csv"
    data.write_case_csv(slip_result, csv)
    for units in ("m/s^2", "normalised"):
        out = tmp_path / units.replace("/", "_")
        p = run_module("oscidrum.plot", "case", "--csv", str(csv), "--out", str(out),
                       "--spectra-units", units)
        assert p.returncode == 0, p.stderr
        assert (out / "spectra.png").read_bytes().startswith(PNG)
    p = run_module("oscidrum.plot", "case", "--csv", str(csv), "--out", str(tmp_path / "x"),
                   "--spectra-units", "dB")
    assert p.returncode == 2 and "spectra-units" in p.stderr


def test_paper_fig7_title_names_G_once(tmp_path, monkeypatch):
    from pathlib import Path
    from oscidrum import paper
    runs = []
    for series in oscidrum.paper_series():
        if series.id in (paper.CIRCLE, paper.SPIRAL):
            case = oscidrum.paper_case(series, 5e6)
            result = oscidrum.simulate(case)
            runs.append(paper.Run(series, 5e6, "steady_state", oscidrum.compute_metrics(result),
                                  None, result))
    assert len(runs) == 2
    drawn = {}
    save = plot.save

    def keep(fig, path, fmt=None):
        drawn[Path(path).stem] = fig
        return save(fig, path, fmt)

    monkeypatch.setattr(plot, "save", keep)
    paper.Writer(tmp_path, "png", paper.Results(runs)).fig07_08()
    title = drawn["fig07"]._suptitle.get_text()
    assert title.startswith("Fig. 7") and title.count("G = 5") == 1, title
    assert title.count("pure rolling") == 1 and "f = 39 Hz" in title, title
    for name in ("fig08a", "fig08b"):
        assert drawn[name]._suptitle.get_text().count("G = 5") == 1


@pytest.mark.parametrize("mu", [-1.0, float("nan"), float("inf"), True, "0.5"])
def test_forces_refuse_a_friction_coefficient_that_is_none(slip_result, mu):
    with pytest.raises(oscidrum.Error, match="mu must be a friction coefficient >= 0"):
        plot.plot_forces(slip_result, mu=mu)


def test_forces_panel_b_legend_names_only_the_friction_limit(slip_result, slip_case):
    pair = (slip_result, slip_case)
    fig = plot.plot_forces([pair, pair], labels=["a", "b"])
    top, bottom = fig.axes
    assert [t.get_text() for t in top.get_legend().get_texts()] == ["a", "b"]
    assert [t.get_text() for t in bottom.get_legend().get_texts()] == [r"$\pm\mu N$"]
    rolling = oscidrum.Case(soil=oscidrum.table2_soil(5e6))
    rolling.contact.pure_rolling = True
    fig = plot.plot_forces((oscidrum.simulate(rolling), rolling))
    assert fig.axes[1].get_legend() is None  # pure rolling: no friction limit to name


def test_cli_diagram_plot_draws_the_stroboscopic_points(cli, tmp_path):
    out = tmp_path / "d.png"
    p = subprocess.run([cli, "diagram", "--param", "MMd", "--from", "0", "--to", "2000",
                        "--steps", "1", "--discard", "20", "--periods", "20", "--quiet",
                        "--format", "none", "--csv", str(tmp_path / "d.csv"), "--plot", str(out),
                        "--plot-quantity", "ddz_M"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert out.stat().st_size > 1000
    table, units = data.read_table(tmp_path / "d.csv")
    fig = plot.plot_diagram(table, "ddz_M", units=units)
    assert len(fig.axes[0].lines[0].get_xdata()) == 2 * 20  # every point of the up sweep


def test_an_absent_signal_is_drawn_flat_with_a_note():
    """The directed vertical exciter's x_M'' is round-off (1e-22 m/s^2): the plots draw it on
    zero on z_M'''s scale with a note, the spectra without bars, the area as 0, instead of scaling
    the round-off up to look like a signal. The plots' rule is the metrics' (absent_signals)."""
    case = oscidrum.Case(type="vibratory", static_moment=0.9, f=30.0, unilateral=True,
                         exciter="vertical")
    result = oscidrum.simulate(case)
    assert result.status == oscidrum.Status.steady_state, result.message
    metrics = oscidrum.compute_metrics(result, case=case)
    state = data.from_result(result, metrics=metrics)
    assert plot.absent_signals(state) == {"ddx_M": True, "ddz_M": False}
    assert oscidrum.absent_signals(metrics.ddx_amplitude, metrics.ddz_amplitude) == (True, False)
    # Without the metrics (the DFT of the samples): the same.
    assert plot.absent_signals(data.from_result(result)) == {"ddx_M": True, "ddz_M": False}
    notes = lambda ax: [t.get_text() for t in ax.texts if "absent" in t.get_text()]  # noqa: E731

    fig = plot.plot_accelerations(state)
    ax_x, ax_z = fig.axes[:2]
    low, high = ax_x.get_ylim()
    z_peak = np.max(np.abs(result.samples.ddz_M))
    assert high >= z_peak and low <= -z_peak  # z_M'''s scale, not 1e-22
    assert len(notes(ax_x)) == 1 and "x_M''" in notes(ax_x)[0] and not notes(ax_z)

    fig = plot.plot_figure_eight(state)
    ax = fig.axes[0]
    assert ax.get_xlim()[1] >= z_peak and len(notes(ax)) == 1
    assert any(t.get_text().startswith("area 0 (round-off")
               for t in ax.get_legend().get_texts())

    for units in ("normalised", "m/s^2", "both"):
        fig = plot.plot_spectra(state, units=units)
        bars = [p.get_height() for p in fig.axes[0].patches]
        assert bars and max(bars) == 0.0 and len(notes(fig.axes[0])) == 1, units
        assert max(p.get_height() for p in fig.axes[1].patches) > 0 and not notes(fig.axes[1])

    # Metrics of two harmonics (--harmonics 1): z_M'' of the default case (even harmonics only)
    # has none of them, but its peaks say it is there (it was drawn flat as absent).
    default = oscidrum.simulate(oscidrum.Case())
    few = data.from_result(default, metrics=oscidrum.compute_metrics(default, n_max=1))
    assert plot.absent_signals(few) == {"ddx_M": False, "ddz_M": False}

    # A case with both signals: no note anywhere, the rule agrees with the core's.
    m = oscidrum.compute_metrics(slip_case_result := oscidrum.simulate(oscidrum.Case()))
    assert oscidrum.absent_signals(m.ddx_amplitude, m.ddz_amplitude) == (False, False)
    fig = plot.plot_accelerations(data.from_result(slip_case_result, metrics=m))
    assert not any(notes(a) for a in fig.axes)


def test_two_absent_signals_share_one_note():
    """A drum without friction: x_M'' and z_M'' are both round-off (1e-16 m/s^2). The figure
    spans 1 m/s^2 each way with one note naming both, and its area reads 0."""
    case = oscidrum.Case(soil=oscidrum.table2_soil(25e6))
    case.contact.mu = 0.0
    result = oscidrum.simulate(case)
    metrics = oscidrum.compute_metrics(result)
    assert np.isnan(metrics.cmv) and np.isnan(metrics.ddz_A2_A1)
    state = data.from_result(result, metrics=metrics)
    assert plot.absent_signals(state) == {"ddx_M": True, "ddz_M": True}
    ax = plot.plot_figure_eight(state).axes[0]
    assert ax.get_xlim() == (-1.0, 1.0) and ax.get_ylim() == (-1.0, 1.0)
    notes = [t.get_text() for t in ax.texts if "absent" in t.get_text()]
    assert len(notes) == 1 and notes[0].startswith("x_M'' and z_M'' are absent")
    # Exactly 0, or the round-off of a curve that is round-off in both coordinates.
    assert any(t.get_text() == "area 0" or t.get_text().startswith("area 0 (round-off ")
               for t in ax.get_legend().get_texts())


def test_figure_eight_of_a_run_without_steady_state_shows_no_area():
    # The legend read "area 95.5 m^2/s^4" for the last periods of a transient (the steady state's
    # is 22.8), a number compute_metrics refuses for the same result.
    bad = oscidrum.simulate(oscidrum.Case(max_periods=3))
    assert bad.status.name == "max_periods_reached"
    fig = plot.plot_figure_eight(bad)
    texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "max_periods_reached, not a steady state" in texts[0], texts
    assert not any("area" in t for t in texts), texts


def test_every_figure_of_a_run_without_steady_state_says_so():
    # Only the figure eight said it: the time traces, spectra and forces of a transient's last
    # periods looked like a steady state's.
    bad = oscidrum.simulate(oscidrum.Case(max_periods=3))
    for draw in (plot.plot_accelerations, plot.plot_spectra, plot.plot_delta_phi,
                 plot.plot_forces, plot.plot_figure_eight):
        fig = draw(bad)
        title = fig._suptitle.get_text() if fig._suptitle else fig.axes[0].get_title()
        assert "max_periods_reached: not a steady state" in title, (draw.__name__, title)


def test_figure_eight_of_a_period_two_orbit_is_drawn_over_both_periods(tmp_path):
    # The log-spiral trough at 25 Hz on stiff soil: a period-2 steady state. Its figure was drawn
    # over the first excitation period, closed by a line that is not on the orbit, beside the
    # legend's area of the two-period figure.
    c = oscidrum.Case(input="modulus", G=150e6, k=0.002, a=0.601, mu=0.7, f=25.0,
                      unbalance=0.22877)
    r = oscidrum.simulate(c)
    assert r.status.name == "steady_state" and r.diagnostics.multiplicity == 2
    state = data.from_result(r)
    assert state.multiplicity == 2 and state.samples_per_orbit == 2 * state.samples_per_period
    fig = plot.plot_figure_eight(r)
    curve = [line for line in fig.axes[0].lines if line.get_zorder() == 2][0]
    assert len(curve.get_xdata()) == state.samples_per_orbit + 1  # closed
    x = np.asarray(r.samples.ddx_M)
    assert curve.get_xdata().min() == x[: state.samples_per_orbit].min() < x[
        : state.samples_per_period].min()
    # A CSV read without its summary: the samples say they repeat after 2 periods.
    data.write_case_csv(r, tmp_path / "p2.csv")
    assert data.read_case(tmp_path / "p2.csv").multiplicity == 2
    assert data.read_case(tmp_path / "p2.csv").samples_per_orbit == state.samples_per_orbit


def test_a_plot_of_something_else_names_what_it_takes():
    # An AttributeError from inside the package ("'int' object has no attribute 'samples'").
    with pytest.raises(oscidrum.Error, match="takes a Result, a CaseOutcome"):
        plot.plot_accelerations(42)


def test_a_window_of_no_periods_is_refused(slip_result):
    # periods=0 drew empty axes without a word; the time plots name the argument.
    for draw in (plot.plot_accelerations, plot.plot_delta_phi, plot.plot_forces):
        for periods in (0, -1, float("nan")):
            with pytest.raises(ValueError, match="periods must be > 0"):
                draw(slip_result, periods=periods)
        with pytest.raises(ValueError, match="periods must be > 0"):
            draw(slip_result, periods=True)  # drew one period


def test_more_periods_than_sampled_are_said(slip_result):
    # periods=10 of a result of 2 sampled periods drew 2 without a word.
    assert slip_result.sample_periods == 2
    with pytest.warns(UserWarning, match=r"periods=10: the result holds 2 sampled excitation "
                      r"periods; all 2 drawn \(sample more with numerics.output_periods\)"):
        fig = plot.plot_accelerations(slip_result, periods=10)
    tau = fig.axes[0].lines[0].get_xdata()
    assert 1.99 < tau.max() < 2.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for periods in (2, 1.5, None):
            plot.plot_accelerations(slip_result, periods=periods)


def test_a_branch_changes_style_at_its_bifurcation():
    # The stable line ran on to the first unstable point, past the Neimark-Sacker point on it.
    table = {"branch": np.zeros(4), "point": np.arange(4.0), "roller.f": np.array([50, 51, 52, 53.0]),
             "arclength": np.arange(4.0), "multiplicity": np.ones(4),
             "stable": np.array([1, 1, 0, 0.0]), "area": np.array([1.0, 2.0, 3.0, 4.0])}
    fig = plot.plot_branch(table, "area", bifurcations=[("neimark_sacker", 51.25, 0)])
    solid = [ln for ln in fig.axes[0].lines if ln.get_linestyle() == "-"]
    dashed = [ln for ln in fig.axes[0].lines if ln.get_linestyle() == "--"]
    assert solid[0].get_xdata()[-1] == 51.25 and dashed[0].get_xdata()[0] == 51.25
    assert solid[0].get_ydata()[-1] == pytest.approx(2.25)
    # Without the bifurcations: half way.
    fig = plot.plot_branch(table, "area")
    solid = [ln for ln in fig.axes[0].lines if ln.get_linestyle() == "-"]
    assert solid[0].get_xdata()[-1] == 51.5


# ---- Ctrl-C while a module is still importing (the tool starts it with the signals held) ------

def _children(pid):
    try:
        return [int(c) for c in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        return []


def test_module_interrupted_while_importing_ends_without_a_traceback(slip_result, tmp_path):
    """SIGINT held back from the start (as the oscidrum tool starts the modules) and sent at
    once, while Python still imports numpy and matplotlib: it waits for run_main's handlers,
    and the module ends with 130 and one line, not a KeyboardInterrupt traceback."""
    csv = tmp_path / "case.csv"
    data.write_case_csv(slip_result, csv)
    p = subprocess.Popen(
        [sys.executable, "-m", "oscidrum.plot", "case", "--csv", str(csv), "--out",
         str(tmp_path / "plots")],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT}))
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    assert p.returncode == 130, out + err
    assert "oscidrum.plot: interrupted" in err and "Traceback" not in err, err


def _interrupt_its_plot(args, delay):
    """Run the CLI with args, send SIGINT `delay` s after its Python module started; the
    (returncode, stdout + stderr, stderr), or a skip when it ended on its own first."""
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=_cli_env())
    deadline = time.monotonic() + 120
    while not _children(p.pid) and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.0005)
    time.sleep(delay)
    if p.poll() is not None:
        pytest.skip("the command ended before its Python module could be interrupted")
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    if p.returncode == 0:
        pytest.skip("the plots were done before the signal")
    return p.returncode, out + err, err


@pytest.mark.parametrize("delay", [0.0, 0.05, 0.15, 0.4])
def test_cli_plot_interrupted_while_the_module_starts(cli, tmp_path, delay):
    """Ctrl-C while `run --plot`'s Python is starting or importing: exit 130 and one line that
    says where the data are, no KeyboardInterrupt traceback (a signal during the imports printed
    one, exit 1; continue and diagram exited 1, run, sweep and identify said nothing)."""
    code, both, err = _interrupt_its_plot(
        [cli, "run", "--quiet", "--plot", str(tmp_path / "plots")], delay)
    assert code == 130, both
    assert "Traceback" not in both and "KeyboardInterrupt" not in both, err
    assert "oscidrum: interrupted while plotting; the data are in" in err, err


def test_cli_continue_plot_interrupted_exits_130(cli, tmp_path):
    code, both, err = _interrupt_its_plot(
        [cli, "continue", "--set", "soil.input=modulus", "--param", "soil.G", "--from", "20",
         "--to", "21", "--csv", str(tmp_path / "b.csv"), "--plot", str(tmp_path / "b.png")], 0.1)
    assert code == 130, both
    assert "Traceback" not in both, err
    assert "oscidrum: interrupted while plotting; the branch is in" in err, err


def test_plot_case_takes_a_result_case_pair(slip_case, slip_result, tmp_path):
    """plot_case refused the (result, case) pair its error message listed as accepted; with the
    pair its figures carry the case's parameters, as the single plots do."""
    paths = plot.plot_case((slip_result, slip_case), tmp_path / "pair")
    assert sorted(p.name for p in paths) == sorted(
        f"{n}.png" for n in ("accelerations", "figure_eight", "spectra", "delta_phi", "forces"))
    assert all(p.read_bytes().startswith(PNG) for p in paths)


def test_a_run_without_samples_says_why_not_keep_samples(tmp_path):
    """A run that lost contact has no samples: the refusal names its status, not a keep_samples
    advice that would not help (it was given for simulate()'s result too)."""
    case = oscidrum.Case(table2_G=5e6, pure_rolling=True)
    case.roller.M0 = 20 * case.roller.M0
    r = oscidrum.simulate(case)
    assert r.status.name == "contact_lost" and len(r.samples) == 0
    for obj in (r, oscidrum.run_study([case], threads=1, keep_samples=True)[0]):
        with pytest.raises(ValueError, match="status contact_lost") as e:
            plot.plot_accelerations(obj)
        assert "keep_samples" not in str(e.value)
    steady = oscidrum.run_study([oscidrum.Case()], threads=1)[0]
    with pytest.raises(ValueError, match="keep_samples=True"):
        plot.plot_accelerations(steady)
    # A run stopped by its budget samples its last periods: a study dropped them, keep_samples
    # keeps them.
    short = oscidrum.Case(method="transient", max_periods=5)
    (unfinished,) = oscidrum.run_study([short], threads=1)
    assert unfinished.result.status.name == "max_periods_reached"
    with pytest.raises(ValueError, match="keep_samples=True"):
        plot.plot_accelerations(unfinished)
    (kept,) = oscidrum.run_study([short], threads=1, keep_samples=True)
    plot.plot_accelerations(kept)


def test_refusals_are_oscidrum_errors_and_labels_are_one_per_case():
    """The plots refused with a plain ValueError, which `except oscidrum.Error` missed; a labels
    list one short or one long was taken without a word."""
    steady = oscidrum.run_study([oscidrum.Case()], threads=1)[0]
    with pytest.raises(oscidrum.Error, match="keep_samples=True"):
        plot.plot_accelerations(steady)
    r = oscidrum.simulate(oscidrum.Case())
    with pytest.raises(oscidrum.Error, match="legend must be one of"):
        plot.plot_accelerations(r, legend="nowhere")
    with pytest.raises(oscidrum.Error, match=r"^labels: give one per case; got 1 for 2 cases$"):
        plot.plot_accelerations([r, r], labels=["a"])
    with pytest.raises(oscidrum.Error, match=r"^labels: give one per case; got 3 for 2 cases$"):
        plot.plot_accelerations([r, r], labels=["a", "b", "c"])
    fig = plot.plot_accelerations([r, r], labels=["a", "b"])
    legends = list(fig.legends) + [ax.get_legend() for ax in fig.axes if ax.get_legend()]
    texts = [t.get_text() for legend in legends for t in legend.get_texts()]
    assert "a" in texts and "b" in texts, texts


def test_cases_differing_in_a_column_not_grouped_are_not_joined_into_one_curve():
    # A product sweep G x mu plotted against G grouped by nothing: the three mu's cases at each
    # G were joined into one zigzag curve (and a map's cell kept the last) without a word.
    G = np.array([5e6, 25e6, 50e6])
    table = {"case": np.arange(9.0), "soil.table2_G": np.repeat(G, 3),
             "contact.mu": np.tile([0.4, 0.5, 0.6], 3), "status": np.full(9, np.nan),
             "area": np.arange(9.0), "ddx_max": np.arange(9.0)}
    with pytest.raises(oscidrum.Error, match=r"differ in contact\.mu \(0\.4, 0\.5, 0\.6\).*"
                       r"add 'contact\.mu' to group= or give where=\{'contact\.mu': 0\.4\}"):
        plot.plot_table(table, "soil.G", "area")
    assert len(plot.plot_table(table, "soil.G", "area", group="contact.mu").axes[0].lines) == 3
    assert len(plot.plot_table(table, "soil.G", "area",
                               where={"contact.mu": 0.5}).axes[0].lines) == 1
    # The plotted metric and columns that are one value per point do not count.
    table["MMd_fraction"] = np.repeat([0.0, 0.05, 0.1], 3)  # follows G (a zip sweep)
    plot.plot_table(table, "soil.G", "area", group="contact.mu")
    # A third key under a map of two: its cells would hold one case of several.
    table = {k: np.concatenate([v, v]) for k, v in table.items()}
    table["contact.pure_rolling"] = np.repeat([0.0, 1.0], 9)
    with pytest.raises(oscidrum.Error, match=r"plot_map: rows with the same soil.table2_G and "
                       r"contact.mu differ in contact.pure_rolling"):
        plot.plot_map(table, "soil.G", "contact.mu", "area")
    plot.plot_map(table, "soil.G", "contact.mu", "area", where={"contact.pure_rolling": 1})
