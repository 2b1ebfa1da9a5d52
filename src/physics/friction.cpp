// Friction laws (oscidrum/friction.hpp).
#include "oscidrum/friction.hpp"

#include <limits>

namespace oscidrum {
namespace {

template <class... F>
struct overloaded : F... {
  using F::operator()...;
};
template <class... F>
overloaded(F...) -> overloaded<F...>;

}  // namespace

FrictionLaw friction_law(const Contact& contact) {
  if (contact.pure_rolling) return PureRolling{};
  if (contact.mu_static >= 0.0 && contact.mu_static != contact.mu)
    return StaticKineticFriction{contact.mu_static, contact.mu};
  return CoulombFriction{contact.mu};
}

double cone_coefficient(const FrictionLaw& law) {
  return std::visit(
      overloaded{[](const PureRolling&) { return std::numeric_limits<double>::infinity(); },
                 [](const CoulombFriction& f) { return f.mu; },
                 [](const StaticKineticFriction& f) { return f.mu_static; }},
      law);
}

double slip_coefficient(const FrictionLaw& law) {
  return std::visit(overloaded{[](const PureRolling&) { return 0.0; },
                               [](const CoulombFriction& f) { return f.mu; },
                               [](const StaticKineticFriction& f) { return f.mu_kinetic; }},
                    law);
}

}  // namespace oscidrum
