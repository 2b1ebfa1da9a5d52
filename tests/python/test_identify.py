"""The Python twin of `oscidrum identify` on a synthetic record made by oscidrum itself."""
import math
import os
import subprocess

import numpy as np
import pytest

import oscidrum
import oscidrum.identify

F = 39.0 * 1.01


def truth(G):
    c = oscidrum.Case()
    c.set("soil.input", "modulus")
    c.set("soil.G", G)
    c.set("roller.M0", 54947.0 * (F / 39.0) ** 2)  # M0 grows with f^2, (5)
    c.set("roller.f", F)
    return c


def test_identify_recovers_G_with_an_interval_that_covers_it():
    r = oscidrum.synthetic_record([truth(17.3e6)], duration=0.6, sample_rate=1500, noise=0.05,
                                  drift=0.05, seed=3)
    rows = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=0)
    assert len(rows) == 1 and rows[0]["valid"], rows[0]["reason"]
    row = rows[0]
    assert abs(row["G"] / 17.3e6 - 1) < 0.03
    assert row["G_lo"] <= 17.3e6 <= row["G_hi"]
    assert abs(row["f"] / F - 1) < 1e-4
    assert row["fitted"].get("soil.G") == pytest.approx(row["G"])
    # The sensors' gain uncertainty, counted: the same G, a wider uncertainty with its gain part.
    wide = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=0,
                                      gain_uncertainty=0.02)[0]
    assert wide["G"] == row["G"] and wide["G_u_gain"] > 0
    assert wide["G_u"] == pytest.approx(math.hypot(row["G_u"], wide["G_u_gain"]), rel=1e-9)
    assert wide["G_lo"] < row["G_lo"] and wide["G_hi"] > row["G_hi"]


def test_a_record_shorter_than_the_default_window_is_identified_whole():
    # window=None (the default): 40 periods, or the whole record when it is shorter (about 12
    # periods here), the same as window=0; a window given explicitly must fit in the record.
    r = oscidrum.synthetic_record([truth(17.3e6)], duration=0.3, sample_rate=1500, noise=0.05,
                                  seed=3)
    case = truth(17.3e6)
    (row,) = oscidrum.identify_record(case, r["t"], r["ddx_M"], r["ddz_M"], profile=False)
    (whole,) = oscidrum.identify_record(case, r["t"], r["ddx_M"], r["ddz_M"], window=0,
                                        profile=False)
    assert row["valid"], row["reason"]
    assert row["G"] == whole["G"] and row["t_end"] == whole["t_end"]
    with pytest.raises(ValueError, match="must span at least one window"):
        oscidrum.identify_record(case, r["t"], r["ddx_M"], r["ddz_M"], window=40, profile=False)


def test_read_record_reads_a_loggers_file_as_the_cli_does(tmp_path):
    # A logger's file: a preamble, semicolons with decimal commas, time in ms under a bare 't',
    # accelerations in g with the z axis up, a repeated time (both sides of a switch).
    r = oscidrum.synthetic_record([truth(17.3e6)], duration=0.6, sample_rate=1500, noise=0.05,
                                  seed=3)
    lines = ["Device: CCC logger", "", "t;acc_x [g];acc_z [g]"]
    for t, x, z in zip(r["t"], r["ddx_M"], r["ddz_M"]):
        lines.append(f"{t * 1000:.6f};{x / 9.80665:.9g};{-z / 9.80665:.9g}".replace(".", ","))
    lines.insert(5, lines[4])
    path = tmp_path / "logger.csv"
    path.write_text("\n".join(lines) + "\n")
    rec = oscidrum.read_record(path, z_positive="up")
    assert rec["delimiter"] == "semicolon"
    assert rec["columns"] == {"t": "t", "ddx_M": "acc_x [g]", "ddz_M": "acc_z [g]"}
    assert rec["factors"] == {"t": 1e-3, "ddx_M": 9.80665, "ddz_M": -9.80665}
    assert any("read in ms" in n for n in rec["notes"]), rec["notes"]
    assert any("1 row repeats the time" in n for n in rec["notes"]), rec["notes"]
    assert len(rec["t"]) == len(r["t"])
    assert np.allclose(rec["t"], r["t"], atol=1e-9)
    assert np.allclose(rec["ddz_M"], r["ddz_M"], rtol=1e-8, atol=1e-8)
    (row,) = oscidrum.identify.identify(rec["t"], rec["ddx_M"], rec["ddz_M"], window=0,
                                        profile=False)
    assert row["valid"] and abs(row["G"] / 17.3e6 - 1) < 0.03, row
    with pytest.raises(oscidrum.Error, match="cannot open the file"):
        oscidrum.read_record(tmp_path / "missing.csv")
    with pytest.raises(oscidrum.Error, match="z_positive must be one of auto, down, up"):
        oscidrum.read_record(path, z_positive="upward")
    assert rec["z_positive"] == "up"
    # The same logger keeping gravity in its z column (+1 g at rest along an axis pointing up):
    # read by default (z_positive='auto') as pointing up, the offset left for the fit's mean.
    lines = [line if k < 3 else line.rsplit(";", 1)[0] + ";" +
             f"{float(line.rsplit(';', 1)[1].replace(',', '.')) + 1:.9g}".replace(".", ",")
             for k, line in enumerate(lines)]
    path.write_text("\n".join(lines) + "\n")
    rec = oscidrum.read_record(path)
    assert rec["z_positive"] == "up" and rec["factors"]["ddz_M"] == -9.80665
    assert any("read as pointing up (negated)" in n for n in rec["notes"]), rec["notes"]
    assert np.allclose(rec["ddz_M"], r["ddz_M"] - 9.80665, rtol=1e-8, atol=1e-7)
    assert oscidrum.read_record(path, z_positive="down")["z_positive"] == "down"


def test_failed_windows_carry_every_estimate_key_as_nan():
    # Windows of noise alone fail their gates (the residual's): the docs' frame example must
    # still find G, G_lo, G_hi (NaN), as the CLI's CSV has the columns; soil_scale is in every
    # row. (Windows of half a period were used; they are refused now, as no window can hold one.)
    r = oscidrum.synthetic_record([truth(17.3e6)], duration=0.3, sample_rate=1500, seed=3)
    rng = np.random.default_rng(3)
    noise_x, noise_z = rng.normal(size=len(r["t"])), rng.normal(size=len(r["t"]))
    frame = oscidrum.identify.identify_frame(r["t"], noise_x, noise_z, window=2, f=39.0,
                                             fit_mu=True)
    assert len(frame) > 0 and not frame["valid"].any()
    for key in ("G", "G_u", "G_lo", "G_hi", "mu", "mu_lo", "mu_hi"):
        assert frame[key].isna().all(), key
    assert (frame["soil_scale"] == "formulas").all()


def test_mu_of_a_rolling_drum_is_not_identifiable_with_either_method():
    c = truth(25.3e6)
    c.set("contact.pure_rolling", True)
    r = oscidrum.synthetic_record([c], duration=0.6, sample_rate=1000, noise=0.05, drift=0.05,
                                  seed=2)
    rows = {}
    for shooting in (True, False):
        (row,) = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], case=c, window=0,
                                            fit_mu=True, profile=False, shooting=shooting)
        assert row["valid"], row["reason"]
        assert any("mu is not identifiable" in w for w in row["warnings"])
        assert math.isnan(row["mu_hi"])
        rows[shooting] = row
    assert abs(rows[True]["G"] / 25.3e6 - 1) < 0.03
    assert abs(rows[True]["G"] - rows[False]["G"]) < 0.01 * rows[False]["G_u"]


def test_pure_noise_is_not_a_valid_window():
    rng = np.random.default_rng(1)
    t = np.arange(1000) * 1e-3
    rows = oscidrum.analyze_windows(t, rng.normal(size=1000), rng.normal(size=1000), f=39.0,
                                    window=20)
    assert rows and not any(w["valid"] for w in rows)
    assert all("fit residual" in w["reason"] for w in rows)
    assert all(math.isnan(w["metrics"].area) for w in rows)


@pytest.mark.skipif("OSCIDRUM_CLI" not in os.environ, reason="needs the CLI")
def test_cli_reads_stdin_and_agrees_with_python(tmp_path):
    r = oscidrum.synthetic_record([truth(8.1e6)], duration=0.6, sample_rate=1000, noise=0.05)
    text = "t,ddx_M,ddz_M\n" + "".join(
        f"{t:.9g},{x:.9g},{z:.9g}\n" for t, x, z in zip(r["t"], r["ddx_M"], r["ddz_M"]))
    out = subprocess.run([os.environ["OSCIDRUM_CLI"], "identify", "-", "--window", "0",
                          "--format", "csv", "--quiet"], input=text, capture_output=True,
                         text=True, check=True).stdout
    (tmp_path / "id.csv").write_text(out)
    cols = oscidrum.identify.read_csv(tmp_path / "id.csv")
    rows = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=0)
    assert cols["G"][0] == pytest.approx(rows[0]["G"], rel=1e-6)
    assert abs(cols["G"][0] / 8.1e6 - 1) < 0.03
    fig = oscidrum.identify.plot_pass(tmp_path / "id.csv")
    fig.savefig(tmp_path / "g.png")
    assert (tmp_path / "g.png").stat().st_size > 0


def test_a_table2_soil_on_the_table2_scale():
    c = oscidrum.Case(G=30e6)  # the Table 2 soil at 30 MN/m^2, as `oscidrum run --G 30`
    c.set("roller.M0", 54947.0 * (F / 39.0) ** 2)
    c.set("roller.f", F)
    r = oscidrum.synthetic_record([c], duration=0.6, sample_rate=1500, noise=0.02, seed=3)
    (row,) = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=0,
                                        soil_scale="table2")
    assert row["valid"], row["reason"]
    assert abs(row["G"] / 30e6 - 1) < 0.01
    assert row["G_lo"] <= 30e6 <= row["G_hi"]
    with pytest.raises(oscidrum.Error, match="soil_scale must be formulas"):
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=0, soil_scale="tabel2")


def test_a_record_with_z_up_is_diagnosed_and_read_with_z_positive_up():
    # Most accelerometer mounts point z up; read as the model's z (down, given) the fit is poor,
    # and the warning says which convention fits. Read with z_positive='up' it is the truth
    # again; so it is by default ('auto': without gravity in the channel, the fit decides, and
    # the window says so).
    r = oscidrum.synthetic_record([truth(30e6)], duration=0.6, sample_rate=1500, noise=0.02,
                                  seed=5)
    z_up = -np.asarray(r["ddz_M"])
    (wrong,) = oscidrum.identify.identify(r["t"], r["ddx_M"], z_up, window=0, z_positive="down")
    assert not wrong["z_negated"]
    assert any("far better with z_M'' negated" in w and "z_positive='up'" in w
               for w in wrong["warnings"]), wrong["warnings"]
    (right,) = oscidrum.identify.identify(r["t"], r["ddx_M"], z_up, window=0, z_positive="up")
    assert right["valid"], right["reason"]
    assert abs(right["G"] / 30e6 - 1) < 0.01
    assert not right["z_negated"]
    assert not any("far better" in w for w in right["warnings"])
    (fitted,) = oscidrum.identify.identify(r["t"], r["ddx_M"], z_up, window=0)
    assert fitted["valid"] and fitted["z_negated"], fitted["warnings"]
    assert fitted["G"] == pytest.approx(right["G"], rel=1e-9)
    assert fitted["warnings"][0].startswith("z_M'' fitted negated"), fitted["warnings"]
    assert not oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=0)[0]["z_negated"]
    with pytest.raises(oscidrum.Error, match="z_positive must be 'auto', 'down' or 'up'"):
        oscidrum.identify.identify(r["t"], r["ddx_M"], z_up, window=0, z_positive="upward")
    # With gravity kept (+1 g along the upward axis), the default ('auto') reads it as pointing
    # up, with a warning, and gives what z_positive='up' gives; 'down' keeps it as it is.
    with pytest.warns(UserWarning, match="about \\+1 g.*read as pointing up"):
        (auto,) = oscidrum.identify.identify(r["t"], r["ddx_M"], z_up + 9.80665, window=0)
    assert auto["valid"] and abs(auto["G"] / right["G"] - 1) < 1e-6, (auto["G"], right["G"])
    (kept,) = oscidrum.identify.identify(r["t"], r["ddx_M"], z_up + 9.80665, window=0,
                                         z_positive="down")
    assert any("far better with z_M'' negated" in w for w in kept["warnings"]), kept["warnings"]


def test_analyze_windows_fits_the_harmonics_the_sampling_resolves():
    # 500 Hz of a 39 Hz drum: 12.8 samples per period resolve 5 harmonics, the default; 10 asked
    # for fail the samples-per-period gate with the reason.
    t = np.arange(500) / 500.0
    nu = 2 * np.pi * 39.0
    x = 12.0 * np.sin(nu * t) + 3.0 * np.sin(3 * nu * t)
    z = 0.5 * np.sin(2 * nu * t + 0.3)
    (w,) = oscidrum.analyze_windows(t, x, z)
    assert w["valid"], w["reason"]
    assert len(w["metrics"].ddx_amplitude) == 6
    assert w["metrics"].ddx_amplitude[3] == pytest.approx(3.0, abs=1e-7)
    (ten,) = oscidrum.analyze_windows(t, x, z, n_max=10)
    assert not ten["valid"] and "too few samples per period" in ten["reason"]


def test_a_window_across_a_change_of_soil_is_flagged():
    # G = 10 then 25 MN/m^2: the windows across the change fail the change gate (key `change`),
    # those on either side are valid; a looser gate lets them through.
    cases = [oscidrum.Case(input="modulus", G=10e6), oscidrum.Case(input="modulus", G=25e6)]
    r = oscidrum.synthetic_record(cases, duration=4.0, sample_rate=2000, noise=0.05, seed=3)
    ws = oscidrum.analyze_windows(r["t"], r["ddx_M"], r["ddz_M"], window=40, hop=10)
    across = [w for w in ws if w["t_start"] < 1.9 and w["t_end"] > 2.1]
    clear = [w for w in ws if w["t_end"] < 2.0 or w["t_start"] > 2.0]
    assert across and clear
    assert all(not w["valid"] and "changes within the window" in w["reason"] for w in across)
    assert all(w["valid"] for w in clear)
    loose = oscidrum.analyze_windows(r["t"], r["ddx_M"], r["ddz_M"], window=40, hop=10,
                                     max_change=10.0)
    assert all("changes within" not in w["reason"] for w in loose)
    with pytest.raises(ValueError):
        oscidrum.analyze_windows(r["t"], r["ddx_M"], r["ddz_M"], window=40, max_change=float("nan"))


@pytest.mark.skipif("OSCIDRUM_CLI" not in os.environ, reason="needs the CLI")
def test_the_pass_plot_marks_windows_over_a_change_of_soil(tmp_path):
    """The pass plot tells a window over a change of soil from one that failed another gate,
    and an estimate with a warning from a clean one, from Python's rows and from the CLI's CSV."""
    cases = [oscidrum.Case(input="modulus", G=10e6), oscidrum.Case(input="modulus", G=25e6)]
    r = oscidrum.synthetic_record(cases, duration=4.0, sample_rate=2000, noise=0.05, seed=3)
    rows = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=40, hop=10,
                                      profile=False)
    assert any("changes within the window" in row["reason"] for row in rows)
    rows[0]["warnings"] = ["poor fit: a warning for the test"]
    text = "t,ddx_M,ddz_M\n" + "".join(
        f"{t:.9g},{x:.9g},{z:.9g}\n" for t, x, z in zip(r["t"], r["ddx_M"], r["ddz_M"]))
    (tmp_path / "pass.csv").write_text(text)
    subprocess.run([os.environ["OSCIDRUM_CLI"], "identify", str(tmp_path / "pass.csv"),
                    "--window", "40", "--hop", "10", "--no-profile", "--csv",
                    str(tmp_path / "id.csv"), "--quiet"], capture_output=True, check=False)
    for source, warned in ((rows, True), (tmp_path / "id.csv", False)):
        fig = oscidrum.identify.plot_pass(source, x="t")
        labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert "soil changes within the window" in labels, labels
        assert ("estimate with a warning (poor fit, ...)" in labels) == warned, labels
        assert "window failed a gate" not in labels, labels


def test_identify_frame_and_geojson(tmp_path):
    pd = pytest.importorskip("pandas")
    # A soil given by G on Appendix B's scale, the scale identify reports by default.
    r = oscidrum.synthetic_record([oscidrum.Case(input="modulus", G=25e6)], duration=1.2,
                                  sample_rate=1000, noise=0.02, seed=1)
    frame = oscidrum.identify.identify_frame(r["t"], r["ddx_M"], r["ddz_M"], window=20)
    assert isinstance(frame, pd.DataFrame)
    assert {"t", "G", "G_lo", "G_hi", "valid", "warnings"} <= set(frame.columns)
    assert len(frame) >= 2 and frame["valid"].all()
    assert np.allclose(frame["G"], 25e6, rtol=0.03)
    lat = 48.2 + 1e-5 * r["t"]
    lon = np.full_like(r["t"], 16.37)
    path = tmp_path / "pass.geojson"
    gj = oscidrum.identify.to_geojson(frame, t=r["t"], lat=lat, lon=lon, path=path)
    assert gj["type"] == "FeatureCollection" and len(gj["features"]) == len(frame)
    import json
    assert json.loads(path.read_text()) == gj  # plain JSON: no NaN, no numpy types
    for f, (_, row) in zip(gj["features"], frame.iterrows()):
        lon_f, lat_f = f["geometry"]["coordinates"]
        assert lat_f == pytest.approx(48.2 + 1e-5 * row["t"], abs=1e-10)
        assert f["properties"]["G"] == pytest.approx(row["G"])
    # A logger's sparse fixes (NaN between, every 100th row a fix): the centres between the fixes,
    # and no NaN in the file (it held NaN coordinates, which is no JSON).
    sparse_lat, sparse_lon = lat.copy(), lon.copy()
    gaps = np.arange(len(lat)) % 100 != 0
    sparse_lat[gaps], sparse_lon[gaps] = np.nan, np.nan
    sparse = oscidrum.identify.to_geojson(frame, t=r["t"], lat=sparse_lat, lon=sparse_lon,
                                          path=path)
    json.loads(path.read_text(), parse_constant=lambda c: pytest.fail("no JSON: " + c))
    for f, g in zip(sparse["features"], gj["features"]):
        assert f["geometry"]["coordinates"] == pytest.approx(g["geometry"]["coordinates"],
                                                             abs=1e-9)
    no_fix = np.full_like(lat, np.nan)
    assert oscidrum.identify.to_geojson(frame, t=r["t"], lat=no_fix,
                                        lon=no_fix)["features"][0]["geometry"] is None
    rows = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=20)
    assert oscidrum.identify.to_geojson(rows)["features"][0]["geometry"] is None
    with pytest.raises(ValueError):
        oscidrum.identify.to_geojson(rows, lat=lat)


def test_calibrate_then_identify_with_the_calibrated_case(tmp_path):
    """A roller with 15 % more unbalance and 20 % more axle load than the paper's: calibrated on
    two references of known G (z up, as a logger writes it), the calibrated case identifies a
    third record's soil; it round-trips through a case file."""
    def roller(G):
        c = truth(G)
        c.set("roller.M0", c.get("roller.M0") * 1.15)
        c.set("roller.P0", 45224.0 * 1.2)
        return c

    def record(G, seed):
        r = oscidrum.synthetic_record([roller(G)], duration=1.0, sample_rate=1000, noise=0.03,
                                      drift=0.05, jitter=0.1, seed=seed)
        return {"t": r["t"], "ddx_M": r["ddx_M"], "ddz_M": -r["ddz_M"], "G": G,
                "name": f"G={G / 1e6:g}"}

    cal = oscidrum.identify.calibrate([record(15e6, 1), record(60e6, 2)],
                                      parameters=["roller.M0", "roller.P0"], z_positive="up")
    truths = {"roller.M0": 54947.0 * 1.15, "roller.P0": 45224.0 * 1.2}
    assert [e["name"] for e in cal["estimates"]] == list(truths)
    for e in cal["estimates"]:
        assert abs(e["value"] / truths[e["name"]] - 1) < 0.02, e
        assert e["lower"] <= truths[e["name"]] <= e["upper"], e
    assert cal["warnings"] == [] and cal["converged"]
    assert [r["name"] for r in cal["references"]] == ["G=15", "G=60"]
    assert not any(r["z_negated"] for r in cal["references"])
    # The same references by default ('auto'; no gravity in them): the fit reads them z up.
    auto = oscidrum.identify.calibrate([record(15e6, 1), record(60e6, 2)],
                                       parameters=["roller.M0", "roller.P0"])
    assert all(r["z_negated"] for r in auto["references"]), auto["warnings"]
    for e, given in zip(auto["estimates"], cal["estimates"]):
        assert e["value"] == pytest.approx(given["value"], rel=1e-9)
    assert auto["warnings"][0].startswith("z_M'' fitted negated in G=15, G=60"), auto["warnings"]
    # Read on the other soil scale, the same references fit poorly, and the warning names the
    # scale they fit on (the references carry their G and scale to the library).
    other = oscidrum.identify.calibrate([record(15e6, 1), record(60e6, 2)],
                                        parameters=["roller.M0", "roller.P0"], z_positive="up",
                                        soil_scale="table2", profile=False)
    assert any("other soil scale" in w and "--soil-scale formulas" in w
               for w in other["warnings"]), other["warnings"]
    path = tmp_path / "roller.toml"
    path.write_text(oscidrum.case_to_toml(cal["calibrated"]))
    case = oscidrum.load_case(str(path))
    assert case.get("roller.M0") == pytest.approx(cal["estimates"][0]["value"], rel=1e-12)
    r = oscidrum.synthetic_record([roller(32e6)], duration=1.0, sample_rate=1000, noise=0.03,
                                  drift=0.05, seed=3)
    row = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], case=case, window=0)[0]
    assert abs(row["G"] / 32e6 - 1) < 0.03 and row["G_lo"] <= 32e6 <= row["G_hi"], row
    with pytest.raises(oscidrum.Error, match="given by each reference"):
        oscidrum.identify.calibrate([record(15e6, 1)], parameters=["soil.G"])
    with pytest.raises(oscidrum.Error, match="G or soil"):
        oscidrum.identify.calibrate([dict(record(15e6, 1), soil=oscidrum.Soil())])
    with pytest.raises(oscidrum.Error, match="MN/m"):
        oscidrum.identify.calibrate([dict(record(15e6, 1), G=1.0)])


def test_plot_pass_takes_legend_like_the_other_plots():
    r = oscidrum.synthetic_record([truth(25e6)], duration=0.6, sample_rate=1000, noise=0.02,
                                  seed=2)
    rows = oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=4, profile=False)
    fig = oscidrum.identify.plot_pass(rows, x="t", legend=None)
    assert fig.axes[0].get_legend() is None
    fig = oscidrum.identify.plot_pass(rows, x="t", legend="outside")
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    assert (ax.get_legend().get_window_extent(renderer).x0 >=
            ax.get_window_extent(renderer).x1)
    with pytest.raises(ValueError, match="legend must be one of"):
        oscidrum.identify.plot_pass(rows, x="t", legend="left")


def test_synthetic_record_refuses_sizes_and_noise_it_cannot_make():
    # A sample rate of 1e12/s ended in MemoryError (std::bad_alloc); negative noise was taken.
    for kw, key in ((dict(sample_rate=1e12), "sample_rate"), (dict(noise=-1.0), "noise"),
                    (dict(drift=float("nan")), "drift")):
        with pytest.raises(oscidrum.Error) as e:
            oscidrum.synthetic_record([oscidrum.Case()], **kw)
        assert e.value.key == key


def test_a_loggers_columns_in_g_without_a_unit_are_read_or_fitted_in_g(tmp_path):
    # Columns in g with no unit in the header: with gravity kept, read_record reads them in g
    # (and gravity turns z up); without it the unit stays open (units_open), and identify_record
    # with units_open=True fits them in g, as the CLI does.
    r = oscidrum.synthetic_record([truth(30e6)], duration=0.6, sample_rate=1500, noise=0.02,
                                  seed=5)
    g = 9.80665
    t, x, z = (np.asarray(r[k]) for k in ("t", "ddx_M", "ddz_M"))
    for gravity in (1.0, 0.0):
        path = tmp_path / f"logger{gravity}.csv"
        np.savetxt(path, np.column_stack([t, x / g, gravity - z / g]), delimiter=",",
                   header="t,ax,az", comments="")
        rec = oscidrum.read_record(path)
        assert rec["units_open"] == (gravity == 0.0)
        assert rec["z_open"] == (gravity == 0.0)
        if gravity:
            assert rec["ddx_M"] == pytest.approx(x, rel=1e-6, abs=1e-6)
            assert any(n.startswith("accelerations: no unit in the header") for n in rec["notes"])
            continue
        (row,) = oscidrum.identify_record(oscidrum.Case(), rec["t"], rec["ddx_M"], rec["ddz_M"],
                                          window=0, z_open=rec["z_open"],
                                          units_open=rec["units_open"])
        assert row["valid"] and row["read_in_g"] and row["z_negated"], row["warnings"]
        assert abs(row["G"] / 30e6 - 1) < 0.01


def test_ctrl_c_interrupts_a_pass():
    # A pass ran to its end whatever Ctrl-C said (the windows ran with the GIL released and no
    # one looked for signals): it stops between windows now.
    import os
    import signal
    import threading
    import time

    r = oscidrum.synthetic_record([truth(17.3e6)], duration=30.0, sample_rate=1000, noise=0.02,
                                  seed=4)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window=2)
    timer.join()
    assert time.perf_counter() - start < 5.0


def test_calibrate_names_a_reference_that_is_no_dict():
    # A TypeError from inside the package ("argument of type 'int' is not iterable").
    with pytest.raises(oscidrum.Error, match="reference 0 must be a dict"):
        oscidrum.identify.calibrate([5])


def test_identify_names_a_misspelled_option():
    # pybind11's refusal named identify_record and dumped its signature and the arrays.
    r = oscidrum.synthetic_record([truth(25e6)], duration=0.3, seed=1)
    with pytest.raises(oscidrum.Error, match="unknown option 'windw' \\(did you mean 'window'\\?\\)"):
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], windw=20)
    with pytest.raises(oscidrum.Error, match="case must be an oscidrum.Case; got int"):
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], case=5)


def test_times_out_of_order_are_quoted_in_the_records_own_times():
    # The pass takes the record from its first sample; the message quoted those times (t = 0.5
    # after 0.5009999999999764 for a record from t = 1000 s).
    t = 1000.0 + np.arange(1000) / 1000.0
    i = np.arange(len(t))
    i[500], i[501] = 501, 500
    x = np.sin(2 * np.pi * 39 * t)
    with pytest.raises(oscidrum.Error, match=r"row 502 has t = 1000\.5 after 1000\.501 "):
        oscidrum.identify.identify(t[i], x, x)


def test_a_wrongly_typed_option_is_named_in_one_line():
    # pybind11's refusal was 783 characters: the binding's signature, the value at its end.
    r = oscidrum.synthetic_record([truth(25e6)], duration=0.3, seed=1)
    with pytest.raises(oscidrum.Error) as e:
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], window="20")
    assert str(e.value) == "identify: window must be a number or None; got str ('20')"
    with pytest.raises(oscidrum.Error, match=r"^identify: fit_mu must be True or False; got int"):
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], fit_mu=1)
    with pytest.raises(oscidrum.Error, match=r"^identify: compare must be an integer; got float"):
        oscidrum.identify.identify(r["t"], r["ddx_M"], r["ddz_M"], compare=4.0)
