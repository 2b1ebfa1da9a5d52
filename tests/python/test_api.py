"""The natural API: flat keywords, the config files' rules in Python (issue 14 item 4),
eval-able reprs, strict types, oscidrum.Error for every bad call, load_case, pickling."""

import pickle

import numpy as np
import pytest

import oscidrum
from oscidrum import (Case, Contact, Numerics, Roller, Soil, Status, Trough,  # noqa: F401
                      SoilInput)


def test_flat_keywords_and_shorthands():
    c = Case(table2_G=5e6, mu=0.3, MMd_fraction=0.05, R=0.62)
    assert c.soil == oscidrum.table2_soil(5e6) and c.soil.G == 5e6
    assert c.contact.mu == 0.3 and c.MMd == 0.05 * c.roller.M0
    assert (c.trough.k, c.trough.a) == (0.0, 0.62)
    d = Case(input="modulus", G=30e6, nu=0.35, m=2000.0, max_periods=100, pure_rolling=True)
    assert (d.soil.G, d.soil.nu, d.roller.m, d.numerics.max_periods) == (30e6, 0.35, 2000.0, 100)
    assert d.contact.pure_rolling is True
    # every field whose last component is unique has its flat name, generated from the table
    aliases = Case.aliases()
    for f in oscidrum.fields():
        last = f.key.rsplit(".", 1)[-1]
        assert aliases.get(last) == f.key
    assert aliases["table2_G"] == "soil.table2_G" and aliases["MMd_fraction"] == "MMd_fraction"
    # the same through set/get/replace/from_dict
    e = Case()
    e.set("mu", 0.2)
    assert e.get("contact.mu") == e.get("mu") == 0.2
    assert e.replace(kd=1e6).roller.kd == 1e6 and Case.from_dict({"mu": 0.1}).contact.mu == 0.1


def test_R_is_a_circular_trough_only():
    assert Case(k=0.1, a=0.62).trough.k == 0.1
    with pytest.raises(oscidrum.Error, match="either as a circle"):
        Case(R=0.62, k=0.1)


@pytest.mark.parametrize("call", [
    lambda: Case(soil={"nu": 0.35}),
    lambda: Case(input="coefficients").set("soil.G", 5e6),
    lambda: Case(input="coefficients", G=25e6),
    lambda: Soil(nu=0.3),
    lambda: Case(input="modulus", ksh=1e7),
    lambda: Case(table2_G=30e6, rho=1800.0),
])
def test_soil_keys_without_effect_are_errors_naming_soil_input(call):
    with pytest.raises(oscidrum.Error, match=r"has no effect while soil\.input") as info:
        call()
    assert info.value.key.startswith("soil.")  # the error carries the key


def test_soil_rule_is_the_config_files(cli, tmp_path):
    """The CLI rejects the same soil key by the same rule and words."""
    import subprocess
    (tmp_path / "c.toml").write_text("[soil]\nnu = 0.35\n")
    p = subprocess.run([cli, "run", str(tmp_path / "c.toml")], capture_output=True, text=True)
    assert p.returncode == 2
    with pytest.raises(oscidrum.Error) as info:
        Case(soil={"nu": 0.35})
    rule = str(info.value).split(": ", 1)[1]
    assert rule in p.stderr
    with pytest.raises(oscidrum.Error, match=r"c\.toml:2:\d+: soil\.nu has no effect"):
        oscidrum.load_case(tmp_path / "c.toml")


def test_G_has_one_meaning_in_python_and_on_the_command_line(cli):
    """Issue 25, point 8: the CLI's --G 30 (MN/m^2) and Case(G=30e6) (Pa) are the same soil, the
    Table 2 row at 30 MN/m^2 (the default soil input is Table 2); values plainly in the wrong
    unit are refused with what was meant."""
    import json
    import subprocess
    case = Case(G=30e6)
    assert case.soil.input == "table2" and case == Case(table2_G=30e6)
    p = subprocess.run([cli, "run", "--G", "30", "--format", "json"], capture_output=True,
                       text=True, check=True)
    soil = json.loads(p.stdout)["soil"]
    model = oscidrum.Model(case)
    assert soil["source"] == "table2" and soil["G"] == 30e6
    assert (soil["ksh"], soil["ksv"], soil["csh"], soil["csv"]) == (model.ksh, model.ksv,
                                                                    model.csh, model.csv)
    with pytest.raises(oscidrum.Error, match=r"soil\.G must be a G of paper Table 2") as info:
        Case(G=27e6)
    assert info.value.key == "soil.G" and info.value.value == 27e6
    assert Case(input="modulus", G=27e6).soil.G == 27e6  # any G through Appendix B
    with pytest.raises(oscidrum.Error, match=r"did you mean 3e\+07, i\.e\. 30 MN/m\^2\?"):
        Case(G=30)
    p = subprocess.run([cli, "run", "--G", "30000000"], capture_output=True, text=True)
    assert p.returncode == 2 and "did you mean --G 30?" in p.stderr


@pytest.mark.parametrize("kwargs", [
    {"roller.r": 0.6, "r": 0.7},
    {"soil": {"nu": 0.3}, "nu": 0.35, "input": "modulus"},
    {"table2_G": 30e6, "G": 40e6},
])
def test_a_key_given_twice_is_refused(kwargs):
    """Issue 24, point 11: Case(**{'roller.r': 0.6, 'r': 0.7}) took 0.7 silently."""
    with pytest.raises(oscidrum.Error, match=r"is given twice, as '.*' and as '.*'; give it once"):
        Case(**kwargs)


def test_table2_G_then_soil_G_moves_to_that_row():
    """docs/config.md: a later soil.G keeps the Table 2 choice (issue 24, point 11)."""
    c = Case(table2_G=30e6)
    c.set("soil.G", 40e6)
    assert c == Case(table2_G=40e6) and c.soil.input == "table2"
    assert oscidrum.Model(c).ksh == oscidrum.table2_soil(40e6).ksh


def test_setting_soil_modulus_after_switching_input():
    c = Case()
    c.soil.input = "modulus"
    c.soil.G = 5e6
    assert c.soil.G == 5e6 and c == Case(input="modulus", G=5e6)
    c.soil = {"table2_G": 10e6}
    assert c.soil == oscidrum.table2_soil(10e6)


@pytest.mark.parametrize("kwargs, message", [
    ({"m": "1851"}, r"roller\.m must be a number \[kg\]; got a string"),
    ({"pure_rolling": "off"}, "contact.pure_rolling must be true or false"),
    ({"pure_rolling": "no"}, "contact.pure_rolling must be true or false"),
    ({"pure_rolling": 1}, "contact.pure_rolling must be true or false; got an integer"),
    ({"max_periods": True}, "numerics.max_periods must be an integer; got a boolean"),
    ({"max_periods": 2.5}, "numerics.max_periods must be an integer"),
    ({"max_periods": 2 ** 70}, "numerics.max_periods must be an integer in"),
    ({"m": None}, r"roller\.m must be a number \[kg\]; got NoneType"),
    ({"m": [1.0]}, r"roller\.m must be a number \[kg\]; got list"),
    ({"input": 1}, "soil.input must be one of coefficients, modulus"),
    ({"roller": 3}, "roller must be a Roller or a dict"),
    ({"mx": 1.0}, "unknown parameter 'mx'"),
])
def test_strict_types(kwargs, message):
    with pytest.raises(oscidrum.Error, match=message):
        Case(**kwargs)


@pytest.mark.parametrize("kwargs, key", [
    ({"m": None}, "roller.m"), ({"m": [1.0]}, "roller.m"), ({"m": "1851"}, "roller.m"),
    ({"pure_rolling": "off"}, "contact.pure_rolling"), ({"max_periods": 2.5}, "numerics.max_periods"),
])
def test_a_value_of_the_wrong_type_names_its_key(kwargs, key):
    # Error.key was None for a value that is no number (Case(m=None)), though the message named it.
    with pytest.raises(oscidrum.Error) as e:
        Case(**kwargs)
    assert e.value.key == key


def test_numpy_scalars_are_numbers():
    c = Case(m=np.float64(2000.0), max_periods=np.int64(100), pure_rolling=np.bool_(True))
    assert (c.roller.m, c.numerics.max_periods, c.contact.pure_rolling) == (2000.0, 100, True)
    assert Case(input=SoilInput.modulus).soil.input == "modulus"


@pytest.mark.parametrize("call, message", [
    (lambda: oscidrum.run_study([1, 2]), r"cases\[0\] must be a Case"),
    (lambda: oscidrum.run_study(5), "cases must be a list"),
    (lambda: oscidrum.run_study([{"mu": -1}]), r"cases\[0\]: contact\.mu must be >= 0"),
    (lambda: oscidrum.run_study([Case()], threads=-1), "threads must be"),
    (lambda: oscidrum.simulate(42), r"simulate\(\): arguments must be"),
    (lambda: oscidrum.make_trough_geometry("a", 0, 1), "make_trough_geometry"),
    (lambda: oscidrum.make_trough_geometry(0.6, 0, 0.5), r"trough\.a must be > roller\.r"),
    (lambda: Status(99), r"Status must be one of steady_state \(0\)"),
    (lambda: Status(True), "Status must be one of"),
    (lambda: oscidrum.EventKind(7), "EventKind must be one of"),
    (lambda: Case().__setstate__("garbage"), "cannot restore a Case"),
    (lambda: Case().__setstate__({"soil.G": -1.0}), r"soil.G must be in \[10000, 1e\+11\]"),
    (lambda: Roller().__setstate__(None), "cannot restore a Roller"),
    (lambda: oscidrum.CaseOutcome.not_run().__setstate__(b"x"), "cannot restore a CaseOutcome"),
    (lambda: oscidrum.load_case(3), "path must be a str"),
    (lambda: oscidrum.load_case("/nonexistent.toml"), "cannot read"),
    (lambda: Case().get(3), r"get\(\): arguments must be"),
    (lambda: setattr(Case(), "roller", 3), "roller must be a Roller"),
])
def test_bad_calls_raise_oscidrum_error(call, message):
    with pytest.raises(oscidrum.Error, match=message) as info:
        call()
    assert isinstance(info.value, ValueError)


def test_a_bad_argument_beside_arrays_reads_as_one_signature():
    # A numpy array's printout in "Invoked with:" has lines that start with digits; they were
    # taken for numbered signatures ("... or 98999500e-01, 9.99499750e-01, ...").
    t = np.linspace(0.0, 1.0, 2000)
    x = np.sin(2 * np.pi * 39 * t)
    with pytest.raises(oscidrum.Error) as info:
        oscidrum.analyze_record(t, x, x, 39.0, n_max=2.5)
    text = str(info.value)
    assert "n_max: int" in text and " or " not in text.split("; got")[0]
    assert "e-01," not in text and "array(...)" in text and len(text) < 1000


def test_enums_accept_members_and_names():
    assert Status(3) == Status.chattering and Status("chattering") == Status.chattering


def test_new_without_init_is_a_default_value():
    for cls in (Roller, Soil, Trough, Contact, Numerics, Case):
        obj = cls.__new__(cls)
        assert obj == cls() and repr(obj) == cls.__name__ + "()"
    o = oscidrum.CaseOutcome.__new__(oscidrum.CaseOutcome)
    assert o.valid and o.metrics.area == 0.0
    r = oscidrum.Result.__new__(oscidrum.Result)  # a default Result, never uninitialised memory
    assert (r.frequency, len(r.samples), r.diagnostics.steps) == (0.0, 0, 0)
    assert oscidrum.Metrics.__new__(oscidrum.Metrics).area == 0.0
    with pytest.raises(oscidrum.Error, match="Result objects come from the library"):
        oscidrum.Result()


@pytest.mark.parametrize("case", [
    Case(),
    Case(table2_G=5e6, mu=0.3, MMd_fraction=0.05, R=0.62),
    Case(input="modulus", G=3e7, nu=0.25, k=0.1, a=0.62, pure_rolling=True, max_periods=100),
    Case(ksh=1.23456789e7, csv=2e5, m=1900.1, rtol=1e-9, suspension_from_static=True),
])
def test_repr_round_trips_through_eval(case):
    namespace = {name: getattr(oscidrum, name) for name in oscidrum.__all__}
    assert eval(repr(case), namespace) == case
    for group in (case.roller, case.soil, case.trough, case.contact, case.numerics):
        assert eval(repr(group), namespace) == group
    assert pickle.loads(pickle.dumps(case)) == case
    assert Case.from_dict(case.to_dict()) == case


def test_load_case_equals_the_cli(cli, root, tmp_path):
    import json
    import subprocess
    case = oscidrum.load_case(root / "examples" / "case.toml")
    out = tmp_path / "s.json"
    subprocess.run([cli, "run", str(root / "examples" / "case.toml"), "--json", str(out),
                    "--format", "csv"], check=True, capture_output=True)
    params = json.loads(out.read_text())
    text = json.dumps(params)
    assert str(case.trough.a) in text or repr(case.trough.a) in text
    assert oscidrum.load_case(tmp_path.joinpath("x.toml").write_text(
        oscidrum.case_to_toml(case)) and tmp_path / "x.toml") == case


def test_result_to_dataframe(rolling_result):
    df = rolling_result.to_dataframe()
    assert list(df.columns) == list(oscidrum.Samples.columns)
    assert len(df) == len(rolling_result.samples)
    np.testing.assert_array_equal(df["ddx_M"].to_numpy(), rolling_result.samples.ddx_M)
    assert df.attrs["units"]["ddx_M"] == "m/s^2" and df.attrs["units"]["t"] == "s"


def test_type_stubs_ship_with_the_package():
    import pathlib
    here = pathlib.Path(oscidrum.__file__).parent
    assert (here / "py.typed").exists()
    stub = (here / "__init__.pyi").read_text()
    for name in ("class Case", "run_study as run_study", "def load_case", "StudyResult",
                 "def to_dataframe"):
        assert name in stub, name
    compile(stub, "__init__.pyi", "exec")
    study = (here / "study.pyi").read_text()
    assert "def to_xarray" in study and "executor:" in study


def test_docstrings_are_numpydoc_and_their_examples_run():
    import doctest
    import inspect
    for obj in (oscidrum.Case, oscidrum.Case.get, oscidrum.Case.set, oscidrum.simulate,
                oscidrum.compute_metrics, oscidrum.table2_soil, oscidrum.load_case,
                oscidrum.run_study, oscidrum.StudyResult.to_dataframe,
                oscidrum.StudyResult.to_xarray, oscidrum.Result.to_dataframe):
        doc = inspect.cleandoc(obj.__doc__)
        assert "Examples\n--------" in doc, obj
        assert "Returns\n-------" in doc or "Parameters\n----------" in doc, obj
        finder = doctest.DocTestFinder(recurse=False)
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        for test in finder.find(obj, "oscidrum", globs={"oscidrum": oscidrum}):
            runner.run(test)
        assert runner.failures == 0, obj


def test_continue_branch_gives_the_branch_as_columns():
    import pandas as pd
    result = oscidrum.continue_branch(oscidrum.Case(), "MMd", 0.0, 14000.0, metrics=False)
    assert result["end"] == "gross_slip" and result["key"] == "MMd" and result["unit"] == "N m"
    points = pd.DataFrame(result["points"])
    assert len(points) == len(result["multipliers"]) > 10
    assert points["parameter"].iloc[0] == 0.0 and points["stable"].all()
    assert [b["kind"] for b in result["bifurcations"]] == ["grazing", "grazing"]
    with pytest.raises(oscidrum.Error, match="numerical setting"):
        oscidrum.continue_branch(oscidrum.Case(), "numerics.rtol", 1e-8, 1e-7)
    # The amplitudes A_1 ... A_harmonics of each spectrum, as the CSV's columns.
    short = oscidrum.continue_branch(oscidrum.Case(), "MMd", 0.0, 1000.0, harmonics=3)
    assert {"ddx_A1", "ddx_A3", "ddz_A3"} <= set(short["points"]) and "ddx_A4" not in short["points"]
    assert (short["points"]["ddx_A1"] > 1.0).all()


def test_bifurcation_diagram_gives_values_and_points_as_columns():
    import pandas as pd
    d = oscidrum.bifurcation_diagram(oscidrum.Case(), "MMd", 0.0, 2000.0, steps=1, sweep="both",
                                     discard=20, periods=20)
    assert d["key"] == "MMd" and d["unit"] == "N m"
    assert list(d["values"]["parameter"]) == [0.0, 2000.0, 2000.0, 0.0]
    assert list(d["values"]["direction"]) == [1, 1, -1, -1]
    assert d["values"]["verdict"] == ["periodic"] * 4 and list(d["values"]["period"]) == [1] * 4
    # Counts and signs are integers, flags booleans (they came back as floats: 1.0, -1.0).
    assert d["values"]["period"].dtype.kind == "i" and d["values"]["direction"].dtype.kind == "i"
    assert d["values"]["from_rest"].dtype == bool and d["values"]["shooting"].dtype == bool
    assert d["points"]["value"].dtype.kind == "i" and d["points"]["direction"].dtype.kind == "i"
    points = pd.DataFrame(d["points"])
    assert len(points) == 4 * 20 and {"ddx_M", "ddz_M", "x_A", "s_A", "delta"} <= set(points)
    # A period-1 orbit: every stroboscopic point of a value is the same.
    spread = points.groupby("value")["ddx_M"].agg(lambda v: v.max() - v.min())
    assert (spread < 1e-6 * points["ddx_M"].abs().max()).all()
    with pytest.raises(oscidrum.Error, match="sweep"):
        oscidrum.bifurcation_diagram(oscidrum.Case(), "MMd", 0.0, 1.0, sweep="sideways")


def test_analyze_motion_of_a_periodic_orbit():
    case = oscidrum.Case()
    result = oscidrum.simulate(case)
    motion = oscidrum.analyze_motion(case, result, periods=200)
    assert motion.kind == "periodic" and motion.recurrence == 1
    assert motion.section.shape == (201, 8)
    # The largest Lyapunov exponent of a periodic orbit: ln |mu_max| / T (to the estimate's
    # convergence over 200 periods, docs/bifurcations.md).
    expected = np.log(max(abs(m) for m in result.floquet_multipliers)) * case.roller.f
    assert abs(motion.lyapunov - expected) < 0.05 * abs(expected)


def test_without_the_compiled_core_the_plots_say_how_to_build_it(tmp_path):
    """The package's Python files alone (imported from a source tree, no build): the compiled
    names, oscidrum.data and oscidrum.plot raise ImportError saying how to build the core (data
    failed with AttributeError: 'NoneType' object has no attribute 'sample_columns')."""
    import shutil
    import subprocess
    import sys
    from pathlib import Path
    src = Path(oscidrum.__file__).resolve().parent
    pkg = tmp_path / "src" / "oscidrum"
    pkg.mkdir(parents=True)
    for f in src.glob("*.py"):
        shutil.copy(f, pkg / f.name)
    script = (
        "import sys\n"
        f"sys.path = [{str(tmp_path / 'src')!r}] + [p for p in sys.path if p.startswith('/usr/lib')]\n"
        "import oscidrum\n"
        "assert oscidrum._core is None, oscidrum._core\n"
        "for what in ('oscidrum.data', 'oscidrum.plot'):\n"
        "    try:\n"
        "        __import__(what)\n"
        "    except ImportError as e:\n"
        "        assert 'need the compiled module oscidrum._core' in str(e), e\n"
        "        assert 'cmake -DOSCIDRUM_BUILD_PYTHON=ON' in str(e), e\n"
        "    else:\n"
        "        raise AssertionError(what + ' imported without the core')\n"
        "try:\n"
        "    oscidrum.simulate\n"
        "except ImportError as e:\n"
        "    assert 'needs the compiled module' in str(e), e\n"
        "print('explained')\n")
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                       timeout=60, cwd=tmp_path)
    assert p.returncode == 0 and p.stdout.strip() == "explained", p.stdout + p.stderr
