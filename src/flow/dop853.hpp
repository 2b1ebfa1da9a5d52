// Internal: Dormand and Prince's explicit Runge-Kutta method of order 8 with its embedded 5th-
// and 3rd-order error estimates and its 7th-order continuous extension ("DOP853"; Hairer, Norsett
// & Wanner, Solving Ordinary Differential Equations I, 2nd ed. 1993, II.10), for a fixed-size
// state. Its interface (initialize, do_step, current_state, calc_state, current_time_step) is
// that of the dense-output stepper the hybrid flow (hybrid_flow.hpp) uses to locate its events
// on the continuous extension of each step.
//
// The flow's integrator, in place of Dormand-Prince 5(4) (MATLAB's ode45, which the paper used):
// at the tolerances the metrics need (rtol 1e-8) an 8th-order step is about four times as long
// as a 5th-order one; with its 12 stages (the 13th is the next step's first, FSAL) and 3 more for
// the continuous extension of an accepted step, it evaluates the right-hand side a quarter to a
// half less often, and the longer steps need fewer variational substeps, recorded pieces and
// event tests (bench/README.md, "Issue 26: Dormand-Prince 8(5,3) in the flow"). No packaged
// library offers this pair with its continuous extension for a fixed-size state (Boost.Odeint's
// 8th-order pair, Fehlberg 7(8), has no continuous extension of its own).
//
// Step control (Hairer, Norsett & Wanner, II.4 and II.10): the error of a step is the largest
// over the components of |h| |err5|^2 / sqrt(err5^2 + 0.01 err3^2) / sc with the scale
// sc = atol + rtol max(|y0|, |y1|); a step is accepted when it is at most 1. The next step is
// h 0.9 err^(-1/8), between h/5 and 10 h, never above max_step. A step whose error is not finite
// (a stage overflowed: the step is far too long for a stiff phase) is rejected and a fifth as
// long tried; where the right-hand side at the step's start is not finite, the step is taken as
// it is (the caller tests the state for finiteness). A step that has to shrink below the
// round-off of t fails (failed()), so no loop of rejections can hang.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "flow/dop853_tableau.hpp"
#include "util/lanes.hpp"

namespace oscidrum::detail {

template <class Vec>
class Dop853 {
 public:
  static constexpr std::size_t n = std::tuple_size<Vec>::value;
  static constexpr int kStages = 12;       // stages of a step; the 13th is at the new point
  static constexpr int kDenseStages = 16;  // with the three of the continuous extension

  Dop853(double atol, double rtol, double max_step)
      : atol_(atol), rtol_(rtol), max_step_(max_step) {}

  // Starts at (t, x) with a first trial step dt.
  void initialize(const Vec& x, double t, double dt) {
    x_ = x;
    t_ = t;
    dt_ = dt;
    have_f_ = false;
    failed_ = false;
  }
  double current_time_step() const { return dt_; }
  const Vec& current_state() const { return x_; }
  double current_time() const { return t_; }
  // True when the last do_step could not find a step the error test accepts above t's round-off.
  bool failed() const { return failed_; }

  // One accepted step, from t to t + h; returns (t, t + h). sys(x, dxdt, t) is the right-hand
  // side. After failed() the state is unchanged and the returned interval empty.
  template <class Sys>
  std::pair<double, double> do_step(Sys sys) {
    namespace c = dop853;
    if (!have_f_) {
      sys(x_, K_[0], t_);
      have_f_ = true;
    }
    double h = std::min(dt_, max_step_);
    const bool finite_start =
        std::all_of(K_[0].begin(), K_[0].end(), [](double v) { return std::isfinite(v); });
    Vec xn{};
    while (true) {
      for (int s = 1; s < kStages; ++s) sys(stage_point(s, h), K_[s], t_ + c::kC[s] * h);
      xn = stage_point(kStages, h);
      sys(xn, K_[kStages], t_ + h);
      const double err = finite_start ? error(h, xn) : 0.0;
      if (err <= 1.0) {
        const double grow = err > 0.0 ? 0.9 * std::pow(err, -1.0 / 8.0) : 10.0;
        finish(h, xn, sys);
        dt_ = std::min(h * std::min(10.0, grow), max_step_);
        return {t_old_, t_};
      }
      h *= std::isfinite(err) ? std::max(0.2, 0.9 * std::pow(err, -1.0 / 8.0)) : 0.2;
      if (!(std::abs(h) > 8.0 * std::numeric_limits<double>::epsilon() * std::abs(t_))) {
        failed_ = true;
        dt_ = h;
        return {t_, t_};
      }
    }
  }

  // The state at t inside the last accepted step by the method's own step from the step's start
  // to t (order 8, 11 evaluations of sys): where one state matters more than the cost (the end of
  // an interval whose states are compared period to period), the continuous extension's error,
  // an order higher in the step, would be noise.
  template <class Sys>
  Vec step_to(double t, Sys sys) const {
    const double h = t - t_old_;
    std::array<Vec, kStages> k{};
    k[0] = f_old_;
    for (int s = 1; s < kStages; ++s)
      sys(combine(x_old_, k, s, h), k[s], t_old_ + dop853::kC[s] * h);
    return combine(x_old_, k, kStages, h);
  }

  // calc_state at the n times t[0 ... n-1] (the output's samples), in lanes of kLanes times
  // (util/lanes.hpp): the same operations in each lane, so the same bits.
  void calc_states(const double* t, int count, Vec* out) const {
    constexpr int kLanes = 8;
    for (int i0 = 0; i0 < count; i0 += kLanes) {
      const int m = std::min(kLanes, count - i0);
      Lanes<kLanes> s;
      for (int j = 0; j < kLanes; ++j) s[j] = (t[i0 + std::min(j, m - 1)] - t_old_) / h_;
      const Lanes<kLanes> s1 = 1.0 - s;
      for (std::size_t i = 0; i < n; ++i) {
        const Lanes<kLanes> y = extension(i, s, s1);
        for (int j = 0; j < m; ++j) out[i0 + j][i] = x_old_[i] + y[j];
      }
    }
  }

  // The continuous extension of the last accepted step at t in [t - h, t] (order 7).
  void calc_state(double t, Vec& out) const {
    const double s = (t - t_old_) / h_;
    const double s1 = 1.0 - s;
    for (std::size_t i = 0; i < n; ++i) out[i] = x_old_[i] + extension(i, s, s1);
  }

 private:
  // The extension's increment of component i at s (double, or lanes of times):
  // s (R0 + s1 (R1 + s (R2 + s1 (R3 + s (R4 + s1 (R5 + s R6)))))), s1 = 1 - s.
  template <class T>
  T extension(std::size_t i, const T& s, const T& s1) const {
    T y = R_[6][i] * s;
    y = (R_[5][i] + y) * s1;
    y = (R_[4][i] + y) * s;
    y = (R_[3][i] + y) * s1;
    y = (R_[2][i] + y) * s;
    y = (R_[1][i] + y) * s1;
    return (R_[0][i] + y) * s;
  }

  // x + h sum_j a_sj k_j over the stages before s (row s of the tableau).
  template <std::size_t N>
  static Vec combine(const Vec& x, const std::array<Vec, N>& k, int s, double h) {
    Vec y = x;
    for (int j = 0; j < s; ++j) {
      const double a = dop853::kA[s][j];
      if (a == 0.0) continue;
      const double ha = h * a;
      for (std::size_t i = 0; i < n; ++i) y[i] += ha * k[j][i];
    }
    return y;
  }
  Vec stage_point(int s, double h) const { return combine(x_, K_, s, h); }

  double error(double h, const Vec& xn) const {
    double err = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double e5 = 0.0, e3 = 0.0;
      for (int j = 0; j <= kStages; ++j) {
        e5 += dop853::kE5[j] * K_[j][i];
        e3 += dop853::kE3[j] * K_[j][i];
      }
      const double sc = atol_ + rtol_ * std::max(std::abs(x_[i]), std::abs(xn[i]));
      const double den = std::sqrt(e5 * e5 + 0.01 * e3 * e3);
      const double ei = den == 0.0 ? 0.0 : std::abs(h) * e5 * e5 / den / sc;
      if (std::isnan(ei)) return ei;  // a stage overflowed: the step is rejected
      err = std::max(err, ei);
    }
    return err;
  }

  // Accepts the step to xn: the three stages of the continuous extension and its coefficients.
  template <class Sys>
  void finish(double h, const Vec& xn, Sys& sys) {
    for (int s = kStages + 1; s < kDenseStages; ++s)
      sys(stage_point(s, h), K_[s], t_ + dop853::kC[s] * h);
    for (std::size_t i = 0; i < n; ++i) {
      const double dy = xn[i] - x_[i];
      const double b = h * K_[0][i] - dy;
      R_[0][i] = dy;
      R_[1][i] = b;
      R_[2][i] = dy - h * K_[kStages][i] - b;
      for (int r = 0; r < 4; ++r) {
        double acc = 0.0;
        for (int j = 0; j < kDenseStages; ++j) acc += dop853::kD[r][j] * K_[j][i];
        R_[3 + r][i] = h * acc;
      }
    }
    x_old_ = x_;
    f_old_ = K_[0];
    t_old_ = t_;
    h_ = h;
    x_ = xn;
    t_ += h;
    K_[0] = K_[kStages];  // FSAL: the derivative at the new point starts the next step
  }

  double atol_, rtol_, max_step_;
  Vec x_{}, x_old_{}, f_old_{};
  double t_ = 0.0, t_old_ = 0.0, h_ = 1.0, dt_ = 0.0;
  bool have_f_ = false, failed_ = false;
  std::array<Vec, kDenseStages> K_{};
  std::array<Vec, 7> R_{};
};

}  // namespace oscidrum::detail
