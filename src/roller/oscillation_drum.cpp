// The oscillation drum as a roller component (src/roller/oscillation_drum.hpp): the flow's
// right-hand side, the event decisions, the checks at step ends, the saltation matrices, the
// section projection and the samples, on the equations of src/equations/.
#include "roller/oscillation_drum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "equations/equations.hpp"
#include "equations/event_logic.hpp"
#include "equations/phase_equations.hpp"
#include "util/format.hpp"
#include "util/lanes.hpp"

namespace oscidrum::detail {

void Dynamics<OscillationDrum>::rhs(Phase phase, double t, const Vector& x, Vector& dxdt) const {
  const State q = State::from_array(x);
  const Kinematics k = kinematics(model_.geometry(), q.delta);
  const Accelerations a =
      phase == Phase::stick
          ? detail::stick_accelerations(model_, t, q, k)
          : detail::slip_accelerations(model_, t, q, slip_sign(phase), baumgarte_, k);
  dxdt[0] = x[4];
  dxdt[1] = x[5];
  dxdt[2] = x[6];
  // (12): in stick phi' = f5 delta' exactly, so phi cannot drift from the rolling condition.
  dxdt[3] = phase == Phase::stick ? k.f5 * x[4] : x[7];
  dxdt[4] = a.delta;
  dxdt[5] = a.x_A;
  dxdt[6] = a.s_A;
  dxdt[7] = a.phi;
}

Dynamics<OscillationDrum>::Switch Dynamics<OscillationDrum>::apply(Phase phase, int which, double t,
                                                                   const Vector& x) const {
  Switch out;
  out.after = x;
  if (which == kEventContact) {  // N reached 0: lift-off is outside the model
    out.kind = EventKind::contact_lost;
    out.to = phase;
    out.terminal = true;
    out.stop = FlowStop::contact_lost;
    out.message = detail::format(
        "contact lost at t = %.9g s (N reached 0): the model assumes permanent "
        "contact and does not cover lift-off",
        t);
    return out;
  }
  const State q = State::from_array(x);
  if (phase == Phase::stick) {
    // The friction limit is reached: slip starts with s = -sign(T) (29). The negative-side
    // function (mu N - T) reaching zero means T > 0, hence slip-.
    out.to = (which == kEventConeNegative) ? Phase::slip_negative : Phase::slip_positive;
    out.kind = EventKind::stick_to_slip;
    const SlipStart start = decide_slip_start(model_, q, static_cast<int>(out.to));
    out.after = start.state.to_array();
    out.consistent = start.consistent;
    out.fresh[kEventSlipVelocity] = true;  // s v_rel starts at zero and must grow
    return out;
  }
  // v_rel = 0: stick resumes if the stick solution stays inside the friction cone, else slip
  // reverses (docs/model.md section 6).
  const SlipEnd decision = decide_slip_end(model_, t, q, static_cast<int>(phase));
  out.after = decision.state.to_array();
  if (decision.stick) {
    out.kind = EventKind::slip_to_stick;
    out.to = Phase::stick;
    // The cone function on the side of the old slip starts at zero: slip+ ended with
    // T = -mu N (mu N + T = 0), slip- with T = +mu N (mu N - T = 0).
    out.fresh[phase == Phase::slip_positive ? kEventConePositive : kEventConeNegative] = true;
    out.consistent = decision.consistent;
  } else {
    out.kind = EventKind::slip_reversal;
    out.to = (phase == Phase::slip_positive) ? Phase::slip_negative : Phase::slip_positive;
    out.reversal = true;
    out.fresh[kEventSlipVelocity] = true;
  }
  return out;
}

Dynamics<OscillationDrum>::Dynamics(const Model& model, double baumgarte)
    : model_(model), baumgarte_(baumgarte), f5_bottom_(kinematics(model.geometry(), 0.0).f5) {}

bool Dynamics<OscillationDrum>::invalid(Phase phase, const Vector& x, double t, std::string* why,
                                        FlowStop* stop) const {
  // The trough is a settlement depression, open above: a contact point (in flight: the trough's
  // point nearest to the drum, docs/model.md section 13) past its vertical tangent, |delta| >=
  // pi/2, would be soil overhanging the drum. The shapes' formulas hold all round (a circle's
  // point nearest to a drum that jumped almost to its centre can be anywhere on it: a landing
  // there orbited the drum round the circle, delta growing without bound), the model does not.
  if (!(std::abs(x[0]) < 0.5 * std::numbers::pi)) {
    *stop = FlowStop::contact_lost;
    *why = detail::format(
        "at t = %.9g s, delta = %.6g rad: the drum's point on the trough passed the trough's "
        "vertical tangent (|delta| >= pi/2), where the soil would overhang the drum; the trough "
        "is a depression open above, so the drum has left it, which the model does not follow",
        t, x[0]);
    return true;
  }
  const Kinematics k = kinematics(model_.geometry(), x[0]);
  // The accelerations grow as 1 / f5 as the trough's curvature radius shrinks to the drum's
  // (a log spiral's does with delta): the step size collapsed before f5 reached 0, and such runs
  // ended as budget_exceeded (blaming the step budget) or non_finite. As for the slip
  // determinant, a value 1e-3 of the bottom's is taken for the singularity itself.
  if (!(k.f5 > kSingularRolling * f5_bottom_)) {
    *stop = FlowStop::invalid_geometry;
    *why = detail::format(
        "at t = %.9g s, delta = %.6g rad, the trough's curvature radius fell "
        "to the drum radius (f5 = %.3g, %.3g of its value at the trough's bottom): rolling is "
        "undefined there (a trough whose curvature radius at the bottom is closer to the drum "
        "radius, or a steeper log spiral, reaches it at a smaller delta)",
        t, x[0], k.f5, k.f5 / f5_bottom_);
    return true;
  }
  if (phase == Phase::stick) return false;
  // In slip the accelerations grow as 1 / D (slip_determinant) and do not exist at D = 0: with
  // a large friction coefficient and the drum high on the trough's flank the massless soil's
  // slip equations have no solution (a Painleve-type singularity). Without this check the step
  // size shrinks towards D = 0 until the step budget runs out, with N diverging.
  const State q = State::from_array(x);
  const double m =
      slip_coefficient(model_.friction(), slip_sign(phase), detail::slip_velocity(model_, q, k)).m;
  const double D = detail::slip_determinant(model_, k, m);
  if (D > kSingularSlip) return false;
  *stop = FlowStop::contact_lost;
  *why = detail::format(
      "at t = %.9g s, delta = %.6g rad, the slip equations became singular (their determinant, "
      "checked at each step's end, is %.3g of its value at delta = 0: at or past its zero, the "
      "run stops at 1e-3; slip coefficient %.6g): the accelerations grow "
      "without bound and the soil cannot keep the drum in contact (a Painleve-type singularity "
      "of the massless soil with a large friction coefficient, docs/model.md section 6)",
      t, x[0], D, m);
  return true;
}

void Dynamics<OscillationDrum>::track(Phase phase, const Vector& x, double N,
                                      FlowCounters& counters) const {
  counters.min_N = std::min(counters.min_N, N);
  if (phase != Phase::stick && model_.cone() > 0.0) {
    const double residual =
        std::abs(slip_constraint_residual(model_, State::from_array(x), slip_sign(phase))) /
        model_.W();
    counters.max_slip_residual = std::max(counters.max_slip_residual, residual);
  }
}

SaltationMatrix<8> Dynamics<OscillationDrum>::saltation(const Event& event, const Vector& before,
                                                        const Vector& after) const {
  // The soil's velocities jumped (a reversal, or a slip start with mu_static > mu).
  const bool jumped = after[4] != before[4] || after[5] != before[5] || after[6] != before[6];
  const Saltation s = switch_saltation(model_, event.t, State::from_array(before), event.from,
                                       event.to, baumgarte_, jumped);
  return {s.S, s.grazing};
}

Dynamics<OscillationDrum>::Vector Dynamics<OscillationDrum>::consistent(Vector z,
                                                                        Phase phase) const {
  if (phase == Phase::stick) z[7] = kinematics(model_.geometry(), z[0]).f5 * z[4];
  return z;
}

std::optional<Dynamics<OscillationDrum>::Matrix> Dynamics<OscillationDrum>::section_jacobian(
    const Vector& z, Phase phase) const {
  if (phase != Phase::stick) return std::nullopt;
  return jump_jacobian(model_, State::from_array(z), true, 0);
}

namespace {

template <class T>
void append(std::vector<T>& column, const T* values, int count) {
  column.insert(column.end(), values, values + count);
}

// The samples at t[0 ... count-1] (count <= N) of states x in `phase`, in lanes of N
// (util/lanes.hpp): the kinematics, the moment and the load per point, the equations of
// equations/phase_equations.hpp for all points at once, the same bits as one point at a time.
template <int N>
void sample_lanes(const Model& model, double baumgarte, const double* t,
                  const Dynamics<OscillationDrum>::Vector* x, int count, Phase phase, Samples& s) {
  using L = Lanes<N>;
  StateOf<L> q;
  KinematicsOf<L> k;
  L MM, Lx, W, alpha;
  std::array<CentreLoad, N> load;
  model.excitation(t, count, MM.v.data(), alpha.v.data(), load.data());
  for (int j = 0; j < N; ++j) {
    const int i = std::min(j, count - 1);  // unused lanes repeat the last point
    set_lane(q, j, x[i]);
    // The moment (5), (6) (the accelerations' and the torque column's) and the load on M.
    if (j >= count) MM[j] = MM[count - 1];
    Lx[j] = load[static_cast<std::size_t>(i)].x;
    W[j] = load[static_cast<std::size_t>(i)].z;
  }
  // The kinematics (15)-(16), (46)-(50), (33), (37) of every point, in lanes where the shape has
  // them (physics/kinematics_lanes.hpp).
  if constexpr (N == kKinematicsLanes) {
    kinematics(model.geometry(), q.delta, k);
  } else {
    for (int j = 0; j < N; ++j) {
      set_lane(k, j, kinematics(model.geometry(), q.delta[j]));
    }
  }
  // In stick phi' is fixed by the rolling condition (12), phi' = f5 delta', and the drum does not
  // slide (v_rel = 0, (13)). The flow integrates phi' there without reading it, so the state's
  // own phi' carries the integration's round-off drift (up to ~1e-9 rad/s after a long transient
  // from rest): the columns report the constrained values instead.
  const bool stick = phase == Phase::stick;
  const L v_rel = stick ? L(0.0) : slip_velocity_of<L>(model, q, k);
  AccelerationsOf<L> a;
  if (stick) {
    stick_accelerations_of<L>(model, q, k, MM, Lx, W, a);
  } else {
    // Coulomb's law: one slip coefficient s mu for all points; a coefficient that depends on
    // v_rel (or differs between points) takes the scalar equations point by point.
    const SlipCoefficient mu = slip_coefficient(model.friction(), slip_sign(phase), v_rel[0]);
    bool constant = mu.dm_dv == 0.0;
    for (int j = 1; j < N && constant; ++j) {
      const SlipCoefficient mj = slip_coefficient(model.friction(), slip_sign(phase), v_rel[j]);
      constant = mj.dm_dv == 0.0 && mj.m == mu.m;
    }
    if (constant) {
      slip_accelerations_of<L>(model, q, k, mu.m, baumgarte, MM, Lx, W, a);
    } else {
      for (int j = 0; j < N; ++j) {
        const int i = std::min(j, count - 1);
        const Accelerations aj =
            detail::accelerations(model, t[i], State::from_array(x[i]), phase, baumgarte,
                                  kinematics(model.geometry(), x[i][0]), MM[j]);
        a.delta[j] = aj.delta;
        a.x_A[j] = aj.x_A;
        a.s_A[j] = aj.s_A;
        a.phi[j] = aj.phi;
      }
    }
  }
  DrumMotionOf<L> d;
  drum_motion_of(q, a, k, d);
  L N_force, T_force;
  soil_contact_forces(model, q, k.sin_delta, k.cos_delta, N_force, T_force);
  const L dphi = stick ? k.f5 * q.ddelta : q.dphi;
  std::array<Phase, N> shown;
  // A smooth law's samples show the apparent phase (stick while creeping, oscidrum/friction.hpp).
  const bool varies = apparent_varies(model.friction(), phase);
  for (int j = 0; j < N; ++j) {
    shown[static_cast<std::size_t>(j)] =
        varies ? apparent_phase(model.friction(), phase, v_rel[j]) : phase;
  }
  const L zero(0.0);
  append(s.t, t, count);
  append(s.delta, q.delta.v.data(), count);
  append(s.phi, q.phi.v.data(), count);
  append(s.x_A, q.x_A.v.data(), count);
  append(s.s_A, q.s_A.v.data(), count);
  append(s.ddelta, q.ddelta.v.data(), count);
  append(s.dphi, dphi.v.data(), count);
  append(s.dx_A, q.dx_A.v.data(), count);
  append(s.ds_A, q.ds_A.v.data(), count);
  append(s.x_M, d.x_M.v.data(), count);
  append(s.z_M, d.z_M.v.data(), count);
  append(s.ddx_M, d.ddx_M.v.data(), count);
  append(s.ddz_M, d.ddz_M.v.data(), count);
  append(s.N, N_force.v.data(), count);
  append(s.T, T_force.v.data(), count);
  append(s.v_rel, v_rel.v.data(), count);
  append(s.gap, zero.v.data(), count);  // permanent contact
  append(s.dgap, zero.v.data(), count);
  append(s.torque, MM.v.data(), count);
  append(s.alpha, alpha.v.data(), count);
  append(s.phase, shown.data(), count);
}

}  // namespace

void Dynamics<OscillationDrum>::sample(double t, const Vector& x, Phase phase, Samples& s) const {
  sample_lanes<1>(model_, baumgarte_, &t, &x, 1, phase, s);
}

void Dynamics<OscillationDrum>::sample_many(const double* t, const Vector* x, int count,
                                            Phase phase, Samples& s) const {
  for (int i = 0; i < count; i += kSampleLanes)
    sample_lanes<kSampleLanes>(model_, baumgarte_, t + i, x + i, std::min(kSampleLanes, count - i),
                               phase, s);
}

std::array<double, 9> Dynamics<OscillationDrum>::quantities(double t, const Vector& x,
                                                            Phase phase) const {
  const State q = State::from_array(x);
  const Kinematics k = kinematics(model_.geometry(), q.delta);  // once for all quantities
  const Accelerations a = detail::accelerations(model_, t, q, phase, baumgarte_, k);
  const DrumMotion d = detail::drum_motion(q, a, k);
  const ContactForces f = detail::contact_forces(model_, q, k);
  return {d.ddx_M, d.ddz_M, q.delta, q.phi,
          // T / N signed (mu_required is its largest magnitude): smooth inside a piece, where
          // |T| / N would have a kink at T = 0.
          f.T / f.N,
          // Friction does work only while the drum slides (13, 27). In stick v_rel = 0 by the
          // rolling condition (12); the flow integrates phi' there without reading it, so
          // slip_velocity would return its round-off drift (over a long transient from rest, up
          // to ~1e-6 of the work of a slipping case). In slip T v_rel keeps its sign.
          phase == Phase::stick ? 0.0 : std::abs(f.T * detail::slip_velocity(model_, q, k)), 0.0,
          f.N * k.cos_delta + f.T * k.sin_delta, d.z_M};
}

int Dynamics<OscillationDrum>::pushed_slip(Phase phase, const Vector& x, double* hold) const {
  // The sign of the slip: the phase's, or v_rel's in the smooth phase of a regularised law and in
  // slip without friction (mu = 0, whose flow phase keeps the arbitrary sign it started with: a
  // drum spun up by MMd > 0 slipping with v_rel < 0 in "slip+" ran to max_periods as aperiodic).
  const bool by_velocity = apparent_varies(phase);
  const double v_rel = by_velocity ? slip_velocity(model_, State::from_array(x)) : 0.0;
  const int s = by_velocity ? (v_rel > 0.0) - (v_rel < 0.0) : slip_sign(phase);
  const double MMd = model_.parameters().MMd;
  *hold = largest_slip_coefficient(model_.friction()) * model_.W() * model_.r();
  return (phase != Phase::stick && -s * MMd > 0.0) ? s : 0;
}

}  // namespace oscidrum::detail
