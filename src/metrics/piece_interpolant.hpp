// piece_interpolant.hpp: the Chebyshev interpolant of a smooth function on one interval [a, b],
// through the N + 1 Chebyshev-Lobatto points t_k = (a + b)/2 + (b - a)/2 cos(pi k / N) (both ends
// included). Used for the metrics of a steady state (steady_metrics.cpp): on one piece of the
// trajectory (one integrator step in one phase) every metric quantity is an analytic function of
// t, so a degree-N interpolant from N + 1 right-hand-side evaluations is accurate to round-off and
// replaces the many evaluations that peaks, quadrature and the area would otherwise need.
#pragma once

#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

namespace oscidrum::detail {

/// The Chebyshev series sum_k c_k T_k(x) at x (Clenshaw's recurrence).
template <std::size_t M>
double chebyshev_sum(const std::array<double, M>& c, double x) {
  double b1 = 0.0, b2 = 0.0;
  for (std::size_t j = M - 1; j >= 1; --j) {
    const double b0 = 2.0 * x * b1 - b2 + c[j];
    b2 = b1;
    b1 = b0;
  }
  return x * b1 - b2 + c[0];
}

template <int N>
class ChebyshevInterpolant {
 public:
  static constexpr int kNodes = N + 1;

  /// The k-th interpolation point in [a, b] (k = 0: b, k = N: a).
  static double node(double a, double b, int k) {
    return 0.5 * (a + b) + 0.5 * (b - a) * cos_table()[k];  // cos(pi k / N)
  }

  ChebyshevInterpolant() = default;
  /// From the values f(node(a, b, k)), k = 0 ... N.
  ChebyshevInterpolant(double a, double b, const std::array<double, kNodes>& values)
      : a_(a), b_(b) {
    // The transform folded by the symmetry C_j,N-k = (-1)^j C_jk (the points mirror about the
    // middle): the even c_j from the sums f_k + f_N-k, the odd ones from the differences (the
    // middle point, for even N, only in the even ones: C_j,N/2 = 0 for odd j). Half the products
    // of the plain sum over k; the same coefficients to round-off.
    constexpr int kPairs = (N + 1) / 2;  // k = 0 ... kPairs - 1 paired with N - k
    std::array<double, kPairs> sum, diff;
    for (int k = 0; k < kPairs; ++k) {
      sum[k] = values[k] + values[N - k];
      diff[k] = values[k] - values[N - k];
    }
    const auto& C = coefficient_matrix();
    for (int j = 0; j <= N; ++j) {
      const auto& u = j % 2 == 0 ? sum : diff;
      double c = (N % 2 == 0 && j % 2 == 0) ? C[j][N / 2] * values[N / 2] : 0.0;
      for (int k = 0; k < kPairs; ++k) c += C[j][k] * u[k];
      c_[j] = c;
    }
  }

  /// The interpolant at t (Clenshaw's recurrence); t outside [a, b] extrapolates.
  double operator()(double t) const { return chebyshev_sum(c_, (2.0 * t - a_ - b_) / (b_ - a_)); }

  /// d/dt of the interpolant at t.
  double derivative(double t) const { return derivative_interpolant()(t); }

  /// The derivative d/dt as an interpolant of the same form (its highest coefficient zero).
  ChebyshevInterpolant derivative_interpolant() const {
    ChebyshevInterpolant d;
    d.a_ = a_;
    d.b_ = b_;
    for (int j = N - 1; j >= 0; --j)
      d.c_[j] = (j + 2 <= N ? d.c_[j + 2] : 0.0) + 2.0 * (j + 1) * c_[j + 1];
    d.c_[0] *= 0.5;
    for (double& c : d.c_) c *= 2.0 / (b_ - a_);
    return d;
  }

  /// How far the interpolant can rise above the largest of its values at the nodes, or fall below
  /// the smallest, anywhere on [a, b], the round-off of its evaluation included. At an extremum
  /// t* (f' = 0) the nearest node lies at most half the largest gap between neighbouring nodes,
  /// (b - a) sin(pi / 2N), away, where f differs by at most max|f''| d^2 / 2; and
  /// max|f''| <= sum |c_k| T_k''(1) (2 / (b - a))^2 with T_k''(1) = k^2 (k^2 - 1) / 3 (Markov).
  /// Together: sum |c_k| k^2 (k^2 - 1) / 3 * sin^2(pi / 2N) / 2.
  double overshoot_bound() const {
    double curvature = 0.0;
    for (int k = 0; k <= N; ++k) curvature += std::abs(c_[k]) * k * k * (k * k - 1) / 3.0;
    const double s = std::sin(std::numbers::pi / (2 * N));
    return 0.5 * curvature * s * s + roundoff_bound();
  }

  /// The round-off allowed for in overshoot_bound: 64 eps sum |c_k|, beyond what evaluating the
  /// interpolant can resolve.
  double roundoff_bound() const {
    double magnitude = 0.0;
    for (int k = 0; k <= N; ++k) magnitude += std::abs(c_[k]);
    return 64.0 * std::numeric_limits<double>::epsilon() * magnitude;
  }

  double a() const { return a_; }
  double b() const { return b_; }
  /// The Chebyshev coefficients (in x = (2 t - a - b) / (b - a)).
  const std::array<double, kNodes>& coefficients() const { return c_; }

 private:
  static const std::array<double, 2 * N>& cos_table() {
    static const std::array<double, 2 * N> table = [] {
      std::array<double, 2 * N> c{};
      for (int m = 0; m < 2 * N; ++m) c[m] = std::cos(std::numbers::pi * m / N);
      return c;
    }();
    return table;
  }

  // c_j = sum_k C_jk f_k: C_jk = (2 / N) w_j w_k cos(pi j k / N), w = 1/2 at 0 and N, else 1
  // (the discrete cosine transform of the values at the Chebyshev-Lobatto points).
  static const std::array<std::array<double, kNodes>, kNodes>& coefficient_matrix() {
    static const auto matrix = [] {
      std::array<std::array<double, kNodes>, kNodes> C{};
      for (int j = 0; j <= N; ++j) {
        for (int k = 0; k <= N; ++k) {
          const double w = ((j == 0 || j == N) ? 0.5 : 1.0) * ((k == 0 || k == N) ? 0.5 : 1.0);
          // cos(pi j k / N) with the product reduced mod 2N, exact at the symmetric points.
          C[j][k] = (2.0 / N) * w * cos_table()[(j * k) % (2 * N)];
        }
      }
      return C;
    }();
    return matrix;
  }

  double a_ = 0.0, b_ = 1.0;
  std::array<double, kNodes> c_{};
};

/// The extremum of f (a maximum for sign +1, a minimum for -1) in the bracket [t_lo, t_lo + width]:
/// the root of f' there, by Newton's method on f' (with f'') kept inside the bracket by bisection,
/// when sign f' is >= 0 at the bracket's start and <= 0 at its end (the bisection keeps that
/// sign pattern, so it ends at a maximum, for sign -1 a minimum, even in a bracket holding more
/// than one turn); otherwise Brent's method on f. Both in the fraction u in [0, 1] of the bracket:
/// in absolute time (seconds into a long transient) a tolerance on t would leave the extremum
/// ~1e-7 s off. The value at the root is exact to round-off (an error d in the abscissa changes
/// it by f'' d^2 / 2).
template <int N>
double extremum(const ChebyshevInterpolant<N>& f, const ChebyshevInterpolant<N>& df,
                const ChebyshevInterpolant<N>& d2f, double t_lo, double width, double sign) {
  const auto g = [&](double u) { return sign * df(t_lo + u * width); };  // decreasing at the root
  double lo = 0.0, hi = 1.0;
  const double g_lo = g(lo), g_hi = g(hi);
  if (g_lo >= 0.0 && g_hi <= 0.0) {
    double u = g_lo == 0.0 ? 0.0 : g_hi == 0.0 ? 1.0 : g_lo / (g_lo - g_hi);  // secant start
    for (int it = 0; it < 100 && g_lo != 0.0 && g_hi != 0.0; ++it) {
      const double gu = g(u);
      if (gu == 0.0) break;
      (gu > 0.0 ? lo : hi) = u;
      const double slope = sign * d2f(t_lo + u * width) * width;  // dg/du
      double next = slope < 0.0 ? u - gu / slope : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      const double step = std::abs(next - u);
      u = next;
      // Quadratic convergence: a step of 1e-9 leaves ~1e-18 of the bracket, below round-off.
      if (step <= 1e-9 || hi - lo <= 1e-15) break;
    }
    return f(t_lo + u * width);
  }
  const auto minus_f = [&](double u) { return -sign * f(t_lo + u * width); };
  const auto best =
      boost::math::tools::brent_find_minima(minus_f, 0.0, 1.0, std::numeric_limits<double>::digits);
  return -sign * best.second;
}

}  // namespace oscidrum::detail
