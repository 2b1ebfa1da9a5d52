"""Branches and diagrams from Python: the keys they take."""

import oscidrum


def test_branch_and_diagram_take_the_flat_names():
    # "mu" was refused as an unknown key, though python.md gives every field its flat name.
    b = oscidrum.continue_branch(oscidrum.Case(), "mu", 0.5, 0.55, metrics=False)
    assert b["key"] == "contact.mu" and b["end"] == "reached_end"
    d = oscidrum.bifurcation_diagram(oscidrum.Case(), "mu", 0.5, 0.55, steps=1, discard=20,
                                     periods=20)
    assert d["key"] == "contact.mu"
