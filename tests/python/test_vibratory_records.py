"""The vibratory drum's indicators from Python: the excitation's angle alpha that `run --csv` and
Result.samples carry, and vibration_modulus (the Evib-type modulus of a force-displacement loop).
Checked against what the bindings do not compute: Lundberg's relation written out below and the
simulated steady state's own evib (from the contact force)."""

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
