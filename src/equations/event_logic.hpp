// Internal: the decisions taken at stick/slip events (docs/model.md section 6).
#pragma once

#include "oscidrum/model.hpp"

namespace oscidrum {

/// d(mu_static N - |T|)/dt under the stick-phase dynamics (30)-(32) at state q, where sign_T is the
/// sign of T to use for |T| (at a slip end T = -s mu N, so sign_T = -s) [N/s]. N and T are the
/// soil forces (24)-(26), differentiated along the stick solution.
double stick_margin_rate(const Model& model, double t, const State& q, int sign_T);

/// What happens when stick ends with slip of sign s.
struct SlipStart {
  bool consistent = true;  ///< false: no velocity jump gives slip of sign s (none is applied)
  State state;             ///< the state slip starts from
};

/// With one coefficient, T is continuous and the state carries over. With mu_static > mu, T
/// drops from mu_static N to mu N at once: the soil's velocities jump along (1, -f1, -f3) of
/// (delta', x_A', s_A') (the drum's velocities x_M', z_M', phi' are continuous) so that the slip
/// coupling (39) holds with the kinetic coefficient.
SlipStart decide_slip_start(const Model& model, const State& q, int s);

/// What happens when v_rel returns to zero at the end of a slip phase with sign s.
struct SlipEnd {
  bool stick = true;       ///< true: stick resumes; false: slip reverses to -s
  bool consistent = true;  ///< false: neither stick nor the reversal is consistent (stick taken)
  State state;             ///< state to continue from (velocities adjusted for a reversal)
};

/// Decide by the rate (docs/model.md section 6): stick if the stick solution stays inside the
/// friction cone (stick_margin_rate >= 0). Otherwise slip reverses: the velocities change along the
/// direction that keeps x_M', z_M' and phi' continuous, (delta', x_A', s_A') += lambda (1, -f1,
/// -f3), so that the coupling (39) holds with the new sign; the reversal is taken only if the
/// resulting v_rel has the new sign.
SlipEnd decide_slip_end(const Model& model, double t, const State& q, int s);

}  // namespace oscidrum
