"""Branches and diagrams from Python: the keys they take."""

import oscidrum


def test_branch_and_diagram_take_the_flat_names():
    # "mu" was refused as an unknown key, though python.md gives every field its flat name.
    b = oscidrum.continue_branch(oscidrum.Case(), "mu", 0.5, 0.55, metrics=False)
    assert b["key"] == "contact.mu" and b["end"] == "reached_end"
    d = oscidrum.bifurcation_diagram(oscidrum.Case(), "mu", 0.5, 0.55, steps=1, discard=20,
                                     periods=20)
    assert d["key"] == "contact.mu"


def test_mmd_fraction_follows_the_varied_m0():
    # A Case keeps the MMd its MMd_fraction gave; MMd_fraction= makes it follow M0 at every point.
    case = oscidrum.Case(MMd_fraction=0.05)
    b = oscidrum.continue_branch(case, "roller.M0", 40000.0, 60000.0, MMd_fraction=0.05)
    assert b["end"] == "reached_end"
    c40 = oscidrum.Case(M0=40000.0, MMd=2000.0)
    m = oscidrum.compute_metrics(oscidrum.simulate(c40), case=c40)
    assert abs(b["points"]["area"][0] - m.area) < 1e-6 * m.area
    fixed = oscidrum.continue_branch(case, "roller.M0", 40000.0, 60000.0)
    assert abs(fixed["points"]["area"][0] - m.area) > 0.1 * m.area
    d = oscidrum.bifurcation_diagram(oscidrum.Case(), "roller.M0", 40000.0, 60000.0, steps=1,
                                     discard=20, periods=20, MMd_fraction=0.05)
    assert list(d["values"]["parameter"]) == [40000.0, 60000.0]
