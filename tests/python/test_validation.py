"""Bindings of oscidrum/validation.hpp: the paper's series and cases, run_paper_studies, validate
and validation_markdown (the single definition of the paper's studies, src/validation.cpp)."""

import numpy as np
import pytest

import oscidrum

TABLE2_G = [row.G for row in oscidrum.table2()]


def test_paper_series():
    series = oscidrum.paper_series()
    ids = [s.id for s in series]
    assert len(set(ids)) == len(ids) >= 11
    for sid in ("rolling_MMd0_R0.603", "rolling_MMd0_R0.606", "rolling_MMd0_R0.620",
                "rolling_MMd0_R0.650", "rolling_MMd0.05_R0.606", "stickslip_MMd0_R0.606",
                "stickslip_MMd0.05_R0.606", "shape_circle_R0.603", "shape_spiral_k0.002_a0.601",
                "rolling_soft_limit", "free_drum"):
        assert sid in ids
    by_id = {s.id: s for s in series}
    s = by_id["stickslip_MMd0.05_R0.606"]
    assert (s.pure_rolling, s.MMd_fraction, s.k, s.a, s.mu) == (False, 0.05, 0.0, 0.606, 0.5)
    assert s.G == TABLE2_G and "stick-slip" in s.description
    spiral = by_id["shape_spiral_k0.002_a0.601"]
    assert (spiral.k, spiral.a, spiral.G) == (0.002, 0.601, [5e6])
    assert by_id["free_drum"].mu == 0.0
    assert "rolling_MMd0_R0.606" in repr(by_id["rolling_MMd0_R0.606"])
    with pytest.raises(AttributeError):
        s.mu = 0.3
    with pytest.raises(AttributeError):
        s.id = "mine"


def test_paper_case():
    M0 = oscidrum.Roller().M0
    for s in oscidrum.paper_series():
        for G in s.G:
            c = oscidrum.paper_case(s, G)
            assert c.contact.pure_rolling == s.pure_rolling
            assert c.contact.mu == s.mu
            assert c.MMd == pytest.approx(s.MMd_fraction * M0, rel=1e-15)
            assert (c.trough.k, c.trough.a) == (s.k, s.a)
            assert c.roller == oscidrum.Roller()
            if G in TABLE2_G:
                assert c.soil == oscidrum.table2_soil(G)
            else:  # the soft soils towards G -> 0: Appendix B
                assert c.get("soil.input") == "modulus" and c.soil.G == G
            c.validate()
    with pytest.raises(oscidrum.Error, match="arguments must be"):
        oscidrum.paper_case("rolling_MMd0_R0.606", 5e6)
    # G by the rule of soil.G, as Case takes it: these made a Case holding an invalid G.
    s = oscidrum.paper_series()[1]
    for G, message in [(float("nan"), r"finite and in \[10000, 1e\+11\] \[Pa\]; got nan"),
                       (-5e6, r"in \[10000, 1e\+11\] \[Pa\]; got -5e\+06"),
                       (True, r"a number \[Pa\]; got a boolean")]:
        with pytest.raises(oscidrum.Error, match=r"^soil\.G must be " + message):
            oscidrum.paper_case(s, G)


def test_run_paper_studies(paper_studies):
    results, calls, ticks = paper_studies
    series = oscidrum.paper_series()
    assert [r.series.id for r in results] == [s.id for s in series]
    total = sum(len(s.G) for s in series)
    for r in results:
        n = len(r.series.G)
        assert len(r) == n and len(r.metrics) == n and len(r.diagnostics) == n
        assert r.status == ["steady_state"] * n
        assert r.results == []  # keep_samples=False
        assert isinstance(r.metrics[0], oscidrum.Metrics)
        assert isinstance(r.diagnostics[0], oscidrum.Diagnostics)
        assert "steady" in repr(r)
    # progress: once per case, with the GIL (it ran Python), and the GIL was released meanwhile.
    assert len(calls) == total and all(t == total for _, t in calls)
    assert sorted(d for d, _ in calls) == list(range(1, total + 1))
    assert len(ticks) > 3


def test_run_paper_studies_equals_run_study(paper_studies):
    """A series' metrics are run_study's on the paper_case cases."""
    result = next(r for r in paper_studies[0] if r.series.id == "stickslip_MMd0.05_R0.606")
    G = [5e6, 45e6]
    outcomes = oscidrum.run_study([oscidrum.paper_case(result.series, g) for g in G])
    for g, o in zip(G, outcomes):
        m = result.metrics[result.series.G.index(g)]
        # The series is a chain of continuation (each G from its neighbour's steady state), these
        # two cases are not: Newton converges to the same orbit from either start (measured: 3e-12
        # relative at most), so 1e-8 leaves room for the step grids and no more.
        a, b = o.metrics.to_dict(), m.to_dict()
        assert a.keys() == b.keys()
        for k in a:
            np.testing.assert_allclose(a[k], b[k], rtol=1e-8, atol=1e-12, err_msg=k)


def test_progress_exception_is_reraised():
    def progress(done, total):
        raise RuntimeError("from progress")

    with pytest.raises(RuntimeError, match="from progress"):
        oscidrum.run_paper_studies(progress=progress)


def test_validate_rows(paper_rows):
    rows = paper_rows
    ids = [r.id for r in rows]
    assert len(set(ids)) == len(ids) >= 40
    checkable = [r for r in rows if r.checkable]
    assert all(r.agrees for r in checkable), [r.to_dict() for r in checkable if not r.agrees]
    assert [r.id for r in rows if not r.checkable] == ["fig23.field"]
    for r in rows:
        d = r.to_dict()
        assert list(d) == ["id", "figure", "claim", "paper", "oscidrum", "rule", "agrees",
                           "checkable", "note"]
        assert all(isinstance(d[k], str) for k in d if k not in ("agrees", "checkable"))
        assert r.figure and r.claim and r.paper and r.oscidrum and r.rule
        if not r.checkable or not r.agrees:
            assert r.note
        assert r.id in repr(r)
    row = next(r for r in rows if r.id == "fig9a.xmax_G5")
    assert row.figure == "Fig. 9a" and row.oscidrum.endswith("m/s^2")
    with pytest.raises(AttributeError):
        row.agrees = False


def test_validation_markdown(paper_rows):
    rows = paper_rows
    md = oscidrum.validation_markdown(rows)
    lines = md.splitlines()
    assert lines[0] == "| id | figure | claim | paper | oscidrum | rule | agrees? | note |"
    assert sum(1 for line in lines if line.startswith("| fig") or line.startswith("| all.")) \
        == len(rows)
    n = sum(r.checkable for r in rows)
    assert lines[-1] == (f"{n} of {n} checkable claims agree ({len(rows) - n} not checkable: "
                         "see the notes).")
    assert oscidrum.validation_markdown([]).splitlines()[-1] == "0 of 0 checkable claims agree."


def test_validate_errors(paper_studies):
    results = paper_studies[0]
    with pytest.raises(oscidrum.Error, match="free_drum"):
        oscidrum.validate(results[:-1])
    with pytest.raises(oscidrum.Error, match=r"^validate: results must be the SeriesResults of "
                       r"run_paper_studies\(\); results\[1\] is int \(5\)$"):
        oscidrum.validate([results[0], 5])  # a raw TypeError
    few = oscidrum.run_paper_studies(n_harmonics=1)
    with pytest.raises(oscidrum.Error, match="n_harmonics >= 2"):
        oscidrum.validate(few)
