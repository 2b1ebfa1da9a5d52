// Internal: forward-mode automatic differentiation with N directions (dual numbers), for the
// Jacobians of equations that are not differentiated by hand (the slip phase with a
// velocity-dependent friction coefficient). A Dual carries a value and its derivatives with
// respect to N seeded inputs; every operation applies the chain rule exactly, so the Jacobian is
// exact to round-off (checked against finite differences in the tests).
#pragma once

#include <array>
#include <cmath>

namespace oscidrum::detail {

template <int N>
struct Dual {
  double v = 0.0;
  std::array<double, N> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: a constant has zero derivatives
  Dual(double value, const std::array<double, N>& derivatives) : v(value), d(derivatives) {}
  /// The i-th input: value x, derivative 1 in direction i.
  static Dual variable(double x, int i) {
    Dual r(x);
    r.d[static_cast<std::size_t>(i)] = 1.0;
    return r;
  }
  /// f(a) with f(a.v) = value and f'(a.v) = slope.
  static Dual chain(const Dual& a, double value, double slope) {
    Dual r(value);
    for (int i = 0; i < N; ++i) r.d[i] = slope * a.d[i];
    return r;
  }

  Dual& operator+=(const Dual& b) {
    v += b.v;
    for (int i = 0; i < N; ++i) d[i] += b.d[i];
    return *this;
  }
  Dual& operator-=(const Dual& b) {
    v -= b.v;
    for (int i = 0; i < N; ++i) d[i] -= b.d[i];
    return *this;
  }
  Dual& operator*=(const Dual& b) {
    for (int i = 0; i < N; ++i) d[i] = d[i] * b.v + v * b.d[i];
    v *= b.v;
    return *this;
  }
  Dual& operator/=(const Dual& b) {
    const double inv = 1.0 / b.v;
    v *= inv;
    for (int i = 0; i < N; ++i) d[i] = (d[i] - v * b.d[i]) * inv;
    return *this;
  }
};

template <int N>
Dual<N> operator+(Dual<N> a, const Dual<N>& b) {
  return a += b;
}
template <int N>
Dual<N> operator-(Dual<N> a, const Dual<N>& b) {
  return a -= b;
}
template <int N>
Dual<N> operator*(Dual<N> a, const Dual<N>& b) {
  return a *= b;
}
template <int N>
Dual<N> operator/(Dual<N> a, const Dual<N>& b) {
  return a /= b;
}
template <int N>
Dual<N> operator-(Dual<N> a) {
  a.v = -a.v;
  for (double& x : a.d) x = -x;
  return a;
}
template <int N>
Dual<N> operator+(Dual<N> a, double b) {
  a.v += b;
  return a;
}
template <int N>
Dual<N> operator+(double b, Dual<N> a) {
  a.v += b;
  return a;
}
template <int N>
Dual<N> operator-(Dual<N> a, double b) {
  a.v -= b;
  return a;
}
template <int N>
Dual<N> operator-(double b, const Dual<N>& a) {
  return -a + b;
}
template <int N>
Dual<N> operator*(Dual<N> a, double b) {
  a.v *= b;
  for (double& x : a.d) x *= b;
  return a;
}
template <int N>
Dual<N> operator*(double b, Dual<N> a) {
  return a * b;
}
template <int N>
Dual<N> operator/(Dual<N> a, double b) {
  return a * (1.0 / b);
}
template <int N>
Dual<N> operator/(double b, const Dual<N>& a) {
  return Dual<N>(b) / a;
}

/// The value of a double or a Dual (for decisions such as pivoting, which do not differentiate).
inline double value_of(double x) { return x; }
template <int N>
double value_of(const Dual<N>& x) {
  return x.v;
}

}  // namespace oscidrum::detail
