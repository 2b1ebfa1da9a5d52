// The cases the tests of branches and bifurcation diagrams share (docs/bifurcations.md).
#pragma once

#include "oscidrum/oscidrum.hpp"

namespace oscidrum::test {

/// The paper's roller on soil by Appendix B (soil.input = modulus: any G), by shooting.
inline Case modulus_case() {
  Case c;
  set_field_text(c, "soil.input", "modulus");
  c.numerics.method = SteadyMethod::shooting;
  return c;
}

/// The log-spiral study of docs/bifurcations.md: the paper's trough (k = 0.002, a = 0.601 m) at
/// 25 Hz with the unbalance and mu = 0.7, a period doubling at G = 125.0016 MN/m^2.
inline Case log_spiral_case() {
  Case c = modulus_case();
  set_field(c, "trough.k", 0.002);
  set_field(c, "trough.a", 0.601);
  set_field(c, "contact.mu", 0.7);
  set_field(c, "roller.f", 25.0);
  set_field(c, "roller.unbalance", 0.22877);
  return c;
}

/// The log-spiral study's case on stiff soil (G = 150 MN/m^2), past its period doubling: the
/// period-1 orbit has a multiplier -1.006 and the drum, sticking throughout, settles on a stable
/// period-2 orbit.
inline Case period_two_case() {
  Case c = log_spiral_case();
  set_field(c, "soil.G", 150e6);
  return c;
}

/// Pure rolling on contact that can open (docs/lift-off.md): the paper's roller with its unbalance
/// at f [Hz] on soil by Appendix B; at 58 Hz the study of docs/bifurcations.md with two
/// Neimark-Sacker points in G.
inline Case rolling_unilateral_case(double f = 58.0) {
  Case c = modulus_case();
  set_field_text(c, "contact.pure_rolling", "true");
  set_field_text(c, "contact.unilateral", "true");
  set_field(c, "roller.unbalance", 0.22877);
  set_field(c, "roller.f", f);
  return c;
}

/// The vibratory drum (circular exciter, static moment [kg m]) with contact that can open, mu =
/// 0.5, on soil by Appendix B at G [Pa]: the double jump and the subcritical period doublings of
/// docs/bifurcations.md's probes.
inline Case vibratory_lift_off_case(double static_moment, double G) {
  Case c = modulus_case();
  set_field_text(c, "roller.type", "vibratory");
  set_field(c, "roller.static_moment", static_moment);
  set_field(c, "contact.mu", 0.5);
  set_field_text(c, "contact.unilateral", "true");
  set_field(c, "soil.G", G);
  return c;
}

}  // namespace oscidrum::test
