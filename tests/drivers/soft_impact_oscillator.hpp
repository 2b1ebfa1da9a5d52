// A textbook hybrid oscillator for the checks of the continuation (tests/drivers/
// test_branch_oscillator.cpp, docs/bifurcations.md "Checks"): the harmonically forced soft-impact
// oscillator, a linear damped oscillator of mass m whose displacement x beyond a gap e engages a
// one-sided support of stiffness k_s (a piecewise-linear oscillator: Shaw & Holmes 1983; the
// soft-impact oscillator of Ing, Pavlovskaia, Wiercigroch & Banerjee 2008) and, optionally, a
// dashpot c_s acting with it:
//
//   m x'' + c x' + k x + H(x - e) (k_s (x - e) + c_s x') = F0 cos(2 pi f t),
//
// H the unit step. With c_s = 0 the force is continuous at x = e (the saltation matrices are the
// identity); with c_s > 0 it jumps by c_s x' there (they are not; the dashpot stays attached
// until x = e, a simplification that keeps the switching surface x = e). Two phases: free (x < e,
// shown as Phase::flight) and contact (x > e, shown as Phase::stick: the mass moves with the
// support's end), switched when x crosses e (events landing and lift_off). The forcing frequency f
// [Hz] is the case's roller.f, so that the engine (the flow, the variational equations with
// saltation matrices, the continuation) runs on it unchanged; the oscillator's other constants are
// the `soft_impact` values below and nothing else of the case is read. Test-only: a Dynamics<>
// specialisation as src/roller/dynamics.hpp describes.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "oscidrum/flow.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum {

/// The soft-impact oscillator's constants (SI units; lengths in units of the gap).
struct SoftImpactConstants {
  double m = 1.0;                   ///< mass [kg]
  double fn = 40.0;                 ///< natural frequency of the free phase [Hz]
  double zeta = 0.05;               ///< damping ratio of the free phase [-]
  double k_ratio = 3.0;             ///< support stiffness k_s / k [-]
  double static_deflection = 0.25;  ///< F0 / k [m]
  double gap = 1.0;                 ///< e [m]
  double support_zeta = 0.0;        ///< c_s / (2 sqrt(k_s m)), the support's damping ratio [-]
  double omega_n() const { return 2.0 * std::numbers::pi * fn; }            ///< [rad/s]
  double k() const { return m * omega_n() * omega_n(); }                    ///< [N/m]
  double c() const { return 2.0 * zeta * m * omega_n(); }                   ///< [N s/m]
  double k_s() const { return k_ratio * k(); }                              ///< [N/m]
  double F0() const { return static_deflection * k(); }                     ///< [N]
  double c_s() const { return 2.0 * support_zeta * std::sqrt(k_s() * m); }  ///< [N s/m]
  /// The amplitude of the free phase's steady state at f when it never reaches the support:
  /// |X| = F0 / sqrt((k - m w^2)^2 + (c w)^2), w = 2 pi f (the linear oscillator's frequency
  /// response, e.g. Den Hartog, Mechanical Vibrations, ch. 2) [m].
  double linear_amplitude(double f) const {
    const double w = 2.0 * std::numbers::pi * f;
    return F0() / std::hypot(k() - m * w * w, c() * w);
  }
  /// That steady state at time t: x = Re(X e^{i w t}), X = F0 / (k - m w^2 + i c w) [m, m/s].
  std::array<double, 2> linear_state(double f, double t) const {
    const double w = 2.0 * std::numbers::pi * f;
    const double re = k() - m * w * w, im = c() * w, d = re * re + im * im;
    const double a = F0() * re / d, b = -F0() * im / d;  // X = a + i b
    return {a * std::cos(w * t) - b * std::sin(w * t),
            -w * (a * std::sin(w * t) + b * std::cos(w * t))};
  }
};

/// The constants every Dynamics<SoftImpactOscillator> uses (tests set them before a run).
inline SoftImpactConstants soft_impact;

/// The roller-type tag of the soft-impact oscillator (oscidrum/roller.hpp's role).
struct SoftImpactOscillator {
  struct State {
    double x = 0.0;  ///< displacement [m]
    double v = 0.0;  ///< velocity [m/s]
    std::array<double, 2> to_array() const { return {x, v}; }
    static State from_array(const std::array<double, 2>& q) { return {q[0], q[1]}; }
  };
  static constexpr int kStates = 2;
  static constexpr const char* name = "soft-impact oscillator";
};

namespace detail {

template <>
class Dynamics<SoftImpactOscillator> {
 public:
  static constexpr int kStates = 2;
  static constexpr int kEvents = 1;
  /// No event function of a contact force (contact ends where the penetration does).
  static constexpr int kContactEvent = -1;
  static constexpr std::array<int, 2> kPeriodic = {0, 1};
  using Vector = std::array<double, 2>;
  using Matrix = Eigen::Matrix2d;
  using EventValues = std::array<double, 1>;
  static constexpr Phase kFree = Phase::flight;
  static constexpr Phase kContact = Phase::stick;

  struct Switch {
    EventKind kind = EventKind::landing;
    Phase to = kFree;
    Vector after{};
    std::array<bool, kEvents> fresh{};
    bool terminal = false;
    FlowStop stop = FlowStop::reached;
    std::string message;
    bool consistent = true;
    bool reversal = false;
    double speed = 0.0;
  };

  Dynamics(const Model& model, double /*baumgarte*/)
      : p_(soft_impact), w_(2.0 * std::numbers::pi / model.period()) {}

  /// x' = v, m v' = F0 cos(w t) - c v - k x - [contact] (k_s (x - e) + c_s v).
  void rhs(Phase phase, double t, const Vector& x, Vector& dxdt) const {
    dxdt[0] = x[1];
    dxdt[1] =
        (p_.F0() * std::cos(w_ * t) - p_.c() * x[1] - p_.k() * x[0] - support(phase, x)) / p_.m;
  }
  /// Free: (e - x) / e, an event when the mass reaches the support; contact: (x - e) / e, an
  /// event when it leaves it. N: the support's force [N].
  EventValues events(Phase phase, const Vector& x, double* N = nullptr) const {
    if (N) *N = support(phase, x);
    const double h = (p_.gap - x[0]) / p_.gap;
    return {phase == kContact ? -h : h};
  }
  Switch apply(Phase phase, int /*which*/, double /*t*/, const Vector& x) const {
    Switch s;
    s.kind = phase == kContact ? EventKind::lift_off : EventKind::landing;
    s.to = phase == kContact ? kFree : kContact;
    s.after = x;
    s.fresh[0] = true;
    s.speed = phase == kContact ? 0.0 : x[1];
    return s;
  }
  bool invalid(Phase, const Vector&, double, std::string*, FlowStop*) const { return false; }
  void track(Phase, const Vector&, double N, FlowCounters& counters) const {
    counters.min_N = std::min(counters.min_N, N);
  }
  Vector initial_state() const { return {0.0, 0.0}; }
  Phase initial_phase() const { return kFree; }

  Matrix jacobian(Phase phase, double, const Vector&) const {
    Matrix J;
    const double k = p_.k() + (phase == kContact ? p_.k_s() : 0.0);
    const double c = p_.c() + (phase == kContact ? p_.c_s() : 0.0);
    J << 0.0, 1.0, -k / p_.m, -c / p_.m;
    return J;
  }
  /// The jump map is the identity (G = I); dh = (-1, 0) free, (1, 0) in contact.
  SaltationMatrix<2> saltation(const Event& event, const Vector& before,
                               const Vector& after) const {
    Vector f_minus, f_plus;
    rhs(event.from, event.t, before, f_minus);
    rhs(event.to, event.t, after, f_plus);
    const Eigen::Vector2d dh(event.from == kContact ? 1.0 : -1.0, 0.0);
    return saltation_matrix<2>(Matrix::Identity(), Eigen::Vector2d(f_minus[0], f_minus[1]),
                               Eigen::Vector2d(f_plus[0], f_plus[1]), dh);
  }
  Vector consistent(Vector z, Phase) const { return z; }
  std::optional<Matrix> section_jacobian(const Vector&, Phase) const { return std::nullopt; }

 private:
  double support(Phase phase, const Vector& x) const {
    return phase == kContact ? p_.k_s() * (x[0] - p_.gap) + p_.c_s() * x[1] : 0.0;
  }
  SoftImpactConstants p_;
  double w_;  // forcing circular frequency 2 pi f [rad/s]
};

}  // namespace detail
}  // namespace oscidrum
