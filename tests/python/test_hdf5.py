"""`oscidrum sweep --hdf5`: a study in one HDF5 file, read with h5py (docs/outputs.md, "HDF5").

The HDF5 file must hold exactly what the CSV outputs hold (results row by row, each case's steady
state sample by sample), with units, and the HDF5 files of shards merged by `oscidrum merge` must
equal the file of the unsharded sweep.
"""

import csv
import math
import os
import subprocess

import pytest

h5py = pytest.importorskip("h5py")
np = pytest.importorskip("numpy")

STUDY = """
[sweep]
"soil.table2_G" = [5e6, 25e6, 45e6, 70e6]
"contact.pure_rolling" = [false, true]
"""


def sweep(cli, *args):
    # Independent cases (--no-continuation): shards then give the unsharded bits.
    done = subprocess.run([cli, "sweep", *map(str, args), "-q", "--no-continuation"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done


def split_label(label):
    name, _, unit = label.rpartition("[")
    return name, unit[:-1]


@pytest.fixture(scope="module")
def study(cli, tmp_path_factory):
    d = tmp_path_factory.mktemp("hdf5")
    (d / "study.toml").write_text(STUDY)
    sweep(cli, d / "study.toml", "--out", d / "all.csv", "--hdf5", d / "all.h5",
          "--cases-dir", d / "cases")
    return d


def test_results_and_parameters_match_the_csv_with_units(study):
    with open(study / "all.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    with h5py.File(study / "all.h5", "r") as h5:
        assert h5.attrs["format"] == "oscidrum-study"
        assert h5.attrs["format_version"] == 1
        assert h5.attrs["shard"] == ""
        assert list(h5.attrs["swept_keys"]) == ["soil.table2_G", "contact.pure_rolling"]
        assert list(h5["case"][:]) == list(range(8))
        assert list(h5["results"].attrs["columns"]) == [split_label(h)[0] for h in header[1:]]
        for c, label in enumerate(header[1:], start=1):
            name, unit = split_label(label)
            ds = h5["results"][name]
            assert ds.attrs["unit"] == unit, name
            for r, row in enumerate(rows):
                cell = row[c]
                if ds.dtype.kind == "O":
                    assert ds.asstr()[r] == cell, (name, r)
                elif cell in ("", "nan"):  # no metric (empty) or a ratio to an absent harmonic
                    assert math.isnan(ds[r]), (name, r)
                else:
                    assert ds[r] == float(cell), (name, r)  # exact: shortest round-trip text
        # Every parameter of every case, with its unit: the swept ones vary as the CSV says.
        G = h5["parameters/soil.G"]
        assert G.attrs["unit"] == "Pa"
        assert list(G[:]) == [5e6, 5e6, 25e6, 25e6, 45e6, 45e6, 70e6, 70e6]
        assert list(h5["parameters/contact.pure_rolling"][:]) == [0, 1] * 4
        assert h5["parameters/roller.f"].attrs["unit"] == "Hz"
        assert list(h5["parameters/soil.input"].attrs["choices"]) == ["coefficients", "modulus", "table2"]
        assert (h5["parameters/roller.m"][:] == 1851).all()


def test_steady_states_equal_the_case_csvs(study):
    with h5py.File(study / "all.h5", "r") as h5:
        group = h5["steady_state"]
        assert len(group) == 8
        columns = list(group.attrs["columns"])
        for i in range(8):
            g = group[f"{i:06d}"]
            assert g.attrs["case"] == i
            assert g.attrs["status"] == "steady_state"
            assert g.attrs["frequency"] == 39.0
            table = np.genfromtxt(study / "cases" / f"case_{i:04d}.csv", delimiter=",",
                                  names=True)
            assert len(table) == g.attrs["sample_periods"] * g.attrs["samples_per_period"]
            with open(study / "cases" / f"case_{i:04d}.csv") as f:
                labels = f.readline().strip().split(",")
            for label, column in zip(labels, columns):
                name, unit = split_label(label)
                assert name == column
                assert g[name].attrs["unit"] == unit
                values = table[table.dtype.names[labels.index(label)]]
                assert np.array_equal(g[name][:], values), (i, name)  # %.17g: exact


def compare(a, b, path=""):
    assert sorted(a.keys()) == sorted(b.keys()), path
    for key in a:
        x, y = a[key], b[key]
        assert dict(x.attrs).keys() == dict(y.attrs).keys(), path + key
        for att in x.attrs:
            if att in ("REFERENCE_LIST", "DIMENSION_LIST"):
                continue  # object references: addresses in their own file (compared by name below)
            assert np.all(x.attrs[att] == y.attrs[att]), (path + key, att)
        if isinstance(x, h5py.Dataset) and x.ndim == 1:
            assert [list(d.keys()) for d in x.dims] == [list(d.keys()) for d in y.dims], path + key
        if isinstance(x, h5py.Group):
            compare(x, y, f"{path}/{key}")
        else:
            assert x.dtype == y.dtype, path + key
            u, v = x[()], y[()]
            if u.dtype.kind == "f":
                assert np.array_equal(u, v, equal_nan=True), path + key
            else:
                assert np.array_equal(u, v), path + key


def test_merged_hdf5_shards_equal_the_unsharded_file(cli, study):
    shards = []
    for i in (1, 2, 3):
        path = study / f"s{i}.h5"
        sweep(cli, study / "study.toml", "--shard", f"{i}/3", "--hdf5", path, "--format", "none")
        shards.append(path)
    with h5py.File(shards[1], "r") as h5:
        assert h5.attrs["shard"] == "2/3"
        assert list(h5["case"][:]) == [1, 4, 7]
    merged = study / "merged.h5"
    done = subprocess.run([cli, "merge", shards[2], shards[0], shards[1], "--out", merged],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with h5py.File(study / "all.h5", "r") as a, h5py.File(merged, "r") as b:
        for att in a.attrs:
            assert np.all(a.attrs[att] == b.attrs[att]), att
        compare(a, b)
    # A missing shard is refused, as for CSV shards.
    done = subprocess.run([cli, "merge", shards[0], shards[1], "--out", study / "bad.h5"],
                          capture_output=True, text=True)
    assert done.returncode == 2
    assert "1 of 3 shards missing: 3" in done.stderr
    assert not (study / "bad.h5").exists()
    # An HDF5 study named .csv (it was written so, exit 0): refused.
    done = subprocess.run([cli, "merge", *shards, "--out", study / "m.csv"],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "name it FILE.h5" in done.stderr, done.stderr
    assert not (study / "m.csv").exists()


def test_hdf5_tables_have_the_named_dimension_case(tmp_path):
    # netCDF-4 readers see /case as the dimension of /parameters and /results (dimension scales).
    xr = pytest.importorskip("xarray")
    study = tmp_path / "s.toml"
    study.write_text('[sweep]\n"contact.mu" = [0.3, 0.5, 0.7]\n')
    out = tmp_path / "s.h5"
    cli = os.environ.get("OSCIDRUM_CLI")
    if not cli:
        pytest.skip("the oscidrum CLI is not built")
    done = subprocess.run([cli, "sweep", str(study), "--out", str(tmp_path / "s.csv"), "--hdf5",
                           str(out), "-q"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with h5py.File(out, "r") as h5:
        assert [list(d.keys()) for d in h5["results/area"].dims] == [["case"]]
    ds = xr.open_dataset(out, group="results")
    assert "case" in ds.dims and ds.sizes["case"] == 3
    assert ds["area"].dims == ("case",)
    # ... and `case` its coordinate, in both tables (it had none: the scale was in the root only).
    assert list(ds["case"].values) == [0, 1, 2] and "case" in ds.coords
    assert "case" in xr.open_dataset(out, group="parameters").coords
    # Each case's steady state: the dimension t, with t its coordinate; merged shards too.
    with h5py.File(out, "r") as h5:
        group = "steady_state/" + sorted(h5["steady_state"].keys())[1]
        assert [list(d.keys()) for d in h5[group + "/ddx_M"].dims] == [["t"]]
    st = xr.open_dataset(out, group=group)
    assert list(st.sizes) == ["t"] and st["ddx_M"].dims == ("t",) and "t" in st.coords
    assert np.array_equal(st["t"].values, h5py.File(out, "r")[group + "/t"][:])
    shards = []
    for i in (1, 2):
        path = tmp_path / f"s{i}.h5"
        done = subprocess.run([cli, "sweep", str(study), "--shard", f"{i}/2", "--out",
                               str(tmp_path / f"s{i}.csv"), "--hdf5", str(path), "-q"],
                              capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        shards.append(str(path))
    merged = tmp_path / "merged.h5"
    done = subprocess.run([cli, "merge", *shards, "--out", str(merged)], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    # A shard's tables select by case index, not by row position (shard 2 holds case 1 alone).
    two = xr.open_dataset(shards[1], group="results")
    assert list(two["case"].values) == [1]
    # (the same case within the continuation's accuracy; mu 0.3, 0.5, 0.7 differ by far more)
    assert float(two.sel(case=1)["area"]) == pytest.approx(float(ds.sel(case=1)["area"]), rel=1e-7)
    assert abs(float(ds.sel(case=2)["area"]) / float(ds.sel(case=1)["area"]) - 1) > 1e-3
    whole = xr.open_dataset(merged, group="results")
    assert list(whole["case"].values) == [0, 1, 2] and "case" in whole.coords
    for k in range(3):
        with h5py.File(merged, "r") as h5:
            name = sorted(h5["steady_state"].keys())[k]
        st = xr.open_dataset(merged, group="steady_state/" + name)
        assert st["ddz_M"].dims == ("t",) and "t" in st.coords


def test_continue_hdf5_holds_the_branches_of_the_csv_with_units(cli, tmp_path):
    """`oscidrum continue --hdf5`: every branch (the period-2 one born at the doubling on the
    log-spiral trough too) with its points, multipliers, metrics and bifurcations, as the CSVs
    have them (docs/bifurcations.md, "Outputs")."""
    done = subprocess.run(
        [cli, "continue", "--param", "soil.G", "--from", "120", "--to", "130",
         "--set", "soil.input=modulus", "--set", "trough.k=0.002", "--set", "trough.a=0.601",
         "--set", "contact.mu=0.7", "--set", "roller.f=25", "--set", "roller.unbalance=0.22877",
         "--csv", str(tmp_path / "b.csv"), "--bifurcations", str(tmp_path / "bif.csv"),
         "--hdf5", str(tmp_path / "b.h5"), "--format", "none", "--quiet"],
        capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(tmp_path / "b.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    with open(tmp_path / "bif.csv", newline="") as f:
        bifs = list(csv.DictReader(f))
    with h5py.File(tmp_path / "b.h5", "r") as h5:
        assert h5.attrs["format"] == "oscidrum-branch" and h5.attrs["format_version"] == 1
        assert h5.attrs["key"] == "soil.G" and h5.attrs["unit"] == "Pa"
        assert h5.attrs["n_branches"] == 2 == len(h5["branches"])
        for index, g in h5["branches"].items():
            mine = [r for r in rows if r["branch[-]"] == index]
            assert len(g["parameter"]) == len(mine) > 2
            assert g["parameter"].attrs["unit"] == "Pa"
            assert g["metrics"]["area"].attrs["unit"] == "m^2/s^4"
            assert g["min_N"].attrs["unit"] == "N"
            np.testing.assert_allclose(g["parameter"][:],
                                       [float(r["soil.G[Pa]"]) for r in mine], rtol=1e-12)
            np.testing.assert_allclose(g["metrics"]["ddx_max"][:],
                                       [float(r["ddx_max[m/s^2]"]) for r in mine], rtol=1e-12)
            h = g["metrics"]["ddz_harmonics"]  # points x H: the amplitudes A_1 ... A_10
            assert h.shape == (len(mine), 10) and h.attrs["unit"] == "m/s^2"
            np.testing.assert_allclose(h[:, 1], [float(r["ddz_A2[m/s^2]"]) for r in mine],
                                       rtol=1e-12)
            assert g["multipliers_re"].shape[0] == len(mine)
            np.testing.assert_allclose(g["multipliers_re"][:, 0],
                                       [float(r["mu1_re[-]"]) for r in mine], rtol=1e-12)
            assert [s.decode() for s in g["sequence"][:]] == [r["sequence[-]"] for r in mine]
            assert g.attrs["end"] == "reached_end"
        root, child = h5["branches"]["0"], h5["branches"]["1"]
        assert child.attrs["multiplicity"] == 2 and child.attrs["parent"] == 0
        kinds = [k.decode() for k in root["bifurcations"]["kind"][:]]
        assert kinds == [b["kind[-]"] for b in bifs if b["branch[-]"] == "0"]
        assert "period_doubling" in kinds
        k = kinds.index("period_doubling")
        assert root["bifurcations"]["child_branch"][k] == 1
        assert abs(root["bifurcations"]["parameter"][k] - 125.004e6) < 0.01e6
        assert root["bifurcations"]["parameter"].attrs["unit"] == "Pa"


def test_hdf5_parameters_without_effect_are_nan_and_derived_holds_what_was_used(cli, tmp_path):
    """/parameters wrote each key's default where the case does not read it (soil.ksh under
    Table 2: 41.4e6 for every G; roller.M0 beside roller.unbalance), as if the run had used it.
    Those are NaN now, and /derived holds the soil coefficients and the moment the model used."""
    study = tmp_path / "s.toml"
    study.write_text('[roller]\nunbalance = 0.22877\nf = 25.0\n'
                     '[sweep]\n"soil.table2_G" = [5e6, 25e6]\n')
    out = tmp_path / "s.h5"
    done = subprocess.run([cli, "sweep", str(study), "--out", str(tmp_path / "s.csv"),
                           "--hdf5", str(out), "-q"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with h5py.File(out, "r") as h5:
        assert np.isnan(h5["parameters/soil.ksh"][:]).all()
        assert np.isnan(h5["parameters/roller.M0"][:]).all()
        assert list(h5["parameters/soil.G"][:]) == [5e6, 25e6]
        assert list(h5["derived/ksh"][:]) == [11.4e6, 41.4e6]  # paper Table 2
        assert h5["derived/ksh"].attrs["unit"] == "N/m"
        M0 = 4 * 0.22877 * (2 * np.pi * 25.0) ** 2  # (5)
        np.testing.assert_allclose(h5["derived/M0"][:], [M0, M0], rtol=1e-12)
    xr = pytest.importorskip("xarray")
    assert "case" in xr.open_dataset(out, group="derived").coords
