"""The excitation's angle alpha that `run --csv` and Result.samples carry for the vibratory drum's
kb (`analyze --unbalance-col alpha`): 2 pi f t wrapped to [0, 2 pi), also where read_case reads a
file written before the column existed."""

import math
import subprocess

import numpy as np

import oscidrum
from oscidrum import data

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
