// Internal: what a roller type supplies to the engine (docs/architecture.md, "The roller as a
// component"). The flow (src/flow/hybrid_flow.hpp), the variational equations
// (src/flow/monodromy.hpp), shooting (src/drivers/shooting.hpp), the transient steady-state search
// (src/drivers/steady_state.hpp), the sampling (src/drivers/sampling.hpp) and the continuation of
// branches (src/drivers/branch_continuation.hpp) are templates on a roller type R
// (oscidrum/roller.hpp) and use only the members of Dynamics<R> listed below. A new roller is a
// specialisation of Dynamics in its own files under src/roller/ and one line that instantiates
// the engine for it (src/roller/engine.cpp).
//
//   constants   kStates (the state's size), kEvents (event functions), kPeriodic (the components
//               that repeat on a periodic orbit: all but the cyclic ones, e.g. the drum angle),
//               kContactEvent (the event function of contact, N over a force scale, in every phase
//               with contact; -1 for none)
//   types       Vector = std::array<double, kStates>, Matrix (kStates x kStates, Eigen),
//               EventValues = std::array<double, kEvents>, Switch (below)
//   flow        rhs(phase, t, x, dxdt); events(phase, x, &N) (scaled to O(1), an event when one
//               falls through zero; N the normal force [N]); apply(phase, which, t, x) -> Switch
//               (what the event does: its kind, the new phase, the state after, the functions
//               that start at zero, a terminal stop); invalid(phase, x, t, &why, &stop) (a
//               state the equations are undefined at, and the stop it ends the run in);
//               track(phase, x, N, counters) (extremes at step ends);
//               initial_state(), initial_phase()
//   variational jacobian(phase, t, x); saltation(event, before, after)
//   shooting    consistent(z, phase) (the section state Newton sees: a projection onto the
//               phase's constraints) and section_jacobian(z, phase) (its Jacobian)
//   sampling    sample(t, x, phase, samples) (one row of the output columns); sampled_state(
//               samples, j) (the state of row j, for continuation)
//   search      gross_slip(...) (motion that cannot become periodic, see steady_state.hpp)
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "equations/saltation.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum::detail {

/// The dynamics of roller type R: specialised by each roller (src/roller/<roller>.hpp).
template <class R>
class Dynamics;

}  // namespace oscidrum::detail
