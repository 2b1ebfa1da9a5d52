"""The vibratory drum's indicators from Python: the excitation's angle alpha that `run --csv` and
Result.samples carry, vibration_modulus (the Evib-type modulus of a force-displacement loop) and
record_kb (kb of a record with its unbalance's angle). Checked against what the bindings do not
compute: Lundberg's relation written out below, the simulated steady state's own kb and evib
(from the contact force), and the CLI's `analyze --case --unbalance-col`."""

import json
import math
import subprocess

import numpy as np
import pytest

import oscidrum
from oscidrum import data

R, L, NU = 0.6, 1.68, 0.3  # the paper's drum (Table 1), Table 2's Poisson's ratio
F_VIB = 30.0  # examples/vibratory.toml's frequency [Hz]

# --- the angle column alpha ---------------------------------------------------------------------

def test_samples_carry_the_excitation_angle(root):
    case = oscidrum.load_case(root / "examples" / "vibratory.toml")
    s = oscidrum.simulate(case).samples
    assert "alpha" in oscidrum.Samples.columns and "alpha[rad]" in s.headers
    assert s.headers[-1] == "phase[-]"
    assert np.all(s.alpha >= 0) and np.all(s.alpha < 2 * math.pi)
    nu_t = 2 * math.pi * F_VIB * s.t
    np.testing.assert_allclose(np.exp(1j * s.alpha), np.exp(1j * nu_t), atol=1e-11)


def test_read_case_of_a_file_without_alpha_computes_it(cli, root, tmp_path):
    """A steady-state CSV of an oscidrum before the column alpha still reads: alpha = nu t."""
    csv, summary = tmp_path / "s.csv", tmp_path / "s.json"
    subprocess.run([cli, "run", str(root / "examples" / "vibratory.toml"), "--quiet", "--csv",
                    str(csv), "--json", str(summary)], check=True, capture_output=True)
    new = data.read_case(csv, summary)
    lines = csv.read_text().splitlines()
    drop = lines[0].split(",").index("alpha[rad]")
    old = tmp_path / "old.csv"
    old.write_text("".join(",".join(c for k, c in enumerate(line.split(",")) if k != drop) + "\n"
                           for line in lines))
    for json_path in (summary, None):
        state = data.read_case(old, json_path)
        assert np.all(state.samples.alpha >= 0) and np.all(state.samples.alpha < 2 * math.pi)
        np.testing.assert_allclose(np.exp(1j * state.samples.alpha),
                                   np.exp(1j * new.samples.alpha), rtol=0, atol=1e-9)


# --- vibration_modulus --------------------------------------------------------------------------

def lundberg(F, E):
    """Lundberg's settlement [m] of the rigid cylinder R, L pressed by F [N] into a half-space
    (E, NU), as docs/outputs.md states it (0 at F = 0)."""
    F = np.atleast_1d(np.asarray(F, dtype=float))
    z = np.zeros_like(F)
    on = F > 0
    b = np.sqrt(16.0 * R * (1.0 - NU**2) * F[on] / (math.pi * L * E))
    z[on] = (1.0 - NU**2) / E * F[on] / L * (2.0 / math.pi) * (1.8864 + np.log(L / b))
    return z


def synthetic_loop(E, F1, F2, flight, rotate):
    """One period of a closed loop, as tests/metrics/test_evib.cpp builds it: the loading branch
    z(F) = z1 + Lundberg(F) - Lundberg(F1) from F1 to F2, the unloading branch back above it and,
    with a flight, a parabola in z at F = 0 from the lift-off over the top to the landing at z1;
    then rotated to start at point `rotate`."""
    n, z1 = 200, 2e-3
    s = np.arange(n + 1) / n
    F_load = F1 + (F2 - F1) * s * s
    z_load = z1 + lundberg(F_load, E) - lundberg(F1, E)
    rise = z_load[-1] - z1
    s = np.arange(n - 1, 0, -1) / n
    F_unload = F1 + (F2 - F1) * s * s
    z_unload = z1 + lundberg(F_unload, E) - lundberg(F1, E) + 0.05 * rise * np.sin(math.pi * s)
    zs, Fs = [z_load, z_unload], [F_load, F_unload]
    if flight:
        s = np.arange(100, 0, -1) / 100  # 1 at the lift-off, towards 0 at the landing
        zs.append(z1 + 0.02 * rise * s - 3.0 * rise * 4.0 * s * (1.0 - s))
        Fs.append(np.zeros_like(s))
    z, F = np.concatenate(zs), np.concatenate(Fs)
    return np.roll(z, -rotate), np.roll(F, -rotate)


@pytest.mark.parametrize("flight", [False, True])
@pytest.mark.parametrize("E", [2e7, 8e7, 3e8])
def test_vibration_modulus_recovers_E_of_a_loop_built_from_lundbergs_relation(E, flight):
    F1 = 0.0 if flight else 25e3
    F2 = 120e3 if flight else 90e3
    for rotate in (0, 37, 250, 400):
        z, F = synthetic_loop(E, F1, F2, flight, rotate)
        assert oscidrum.vibration_modulus(z, F, R, L, NU) == pytest.approx(E, rel=1e-6), rotate
    # Arguments by name, any float sequence.
    z, F = synthetic_loop(E, F1, F2, flight, 0)
    assert oscidrum.vibration_modulus(z=list(z), F=list(F), R=R, L=L, nu=NU) == pytest.approx(
        E, rel=1e-6)


def test_vibration_modulus_reads_the_geometry_and_poissons_ratio():
    E = 8e7
    z, F = synthetic_loop(E, 25e3, 90e3, False, 0)
    for args in ((2 * R, L, NU), (R, 2 * L, NU), (R, L, 0.45)):
        assert abs(oscidrum.vibration_modulus(z, F, *args) - E) > 1e-3 * E, args


def test_vibration_modulus_of_a_simulated_loop_is_the_steady_states_evib(root):
    """The loop F_v = N cos(delta) + T sin(delta) over z_M of the samples of one steady period of
    examples/vibratory.toml (partial uplift) gives Metrics.evib, which run reads off the dense
    output, to the samples' resolution of the landing, where F_v jumps (linear interpolation
    between the samples on either side) and of the largest force: 5e-3 at 1024 samples per period
    (seen: 2.0e-3), shrinking as the sampling refines (16384: 3.9e-4)."""
    errors = []
    for samples in (1024, 16384):
        case = oscidrum.load_case(root / "examples" / "vibratory.toml")
        case.set("numerics.samples_per_period", samples)
        result = oscidrum.simulate(case)
        assert result.status == oscidrum.Status.steady_state, result.message
        m = oscidrum.compute_metrics(result, case=case)
        assert m.flight_fraction > 0 and m.evib > 0
        s, n = result.samples, result.samples_per_period
        Fv = s.N[:n] * np.cos(s.delta[:n]) + s.T[:n] * np.sin(s.delta[:n])
        evib = oscidrum.vibration_modulus(s.z_M[:n], Fv, case.roller.r, case.roller.b, NU)
        errors.append(abs(evib / m.evib - 1.0))
    assert errors[0] < 5e-3
    assert errors[1] < errors[0] / 3.0, errors


def test_vibration_modulus_is_nan_for_a_degenerate_loop():
    z = np.array([0.0, 1e-3, 2e-3, 1e-3])
    assert math.isnan(oscidrum.vibration_modulus(z, np.zeros(4), R, L, NU))  # no force
    assert math.isnan(oscidrum.vibration_modulus(np.full(4, 1e-3), z, R, L, NU))  # no motion
    assert math.isnan(oscidrum.vibration_modulus(z[:2], z[:2], R, L, NU))  # fewer than 3 points


def test_vibration_modulus_refuses_bad_input_naming_the_argument():
    z = np.array([0.0, 1e-3, 2e-3, 1e-3])
    with pytest.raises(oscidrum.Error, match=r"z has 4 points and F 3"):
        oscidrum.vibration_modulus(z, z[:3], R, L, NU)
    with pytest.raises(oscidrum.Error, match=r"radius R must be > 0"):
        oscidrum.vibration_modulus(z, z, 0.0, L, NU)
    with pytest.raises(oscidrum.Error, match=r"length L must be > 0"):
        oscidrum.vibration_modulus(z, z, R, -1.0, NU)
    with pytest.raises(oscidrum.Error, match=r"Poisson's ratio nu must be in \[0, 0.5\)"):
        oscidrum.vibration_modulus(z, z, R, L, 0.5)
    with pytest.raises(oscidrum.Error, match=r"^F must be a 1-D array"):
        oscidrum.vibration_modulus(z, np.zeros((2, 2)), R, L, NU)
    with pytest.raises(oscidrum.Error, match=r"vibration_modulus"):
        oscidrum.vibration_modulus(z, "force", R, L, NU)
    assert issubclass(oscidrum.Error, ValueError)


# --- record_kb ----------------------------------------------------------------------------------

def vibratory(G, f=F_VIB):
    """The paper's drum with the rotating unbalance of examples/vibratory.toml on Appendix B soil
    of shear modulus G, contact that may open, as tests/identify/test_identify_vibratory.cpp."""
    c = oscidrum.Case()
    c.set("roller.type", "vibratory")
    c.set("roller.static_moment", 0.9)
    c.set("roller.f", f)
    c.set("contact.unilateral", True)
    c.set("soil.input", "modulus")
    c.set("soil.G", G)
    return c


@pytest.mark.parametrize("G, tolerance, lift_off", [(12e6, 1e-6, False), (60e6, 2e-3, True)])
def test_record_kb_of_a_simulated_record_is_the_simulated_kb(G, tolerance, lift_off):
    """As IdentifyVibratory.KbOfARecordIsTheSimulatedKb: a noise-free record of the steady state
    (record time = model time modulo the period, so alpha = 2 pi f t) at 2000 samples per period
    over 6 periods gives the kb that the steady state's contact force gives, in continuous
    contact to 1e-6, with lift-off to the aliasing of z_M'''s jump at the landing (2e-3)."""
    case = vibratory(G)
    result = oscidrum.simulate(case)
    assert result.status == oscidrum.Status.steady_state, result.message
    sim = oscidrum.compute_metrics(result, case=case)
    assert (sim.flight_fraction > 0) == lift_off
    r = oscidrum.synthetic_record([case], duration=6.0 / F_VIB, sample_rate=2000.0 * F_VIB)
    t = r["t"]
    alpha = 2.0 * math.pi * F_VIB * t
    windows = oscidrum.analyze_windows(t, r["ddx_M"], r["ddz_M"], f=F_VIB)
    assert len(windows) == 1 and windows[0]["valid"], windows[0]["reason"]
    before = windows[0]["metrics"].to_dict()
    assert math.isnan(before["kb"])  # before record_kb
    assert oscidrum.record_kb(windows, t, alpha, case) == ""
    kb = windows[0]["metrics"].kb
    assert kb == pytest.approx(sim.kb, rel=tolerance)
    # The window's other metrics are kept.
    after = windows[0]["metrics"].to_dict()
    assert {k: v for k, v in after.items() if k != "kb"} == {
        k: v for k, v in before.items() if k != "kb"}
    # An angle read as a sensor gives it, wrapped to [0, 2 pi) or (-pi, pi]: the same kb.
    for wrapped in (np.mod(alpha, 2 * math.pi), np.angle(np.exp(1j * alpha))):
        again = oscidrum.analyze_windows(t, r["ddx_M"], r["ddz_M"], f=F_VIB)
        assert oscidrum.record_kb(again, t, wrapped, case) == ""
        assert again[0]["metrics"].kb == pytest.approx(kb, rel=1e-9)
    # The phase matters: a quarter turn off gives another number.
    shifted = oscidrum.analyze_windows(t, r["ddx_M"], r["ddz_M"], f=F_VIB)
    assert oscidrum.record_kb(shifted, t, alpha + math.pi / 2, case) == ""
    assert abs(shifted[0]["metrics"].kb - sim.kb) > 0.1 * sim.kb


def test_record_kb_reads_each_windows_own_angles():
    """Three windows of two periods: an angle a quarter turn off in the first window's samples
    only changes that window's kb; the others give the simulated kb (continuous contact: 1e-6)."""
    case = vibratory(12e6)
    sim = oscidrum.compute_metrics(oscidrum.simulate(case), case=case)
    r = oscidrum.synthetic_record([case], duration=6.0 / F_VIB, sample_rate=2000.0 * F_VIB)
    t = r["t"]
    windows = oscidrum.analyze_windows(t, r["ddx_M"], r["ddz_M"], f=F_VIB, window=2)
    assert len(windows) == 3 and all(w["valid"] for w in windows)
    alpha = 2.0 * math.pi * F_VIB * t + np.where(t < windows[1]["t_start"], math.pi / 2, 0.0)
    assert oscidrum.record_kb(windows, t, alpha, case) == ""
    kb = [w["metrics"].kb for w in windows]
    assert abs(kb[0] - sim.kb) > 0.1 * sim.kb
    assert kb[1] == pytest.approx(sim.kb, rel=1e-6) and kb[2] == pytest.approx(sim.kb, rel=1e-6)


def test_record_kb_takes_the_windows_of_a_record_with_a_pause():
    """A logger paused for 20 periods: the windows inside the pause have no samples (their t_start
    no sample's); record_kb passes over them as over any invalid window (it refused them as
    windows 'not of this t') and gives the others their kb."""
    case = vibratory(12e6)
    sim = oscidrum.compute_metrics(oscidrum.simulate(case), case=case)
    r = oscidrum.synthetic_record([case], duration=6.0 / F_VIB, sample_rate=2000.0 * F_VIB)
    t = np.where(r["t"] < 3.0 / F_VIB, r["t"], r["t"] + 20.0 / F_VIB)
    alpha = 2.0 * math.pi * F_VIB * t
    windows = oscidrum.analyze_windows(t, r["ddx_M"], r["ddz_M"], f=F_VIB, window=3)
    empty = [w for w in windows if w["samples"] == 0]
    assert empty and all(not w["valid"] and "no samples" in w["reason"] for w in empty)
    assert oscidrum.record_kb(windows, t, alpha, case) == ""
    valid = [w for w in windows if w["valid"]]
    assert len(valid) >= 2  # one on either side of the pause (and the record's end window)
    for w in valid:
        assert w["metrics"].kb == pytest.approx(sim.kb, rel=1e-6)


def two_period_record():
    """A synthetic record of two periods of the vibratory drum at G = 12 MN/m^2: the case, t, the
    unbalance angle nu t and its analyze_windows."""
    case = vibratory(12e6)
    r = oscidrum.synthetic_record([case], duration=2.0 / F_VIB, sample_rate=1000.0 * F_VIB)
    t = r["t"]
    alpha = 2.0 * math.pi * F_VIB * t
    return case, t, alpha, oscidrum.analyze_windows(t, r["ddx_M"], r["ddz_M"], f=F_VIB)


def test_record_kb_says_why_kb_is_nan():
    case, t, alpha, windows = two_period_record()
    for a, c, why in ((None, case, "no unbalance angle"), (alpha, None, "--case"),
                      (alpha, oscidrum.Case(), "oscillation drum")):
        assert why in oscidrum.record_kb(windows, t, a, c)
        assert math.isnan(windows[0]["metrics"].kb)
    # An invalid window keeps kb NaN too (NaN metrics, no fundamental).
    bad = dict(windows[0], valid=False)
    assert oscidrum.record_kb([bad], t, alpha, case) == ""
    assert math.isnan(bad["metrics"].kb)


def test_record_kb_refuses_bad_input_naming_the_argument():
    case, t, alpha, windows = two_period_record()
    with pytest.raises(oscidrum.Error, match=r"record_kb: alpha has \d+ samples and t \d+"):
        oscidrum.record_kb(windows, t, alpha[:-1], case)
    with pytest.raises(oscidrum.Error, match=r"^alpha must be a 1-D array"):
        oscidrum.record_kb(windows, t, alpha.reshape(-1, 1), case)
    with pytest.raises(oscidrum.Error, match=r"^t must be a 1-D array"):
        oscidrum.record_kb(windows, t.reshape(1, -1), alpha, case)
    with pytest.raises(oscidrum.Error, match=r"windows\[0\] must be a dict of analyze_windows"):
        oscidrum.record_kb([1.0], t, alpha, case)
    with pytest.raises(oscidrum.Error, match=r"windows\[0\] has no key 'metrics'"):
        oscidrum.record_kb([{k: v for k, v in windows[0].items() if k != "metrics"}], t, alpha,
                           case)
    with pytest.raises(oscidrum.Error, match=r"windows\[0\]: its t_start = .* is no sample of t"):
        oscidrum.record_kb(windows, t + 1e-3, alpha, case)
    with pytest.raises(oscidrum.Error, match=r"windows\[0\]: .* run past the end of t"):
        oscidrum.record_kb(windows, t[: len(t) // 2], alpha[: len(t) // 2], case)
    with pytest.raises(oscidrum.Error, match=r"windows\[0\]: t_start, samples, f, valid or "):
        oscidrum.record_kb([dict(windows[0], metrics="kb")], t, alpha, case)
    with pytest.raises(oscidrum.Error, match=r"record_kb"):
        oscidrum.record_kb(windows, t, alpha, "examples/vibratory.toml")


def test_run_csv_alpha_gives_the_clis_and_the_runs_kb(cli, root, tmp_path):
    """`run --csv` of examples/vibratory.toml read in Python with its own column alpha: record_kb
    gives what `analyze --case --unbalance-col alpha` prints for the same file (the same
    computation: 1e-12) and the run's kb (the contact force's: 1e-3, as the CLI's test)."""
    example = root / "examples" / "vibratory.toml"
    csv, summary = tmp_path / "s.csv", tmp_path / "s.json"
    subprocess.run([cli, "run", str(example), "--quiet", "--csv", str(csv), "--json",
                    str(summary)], check=True, capture_output=True)
    out = subprocess.run([cli, "analyze", str(csv), "--f", "30", "--case", str(example),
                          "--unbalance-col", "alpha", "--format", "json"], check=True,
                         capture_output=True, text=True).stdout
    cli_kb = json.loads(out)["kb"]
    run_kb = json.loads(summary.read_text())["metrics"]["kb"]
    columns, units = data.read_csv_columns(csv)
    assert units["alpha"] == "rad"
    windows = oscidrum.analyze_windows(columns["t"], columns["ddx_M"], columns["ddz_M"], f=30.0)
    assert oscidrum.record_kb(windows, columns["t"], columns["alpha"],
                              oscidrum.load_case(example)) == ""
    kb = windows[0]["metrics"].kb
    assert kb == pytest.approx(cli_kb, rel=1e-12)
    assert kb == pytest.approx(run_kb, rel=1e-3)
