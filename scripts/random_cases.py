"""The random plausible cases of the scans (scripts/aperiodic_scan.py, scripts/contact_lost_scan.py):
the paper's roller with its unbalance (M0 follows f^2) on Appendix B soil, drawn from one random
stream so that a scan with the same seed draws the same cases."""

import numpy as np

import oscidrum

UNBALANCE = 0.22877  # the paper's m_u e_u e_w [kg m^2]


def draw_case(rng: np.random.Generator, mmd_max_fraction: float) -> oscidrum.Case:
    """G 5-100 MN/m^2 (Appendix B), f 25-70 Hz with the paper's unbalance, pure rolling (one case
    in four) or mu 0.2-1.0, MMd 0 ... mmd_max_fraction M0. The trough is the caller's to draw
    (next from the same stream)."""
    c = oscidrum.Case()
    c.set("soil.input", "modulus")
    c.set("soil.G", rng.uniform(5e6, 100e6))
    f = rng.uniform(25.0, 70.0)
    c.set("roller.f", f)
    c.set("roller.unbalance", UNBALANCE)
    if rng.uniform() < 0.25:
        c.set("contact.pure_rolling", True)
    else:
        c.set("contact.mu", rng.uniform(0.2, 1.0))
    c.set("MMd", rng.uniform(0.0, mmd_max_fraction) * 4 * UNBALANCE * (2 * np.pi * f) ** 2)
    return c
