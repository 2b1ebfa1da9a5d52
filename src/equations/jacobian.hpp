// Internal: the first-order right-hand side of each contact phase as the flow integrates it, its
// Jacobian with respect to the state, the gradients of the event functions, the jump maps at
// slip ends and the saltation matrices that carry the variational equations through a switch
// (docs/periodic.md).
//
// The state vector is y = (delta, x_A, s_A, phi, delta', x_A', s_A', phi') (54). In stick the
// flow integrates phi' = f5 delta' (12) for phi, and phi'' = f5 delta'' + f6 delta'^2.
#pragma once

#include <Eigen/Core>

#include "equations/saltation.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum::detail {

using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;

Vec8 to_vec8(const State& q);
State to_state(const Vec8& y);

/// y' = f(t, y) of `phase` ((52) in stick, (55) in slip with s = phase).
Vec8 phase_rhs(const Model& model, double t, const State& q, Phase phase, double baumgarte);

/// d f / d y of phase_rhs, analytic. The accelerations solve A(y) a = b(t, y), so
/// d a / d y = -A^-1 d(A a - b)/d y at fixed a; the partial derivatives of the balance rows
/// (30)-(32) or (34), (38), (53) (with its Baumgarte term), (36) are coded term by term.
Mat8 phase_jacobian(const Model& model, double t, const State& q, Phase phase, double baumgarte);

/// The event functions of the hybrid flow (all depend on the state only, d h / d t = 0).
enum class EventFunction {
  stick_limit_negative,  ///< mu_static N - T: zero when stick ends into slip- (T > 0)
  stick_limit_positive,  ///< mu_static N + T: zero when stick ends into slip+ (T < 0)
  slip_velocity,         ///< v_rel (13): zero when a slip phase ends
  normal_force,          ///< N (26): zero when contact would be lost
};
double event_value(const Model& model, const State& q, EventFunction h);
/// Gradient of event_value with respect to y.
Vec8 event_gradient(const Model& model, const State& q, EventFunction h);

/// The jump maps of the switches (src/equations/event_logic.cpp): at a slip end phi' is set to
/// f5 delta' (12) (`reset_phi`); at a reversal to s, and at a slip start with mu_static > mu, the
/// soil's velocities jump, (delta', x_A', s_A') += lambda (1, -f1, -f3), so that (39) holds with
/// sign `coupling_sign` and the kinetic mu (0: no such jump). jump_map returns g(y),
/// jump_jacobian G = d g / d y.
State jump_map(const Model& model, const State& q, bool reset_phi, int coupling_sign);
Mat8 jump_jacobian(const Model& model, const State& q, bool reset_phi, int coupling_sign);

/// Saltation matrix S = G + (f+ - G f-) dh^T / (dh . f- + dh/dt) of the drum's 8 components
/// (saltation_matrix, src/equations/saltation.hpp).
using Saltation = SaltationMatrix<8>;
inline Saltation saltation(const Mat8& G, const Vec8& f_minus, const Vec8& f_plus, const Vec8& dh,
                           double dh_dt = 0.0, double grazing_tol = 1e-9) {
  return saltation_matrix<8>(G, f_minus, f_plus, dh, dh_dt, grazing_tol);
}

/// The saltation matrix of a switch of the hybrid flow at state q (the state before the switch,
/// on the surface) and time t, from phase `from` to phase `to`. `jumped`: the soil's velocities
/// jumped at the switch (a reversal, or a slip start with mu_static > mu; the flow reports the
/// state after the switch, see FlowObserver::on_event).
Saltation switch_saltation(const Model& model, double t, const State& q, Phase from, Phase to,
                           double baumgarte, bool jumped, double grazing_tol = 1e-9);

}  // namespace oscidrum::detail
