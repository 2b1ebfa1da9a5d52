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

}  // namespace oscidrum::test
