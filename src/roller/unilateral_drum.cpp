// The oscillation drum with unilateral contact (src/roller/unilateral_drum.hpp, docs/model.md
// section 13): contact phases by the drum's equations, the flight phase, lift-off and landing,
// and their Jacobians and saltation matrices.
#include "roller/unilateral_drum.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "equations/equations.hpp"
#include "equations/jacobian.hpp"
#include "util/dual.hpp"
#include "util/format.hpp"

namespace oscidrum::detail {
namespace {

using U = Dynamics<UnilateralDrum>;
using namespace flight_index;
// The drum's eight components within the unilateral state.
constexpr std::array<int, 8> kContact = {0, 1, 2, 3, 5, 6, 7, 8};

U::Matrix embed_matrix(const Mat8& m8, bool identity_gap) {
  U::Matrix m = U::Matrix::Zero();
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) m(kContact[i], kContact[j]) = m8(i, j);
  if (identity_gap) m(kGap, kGap) = m(kDGap, kDGap) = 1.0;
  return m;
}

template <class F>
U::Matrix map_jacobian(const U::Vector& x, const Model& model, F&& map) {
  using Dn = Dual<10>;
  std::array<Dn, 10> y;
  for (int i = 0; i < 10; ++i) y[i] = Dn::variable(x[i], i);
  const Kinematics k = kinematics(model.geometry(), x[kDelta]);
  const KinematicsRates kr = kinematics_rates(model.geometry(), x[kDelta]);
  const std::array<Dn, 10> out = map(y, kinematics_t(k, kr, y[kDelta]));
  U::Matrix G;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) G(i, j) = out[i].d[j];
  return G;
}

Eigen::Matrix<double, 10, 1> as_column(const U::Vector& v) {
  return Eigen::Map<const Eigen::Matrix<double, 10, 1>>(v.data());
}

}  // namespace

Dynamics<UnilateralDrum>::Dynamics(const Model& model, double baumgarte)
    : drum_(model, baumgarte), gap_scale_(model.W() / (model.ksv() + model.kd())) {}

void Dynamics<UnilateralDrum>::flight_rhs(double t, const Vector& x, Vector& dxdt) const {
  const Model& m = model();
  const auto a = flight_accelerations(m, t, x, kinematics_t(kinematics(m.geometry(), x[kDelta])));
  dxdt = {x[kDDelta], x[kDXA], x[kDSA], x[kDPhi], x[kDGap], a[0], a[1], a[2], a[3], a[4]};
}

void Dynamics<UnilateralDrum>::rhs(Phase phase, double t, const Vector& x, Vector& dxdt) const {
  if (phase == Phase::flight) return flight_rhs(t, x, dxdt);
  Drum::Vector dq;
  drum_.rhs(phase, t, contact_part(x), dq);
  dxdt = {dq[0], dq[1], dq[2], dq[3], 0.0, dq[4], dq[5], dq[6], dq[7], 0.0};  // g = g' = 0
}

U::EventValues Dynamics<UnilateralDrum>::events(Phase phase, const Vector& x, double* N) const {
  if (phase != Phase::flight) return drum_.events(phase, contact_part(x), N);
  if (N != nullptr) *N = 0.0;  // no contact force (track() ignores flight)
  // The gap (landing when it closes) over the static soil deflection, and the chart's margin
  // r f5 - g over r f5 (the gap reaching the trough's clearance ends the chart).
  const double rf5 = model().r() * kinematics(model().geometry(), x[kDelta]).f5;
  return {x[kGap] / gap_scale_, (rf5 - x[kGap]) / rf5, 1.0};
}

Landing Dynamics<UnilateralDrum>::landing(const Vector& x, Phase* to, int* s,
                                          bool* consistent) const {
  *consistent = true;
  *s = 0;
  const Model& m = model();
  switch (m.friction_phases()) {
    case FrictionPhases::stick_only:
      *to = Phase::stick;
      return Landing::stick;
    case FrictionPhases::smooth:
      *to = Phase::smooth;
      return Landing::smooth;
    case FrictionPhases::stick_slip:
      break;
  }
  const KinematicsT<double> k = kinematics_t(kinematics(m.geometry(), x[kDelta]));
  // Rolling, if the friction cone holds the contact's forces (28).
  const Vector rolled = landing_map(m, x, k, Landing::stick, 0);
  const ContactForces f = contact_forces(m, UnilateralState::from_array(rolled).contact());
  if (m.cone() > 0.0 && std::abs(f.T) <= m.cone() * f.N) {
    *to = Phase::stick;
    return Landing::stick;
  }
  // Else slip against T: s = -sign(T) (29); without friction the sign is that of v_rel.
  *s = f.T > 0.0 ? -1 : 1;
  Vector slid = landing_map(m, x, k, Landing::slip, *s);
  double v = slip_velocity(m, UnilateralState::from_array(slid).contact());
  if (m.cone() == 0.0 && *s * v < 0.0) {
    *s = -*s;
    slid = landing_map(m, x, k, Landing::slip, *s);
    v = slip_velocity(m, UnilateralState::from_array(slid).contact());
  }
  if (*s * v > 0.0) {
    *to = *s > 0 ? Phase::slip_positive : Phase::slip_negative;
    return Landing::slip;
  }
  // Neither rolling nor slip is consistent: take rolling, whose cone event follows at once.
  *consistent = false;
  *s = 0;
  *to = Phase::stick;
  return Landing::stick;
}

U::Switch Dynamics<UnilateralDrum>::apply(Phase phase, int which, double t, const Vector& x) const {
  Switch out;
  out.after = x;
  const Model& m = model();
  if (phase != Phase::flight) {
    if (which == kEventContact) {  // N reached 0: the drum lifts off
      out.kind = EventKind::lift_off;
      out.to = Phase::flight;
      out.after = liftoff_map(m, x, kinematics_t(kinematics(m.geometry(), x[kDelta])),
                              phase == Phase::stick);
      out.fresh[kEventGap] = true;  // the gap starts at 0 and must open
      // From slip (Coulomb or regularised) T = -m N has vanished with N, the soil is already
      // relaxed and the gap opens from g' = 0. From stick (pure rolling: no friction limit) T
      // need not vanish with N, and the soil's release can move the trough into the drum
      // (g' < 0): neither flight nor contact is consistent (a Painleve-type paradox of the
      // massless soil), and the run stops saying so.
      const double dgap = out.after[kDGap];
      const double scale = m.r() * m.nu() * gap_scale_;  // a gap of the static deflection at nu
      if (phase == Phase::stick && dgap < -1e-9 * scale) {
        // Where the contact pulled from the start of stick (a landing with N < 0, switched at
        // once), N did not reach 0 but started below it: say so, with its value.
        const ContactForces f = contact_forces(m, UnilateralState::from_array(x).contact());
        const std::string where =
            f.N < -1e-6 * m.W() ? detail::format(
                                      "at t = %.9g s the contact pulled where stick began after a "
                                      "landing (N = %.4g N)",
                                      t, f.N)
                                : detail::format("at t = %.9g s N reached 0 in stick", t);
        out.terminal = true;
        out.kind = EventKind::contact_lost;
        out.to = phase;
        out.after = x;
        out.stop = FlowStop::contact_lost;
        out.message =
            where + detail::format(
                        " while the contact still carried T = %.6g N: without a friction limit "
                        "(contact.pure_rolling) the soil's release moves the trough into the drum "
                        "(g' = %.3g m/s), so the drum can neither lift off nor stay in contact "
                        "(docs/model.md section 13); give a friction coefficient instead",
                        f.T, dgap);
      }
      return out;
    }
    const Drum::Switch d = drum_.apply(phase, which, t, contact_part(x));
    out.kind = d.kind;
    out.to = d.to;
    out.after = embed(d.after);
    out.fresh = d.fresh;
    out.terminal = d.terminal;
    out.stop = d.stop;
    out.message = d.message;
    out.consistent = d.consistent;
    out.reversal = d.reversal;
    return out;
  }
  if (which == kEventClearance) {
    out.kind = EventKind::contact_lost;
    out.to = phase;
    out.terminal = true;
    out.stop = FlowStop::contact_lost;
    out.message = detail::format(
        "at t = %.9g s the drum in flight reached the trough's clearance (gap %.6g m = r f5): "
        "it left the trough altogether, which the model does not follow",
        t, x[kGap]);
    return out;
  }
  // The gap closed: landing, in the phase the friction law decides.
  int s = 0;
  const Landing how = landing(x, &out.to, &s, &out.consistent);
  out.kind = EventKind::landing;
  out.speed = -x[kDGap];
  out.after = landing_map(m, x, kinematics_t(kinematics(m.geometry(), x[kDelta])), how, s);
  // A landing whose contact would pull (N <= 0) lifts off again at once.
  double N = 0.0;
  drum_.events(out.to, contact_part(out.after), &N);
  if (!(N > 0.0)) out.fresh[kEventContact] = true;
  return out;
}

U::Matrix Dynamics<UnilateralDrum>::jacobian(Phase phase, double t, const Vector& x) const {
  if (phase != Phase::flight) return embed_matrix(drum_.jacobian(phase, t, contact_part(x)), false);
  // Flight: the accelerations on dual numbers seeded with the ten components.
  using Dn = Dual<10>;
  std::array<Dn, 10> y;
  for (int i = 0; i < 10; ++i) y[i] = Dn::variable(x[i], i);
  const Model& m = model();
  const Kinematics k = kinematics(m.geometry(), x[kDelta]);
  const KinematicsRates kr = kinematics_rates(m.geometry(), x[kDelta]);
  const auto a = flight_accelerations(m, t, y, kinematics_t(k, kr, y[kDelta]));
  Matrix J = Matrix::Zero();
  for (int i = 0; i < 5; ++i) J(i, i + 5) = 1.0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 10; ++j) J(5 + i, j) = a[i].d[j];
  return J;
}

SaltationMatrix<10> Dynamics<UnilateralDrum>::saltation(const Event& event, const Vector& before,
                                                        const Vector& after) const {
  const Model& m = model();
  if (event.kind != EventKind::lift_off && event.kind != EventKind::landing) {
    const SaltationMatrix<8> s8 = drum_.saltation(event, contact_part(before), contact_part(after));
    return {embed_matrix(s8.S, true), s8.grazing};
  }
  Vector f_minus, f_plus;
  rhs(event.from, event.t, before, f_minus);
  rhs(event.to, event.t, after, f_plus);
  Matrix G;
  Eigen::Matrix<double, 10, 1> dh = Eigen::Matrix<double, 10, 1>::Zero();
  if (event.kind == EventKind::lift_off) {
    const bool from_stick = event.from == Phase::stick;
    G = map_jacobian(
        before, m, [&](const auto& y, const auto& k) { return liftoff_map(m, y, k, from_stick); });
    // The surface N = 0 (26), a function of the contact's components.
    const Vec8 dN = event_gradient(m, UnilateralState::from_array(before).contact(),
                                   EventFunction::normal_force);
    for (int i = 0; i < 8; ++i) dh[kContact[i]] = dN[i];
  } else {
    const Landing how = event.to == Phase::stick    ? Landing::stick
                        : event.to == Phase::smooth ? Landing::smooth
                                                    : Landing::slip;
    const int s = slip_sign(event.to);
    G = map_jacobian(before, m,
                     [&](const auto& y, const auto& k) { return landing_map(m, y, k, how, s); });
    dh[kGap] = 1.0;  // the surface g = 0
  }
  return saltation_matrix<10>(G, as_column(f_minus), as_column(f_plus), dh);
}

U::Vector Dynamics<UnilateralDrum>::consistent(Vector z, Phase phase) const {
  if (phase != Phase::flight) return embed(drum_.consistent(contact_part(z), phase));
  const Model& m = model();
  z[kDXA] = -(m.ksh() / m.csh()) * z[kXA];
  z[kDSA] = -(m.ksv() / m.csv()) * z[kSA];
  return z;
}

std::optional<U::Matrix> Dynamics<UnilateralDrum>::section_jacobian(const Vector& z,
                                                                    Phase phase) const {
  if (phase != Phase::flight) {
    const std::optional<Mat8> g8 = drum_.section_jacobian(contact_part(z), phase);
    return embed_matrix(g8 ? *g8 : Mat8(Mat8::Identity()), false);  // g, g' set to 0
  }
  const Model& m = model();
  Matrix G = Matrix::Identity();
  G(kDXA, kDXA) = G(kDSA, kDSA) = 0.0;
  G(kDXA, kXA) = -m.ksh() / m.csh();
  G(kDSA, kSA) = -m.ksv() / m.csv();
  return G;
}

std::array<double, 9> Dynamics<UnilateralDrum>::quantities(double t, const Vector& x,
                                                           Phase phase) const {
  if (phase != Phase::flight) return drum_.quantities(t, contact_part(x), phase);
  const Model& m = model();
  const KinematicsT<double> k = kinematics_t(kinematics(m.geometry(), x[kDelta]));
  const FlightCentre<double> M = flight_centre(x, k, m.r());
  const CentreLoad L = m.centre_load(t);
  return {(-m.cd() * M.dx - m.kd() * M.x + L.x) / m.m(),
          (L.z - m.cd() * M.dz - m.kd() * (M.z - m.z_ref())) / m.m(),
          x[kDelta],
          x[kPhi],
          0.0,
          0.0,
          x[kGap],
          0.0,
          M.z};
}

void Dynamics<UnilateralDrum>::sample(double t, const Vector& x, Phase phase, Samples& s) const {
  if (phase != Phase::flight) return drum_.sample(t, contact_part(x), phase, s);
  const Model& m = model();
  const KinematicsT<double> k = kinematics_t(kinematics(m.geometry(), x[kDelta]));
  const FlightCentre<double> M = flight_centre(x, k, m.r());
  s.t.push_back(t);
  s.delta.push_back(x[kDelta]);
  s.phi.push_back(x[kPhi]);
  s.x_A.push_back(x[kXA]);
  s.s_A.push_back(x[kSA]);
  s.ddelta.push_back(x[kDDelta]);
  s.dphi.push_back(x[kDPhi]);
  s.dx_A.push_back(x[kDXA]);
  s.ds_A.push_back(x[kDSA]);
  s.x_M.push_back(M.x);
  s.z_M.push_back(M.z);
  // (19), (20) with N = T = 0.
  const CentreLoad L = m.centre_load(t);
  s.ddx_M.push_back((-m.cd() * M.dx - m.kd() * M.x + L.x) / m.m());
  s.ddz_M.push_back((L.z - m.cd() * M.dz - m.kd() * (M.z - m.z_ref())) / m.m());
  s.N.push_back(0.0);
  s.T.push_back(0.0);
  s.v_rel.push_back(0.0);
  s.gap.push_back(x[kGap]);
  s.dgap.push_back(x[kDGap]);
  s.torque.push_back(m.torque(t));
  s.alpha.push_back(m.excitation_angle(t));
  s.phase.push_back(Phase::flight);
}

}  // namespace oscidrum::detail
