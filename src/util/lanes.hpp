// Internal: N independent doubles that take part in the same arithmetic, lane by lane, for
// equations evaluated at many points at once (the output's samples of a step, the samples of a
// step's event functions). Each operation is the scalar one in every lane, in the same order, so
// a lane's result has the scalar code's bits: the builds' targets (x86-64's baseline, WebAssembly)
// have no fused multiply-add for the compiler to contract either into, and the tests compare lanes
// with one point at a time to the bit. What the lanes buy is independence: a point's equations are
// a long chain of dependent operations (two divisions among them), and N chains side by side keep
// the arithmetic units busy where one chain waits; the compiler turns the lane loops into vector
// instructions.
#pragma once

#include <array>

namespace oscidrum::detail {

template <int N>
struct Lanes {
  std::array<double, N> v;  // not initialised: every use sets each lane

  Lanes() = default;
  Lanes(double x) { v.fill(x); }  // NOLINT: a constant in every lane
  double& operator[](int i) { return v[static_cast<std::size_t>(i)]; }
  double operator[](int i) const { return v[static_cast<std::size_t>(i)]; }
};

#define OSCIDRUM_LANES_OPERATOR(op)                                                          \
  template <int N>                                                                           \
  [[gnu::always_inline]] inline Lanes<N> operator op(const Lanes<N>& a, const Lanes<N>& b) { \
    Lanes<N> r;                                                                              \
    for (int i = 0; i < N; ++i) r.v[i] = a.v[i] op b.v[i];                                   \
    return r;                                                                                \
  }                                                                                          \
  template <int N>                                                                           \
  [[gnu::always_inline]] inline Lanes<N> operator op(const Lanes<N>& a, double b) {          \
    Lanes<N> r;                                                                              \
    for (int i = 0; i < N; ++i) r.v[i] = a.v[i] op b;                                        \
    return r;                                                                                \
  }                                                                                          \
  template <int N>                                                                           \
  [[gnu::always_inline]] inline Lanes<N> operator op(double a, const Lanes<N>& b) {          \
    Lanes<N> r;                                                                              \
    for (int i = 0; i < N; ++i) r.v[i] = a op b.v[i];                                        \
    return r;                                                                                \
  }                                                                                          \
  template <int N>                                                                           \
  [[gnu::always_inline]] inline Lanes<N>& operator op##=(Lanes<N>& a, const Lanes<N>& b) {   \
    for (int i = 0; i < N; ++i) a.v[i] = a.v[i] op b.v[i];                                   \
    return a;                                                                                \
  }
OSCIDRUM_LANES_OPERATOR(+)
OSCIDRUM_LANES_OPERATOR(-)
OSCIDRUM_LANES_OPERATOR(*)
OSCIDRUM_LANES_OPERATOR(/)
#undef OSCIDRUM_LANES_OPERATOR

template <int N>
[[gnu::always_inline]] inline Lanes<N> operator-(const Lanes<N>& a) {
  Lanes<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = -a.v[i];
  return r;
}

}  // namespace oscidrum::detail
