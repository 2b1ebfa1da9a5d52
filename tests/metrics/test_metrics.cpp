// test_metrics.cpp: harmonics, wrap_pi, enclosed_area and compute_metrics (docs/model.md section
// 8).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "metrics/area.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/result.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

using test::kIdentity;
constexpr double kPi = std::numbers::pi;

/// Runs fn, expects an oscidrum::Error whose message contains every one of `parts`.
void expect_error(const std::function<void()>& fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "no oscidrum::Error thrown";
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' not in: " << msg;
    }
  }
}

/// Angle difference reduced to (-pi, pi] (phases near +-pi must compare equal).
double angle_diff(double a, double b) { return wrap_pi(a - b); }

/// A sum of sines sampled as harmonics() expects.
struct Component {
  int n;
  double amplitude, phase;
};
std::vector<double> sample(double mean, const std::vector<Component>& parts, int cycles,
                           int per_cycle, double f, double t0) {
  const std::size_t size = static_cast<std::size_t>(cycles * per_cycle);
  const double dt = 1.0 / (f * per_cycle);
  std::vector<double> y(size, mean);
  for (std::size_t j = 0; j < size; ++j) {
    const double t = t0 + static_cast<double>(j) * dt;
    for (const Component& c : parts) {
      y[j] += c.amplitude * std::sin(c.n * 2.0 * kPi * f * t + c.phase);
    }
  }
  return y;
}

/// Signed shoelace area of the closed polygon.
double shoelace(const std::vector<double>& x, const std::vector<double>& y) {
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::size_t k = (i + 1) % x.size();
    s += x[i] * y[k] - x[k] * y[i];
  }
  return 0.5 * s;
}

// ---------------------------------------------------------------------------------------------
// wrap_pi

TEST(WrapPi, MapsToHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_pi(0.5), 0.5);
  EXPECT_DOUBLE_EQ(wrap_pi(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_pi(-kPi), kPi);  // -pi is excluded
  EXPECT_NEAR(wrap_pi(3.0 * kPi), kPi, kIdentity);
  EXPECT_NEAR(wrap_pi(2.0 * kPi), 0.0, kIdentity);
  EXPECT_NEAR(wrap_pi(-7.0), -7.0 + 2.0 * kPi, kIdentity);
  EXPECT_NEAR(wrap_pi(100.0), 100.0 - 32.0 * kPi, kIdentity);
  for (double a = -20.0; a < 20.0; a += 0.37) {
    const double w = wrap_pi(a);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    const double turns = (a - w) / (2.0 * kPi);  // a whole number of turns was removed
    EXPECT_NEAR(turns, std::round(turns), kIdentity);
  }
}

// ---------------------------------------------------------------------------------------------
// harmonics

// A band-limited signal is reproduced to round-off: amplitudes, absolute-time phases (t0 is not
// a multiple of the period, several cycles) and zeros at the harmonics it does not hold.
TEST(Harmonics, BandLimitedSignalIsExactAtNonZeroStart) {
  const double f = 28.3;
  const double t0 = 0.4567;  // 12.92 periods: the phases must be shifted by n nu t0
  const int cycles = 3, per_cycle = 64, n_max = 10;
  const std::vector<Component> parts = {
      {1, 3.0, 0.4}, {3, 1.5, -2.0}, {5, 0.2, 3.0}, {10, 0.05, -3.1}};
  const std::vector<double> y = sample(0.7, parts, cycles, per_cycle, f, t0);
  const std::vector<Harmonic> h = harmonics(y, cycles, f, t0, n_max);
  ASSERT_EQ(h.size(), 11u);
  EXPECT_NEAR(h[0].amplitude, 0.7, kIdentity);
  EXPECT_DOUBLE_EQ(h[0].phase, kPi / 2.0);
  std::vector<double> expected(11, 0.0);
  for (const Component& c : parts) {
    expected[static_cast<std::size_t>(c.n)] = c.amplitude;
    EXPECT_NEAR(angle_diff(h[static_cast<std::size_t>(c.n)].phase, c.phase), 0.0, kIdentity)
        << "n = " << c.n;
  }
  for (std::size_t n = 1; n < h.size(); ++n) {
    EXPECT_NEAR(h[n].amplitude, expected[n], kIdentity) << "n = " << n;
    EXPECT_GT(h[n].phase, -kPi);
    EXPECT_LE(h[n].phase, kPi);
  }
}

// The same signal recorded from different start times has the same absolute-time phases; a
// sine started a quarter period late (samples of a cosine) still has phase 0.
TEST(Harmonics, PhasesReferToAbsoluteTime) {
  const double f = 30.0;
  for (double t0 : {0.0, 0.25 / f, 7.0 / f, 7.61 / f, 123.0 / f}) {
    const std::vector<double> y = sample(0.0, {{1, 2.0, 0.0}, {2, 1.0, -1.2}}, 2, 32, f, t0);
    const std::vector<Harmonic> h = harmonics(y, 2, f, t0, 3);
    EXPECT_NEAR(h[1].amplitude, 2.0, kIdentity) << "t0 = " << t0;
    EXPECT_NEAR(angle_diff(h[1].phase, 0.0), 0.0, kIdentity) << "t0 = " << t0;
    EXPECT_NEAR(angle_diff(h[2].phase, -1.2), 0.0, kIdentity) << "t0 = " << t0;
  }
}

// A half-wave antisymmetric signal y(t + T/2) = -y(t) holds only odd harmonics, whatever its
// shape (here not band-limited, so the odd ones alias, but the even bins stay zero). Its square
// holds only even ones and a mean.
TEST(Harmonics, ParityOfOddAndEvenSignals) {
  const double f = 25.0, t0 = 1.234;
  const int cycles = 2, per_cycle = 128;
  const std::size_t size = static_cast<std::size_t>(cycles * per_cycle);
  std::vector<double> odd(size), even(size);
  for (std::size_t j = 0; j < size; ++j) {
    const double t = t0 + static_cast<double>(j) / (f * per_cycle);
    odd[j] = std::tanh(3.0 * std::sin(2.0 * kPi * f * t + 0.2));
    even[j] = odd[j] * odd[j];
  }
  const std::vector<Harmonic> ho = harmonics(odd, cycles, f, t0, 20);
  const std::vector<Harmonic> he = harmonics(even, cycles, f, t0, 20);
  EXPECT_GT(ho[1].amplitude, 1.0);
  EXPECT_GT(ho[3].amplitude, 0.1);
  EXPECT_GT(he[2].amplitude, 0.1);
  EXPECT_GT(he[0].amplitude, 0.5);
  EXPECT_NEAR(ho[0].amplitude, 0.0, kIdentity);
  for (std::size_t n = 1; n <= 20; ++n) {
    if (n % 2 == 0) {
      EXPECT_NEAR(ho[n].amplitude, 0.0, kIdentity) << "n = " << n;
    } else {
      EXPECT_NEAR(he[n].amplitude, 0.0, kIdentity) << "n = " << n;
    }
  }
}

// n = 0 carries the mean as |mean| with phase +-pi/2, so A_0 sin(theta_0) = mean.
TEST(Harmonics, MeanAndItsSign) {
  const double f = 10.0;
  for (double mean : {2.5, -2.5, 0.0}) {
    const std::vector<double> y = sample(mean, {{1, 1.0, 0.3}}, 1, 16, f, 0.05);
    const std::vector<Harmonic> h = harmonics(y, 1, f, 0.05, 0);
    ASSERT_EQ(h.size(), 1u);
    EXPECT_GE(h[0].amplitude, 0.0);
    EXPECT_NEAR(h[0].amplitude, std::abs(mean), kIdentity);
    EXPECT_NEAR(h[0].amplitude * std::sin(h[0].phase), mean, kIdentity);
  }
}

// The highest harmonic below Nyquist is resolved; n = samples_per_cycle/2 is refused.
TEST(Harmonics, HighestHarmonicBelowNyquist) {
  const double f = 50.0;
  const std::vector<double> y = sample(0.0, {{3, 0.8, 1.0}}, 2, 8, f, 0.3);
  const std::vector<Harmonic> h = harmonics(y, 2, f, 0.3, 3);
  EXPECT_NEAR(h[3].amplitude, 0.8, kIdentity);
  EXPECT_NEAR(angle_diff(h[3].phase, 1.0), 0.0, kIdentity);
  expect_error([&] { harmonics(y, 2, f, 0.3, 4); }, {"n_max", "Nyquist", "8 samples per cycle"});
}

// A signal is absent when every component of its spectrum (mean included) is at most 1e-6 of the
// largest component of the two spectra; a signal small against the other but above that is not.
TEST(AbsentSignals, EveryComponentAgainstTheLargestOfBoth) {
  auto spectrum = [](std::vector<double> a) {
    Spectrum h;
    for (double v : a) h.push_back({v, 0.3});
    return h;
  };
  const Spectrum z = spectrum({2.0, 25.0, 3.7, 2.7});
  // The directed vertical exciter's x_M'' (round-off) against its z_M''.
  AbsentSignals a = absent_signals(spectrum({1e-23, 3e-22, 7e-23, 1.3e-22}), z);
  EXPECT_TRUE(a.ddx);
  EXPECT_FALSE(a.ddz);
  // The same the other way round.
  a = absent_signals(z, spectrum({1e-23, 3e-22, 7e-23, 1.3e-22}));
  EXPECT_FALSE(a.ddx);
  EXPECT_TRUE(a.ddz);
  // Just below the threshold (1e-6 of 25) absent, just above it present; the mean counts as a
  // component.
  EXPECT_TRUE(absent_signals(spectrum({0.0, 24.9e-6, 0.0, 0.0}), z).ddx);
  EXPECT_FALSE(absent_signals(spectrum({0.0, 25.1e-6, 0.0, 0.0}), z).ddx);
  EXPECT_FALSE(absent_signals(spectrum({1e-3, 0.0, 0.0, 0.0}), z).ddx);
  // A signal without a fundamental (z_M'' of the oscillation drum without driving torque: even
  // harmonics only) is present.
  EXPECT_FALSE(absent_signals(z, spectrum({0.0, 1e-9, 3.1, 1e-9})).ddz);
  // Two signals of round-off (a drum without friction: 1e-16 m/s^2): both absent, below the
  // floor of 1e-12 g, though each is far above 1e-6 of the other; just above the floor present.
  a = absent_signals(spectrum({3e-16, 1.5e-16, 1.5e-16}), spectrum({1e-15, 1.5e-16, 1.5e-16}));
  EXPECT_TRUE(a.ddx && a.ddz);
  a = absent_signals(spectrum({0.0, 1.1e-11, 0.0}), spectrum({0.0, 0.9e-11, 0.0}));
  EXPECT_FALSE(a.ddx);
  EXPECT_TRUE(a.ddz);
  // Two dead channels: both absent.
  a = absent_signals(spectrum({0.0, 0.0}), spectrum({0.0, 0.0}));
  EXPECT_TRUE(a.ddx && a.ddz);
}

TEST(Harmonics, RejectsBadInput) {
  const std::vector<double> y(12, 1.0);
  expect_error([] { harmonics({}, 1, 1.0, 0.0, 0); }, {"empty"});
  expect_error([&] { harmonics(y, 0, 1.0, 0.0, 0); }, {"cycles", ">= 1", "got 0"});
  expect_error([&] { harmonics(y, 5, 1.0, 0.0, 0); }, {"multiple of cycles", "12", "5"});
  expect_error([&] { harmonics(y, 2, 0.0, 0.0, 0); }, {"frequency", "> 0"});
  expect_error([&] { harmonics(y, 2, -3.0, 0.0, 0); }, {"frequency", "> 0"});
  expect_error([&] { harmonics(y, 2, std::nan(""), 0.0, 0); }, {"frequency", "finite"});
  expect_error([&] { harmonics(y, 2, INFINITY, 0.0, 0); }, {"frequency", "finite"});
  expect_error([&] { harmonics(y, 2, 1.0, std::nan(""), 0); }, {"t0", "finite"});
  expect_error([&] { harmonics(y, 2, 1.0, 0.0, -1); }, {"n_max", ">= 0", "-1"});
  expect_error([&] { harmonics(y, 2, 1.0, 0.0, 3); }, {"n_max", "Nyquist"});
  EXPECT_NO_THROW(harmonics(y, 2, 1.0, 0.0, 2));  // 6 samples per cycle: n = 2 < 3
}

// ---------------------------------------------------------------------------------------------
// enclosed_area

TEST(EnclosedArea, UnitSquareBothOrientations) {
  const std::vector<double> x = {0, 1, 1, 0}, y = {0, 0, 1, 1};
  EXPECT_NEAR(enclosed_area(x, y), 1.0, kIdentity);
  const std::vector<double> xr(x.rbegin(), x.rend()), yr(y.rbegin(), y.rend());
  EXPECT_NEAR(enclosed_area(xr, yr), 1.0, kIdentity);
  // Repeated points, a collinear extra vertex and a start in the middle of an edge change
  // nothing.
  const std::vector<double> x2 = {0.5, 1, 1, 1, 1, 0, 0, 0, 0}, y2 = {0, 0, 0, 0.4, 1, 1, 1, 0, 0};
  EXPECT_NEAR(enclosed_area(x2, y2), 1.0, kIdentity);
}

// A simple polygon: the area is the shoelace area, whatever the position of the origin.
TEST(EnclosedArea, CirclePolygonEqualsShoelace) {
  const double r = 2.0;
  for (int n : {3, 7, 1000}) {
    for (double offset : {0.0, 1e3}) {
      std::vector<double> x, y;
      for (int j = 0; j < n; ++j) {
        const double a = 2.0 * kPi * j / n + 0.1;
        x.push_back(offset + r * std::cos(a));
        y.push_back(-offset + r * std::sin(a));
      }
      const double exact = 0.5 * n * r * r * std::sin(2.0 * kPi / n);  // regular n-gon
      // Round-off grows with the offset: relative eps * offset / r per trapezoid.
      const double tol = kIdentity * (1.0 + offset);
      EXPECT_NEAR(enclosed_area(x, y), exact, tol) << "n = " << n << " offset = " << offset;
      if (n == 1000) {
        // The polygon converges to the circle: pi r^2 - (n/2) r^2 sin(2 pi/n) is
        // 2 pi^3 r^2 / (3 n^2) to leading order; allow a factor 1.5 for the higher orders.
        const double leading = 2.0 * kPi * kPi * kPi * r * r / (3.0 * n * n);
        EXPECT_GT(kPi * r * r - enclosed_area(x, y), 0.0);  // inscribed: smaller than the disc
        EXPECT_NEAR(enclosed_area(x, y), kPi * r * r, 1.5 * leading);
      }
    }
  }
}

// Lemniscate of Gerono x = sin t, y = sin t cos t: a figure-eight whose lobes have opposite
// orientation. The signed shoelace sum cancels; enclosed_area is the sum of the lobe areas.
TEST(EnclosedArea, GeronoLemniscateCountsBothLobes) {
  struct Case {
    int n;
    double offset;  // t_j = 2 pi (j + offset) / n
  };
  // offset 1/2: neither pass through the node is a vertex; offset 0: one or both are vertices.
  for (const Case c :
       {Case{400, 0.5}, Case{401, 0.5}, Case{400, 0.0}, Case{401, 0.0}, Case{65536, 0.5}}) {
    std::vector<double> x, y;
    for (int j = 0; j < c.n; ++j) {
      const double t = 2.0 * kPi * (j + c.offset) / c.n;
      x.push_back(std::sin(t));
      y.push_back(std::sin(t) * std::cos(t));
    }
    SCOPED_TRACE("n = " + std::to_string(c.n) + ", offset = " + std::to_string(c.offset));
    EXPECT_NEAR(shoelace(x, y), 0.0, kIdentity);
    // The samples are symmetric under t -> -t, i.e. (x, y) -> (-x, -y), so the two edges that
    // pass the node cross at the origin (or end there). Each lobe alone is then a simple polygon:
    // the node (0, 0) followed by the lobe's vertices (x > 0: t in (0, pi); x <= 0: the rest).
    std::vector<double> lx = {0.0}, ly = {0.0}, rx = {0.0}, ry = {0.0};
    for (std::size_t j = 0; j < x.size(); ++j) {
      (x[j] > 0.0 ? rx : lx).push_back(x[j]);
      (x[j] > 0.0 ? ry : ly).push_back(y[j]);
    }
    const double lobes = std::abs(shoelace(rx, ry)) + std::abs(shoelace(lx, ly));
    EXPECT_NEAR(enclosed_area(x, y), lobes, kIdentity);
    // The polygon converges to the continuous Gerono area 4/3. An inscribed polygon with uniform
    // parameter step h misses segments of area h^3/12 |x'y'' - y'x''| each; the total,
    // h^2/12 * (integral of |x'y'' - y'x''| dt = 20/3), is 20 pi^2 / (9 n^2). What remains is
    // O(1/n^4).
    const double n2 = double(c.n) * c.n;
    EXPECT_NEAR(enclosed_area(x, y), 4.0 / 3.0 - 20.0 * kPi * kPi / (9.0 * n2),
                200.0 / (n2 * n2) + kIdentity);
  }
}

// A circle traversed twice has winding 2 inside: counted once.
TEST(EnclosedArea, DoublyTraversedCircleCountsOnce) {
  const int n = 360;
  std::vector<double> x, y;
  for (int j = 0; j < 2 * n; ++j) {
    const double a = 2.0 * kPi * j / n;
    x.push_back(3.0 * std::cos(a));
    y.push_back(3.0 * std::sin(a));
  }
  const std::vector<double> x1(x.begin(), x.begin() + n), y1(y.begin(), y.begin() + n);
  EXPECT_NEAR(enclosed_area(x, y), shoelace(x1, y1), kIdentity);
  EXPECT_NEAR(shoelace(x, y), 2.0 * shoelace(x1, y1), kIdentity);  // what a signed sum would give
}

// The sweep's work: every slab between two point heights of a convex polygon is crossed by two
// edges, of the same circle run m times by 2 m; the count grows with the windings, not the area.
TEST(EnclosedArea, SweepVisitsCountEdgesPerSlab) {
  const int n = 90;
  for (int m : {1, 3}) {
    std::vector<double> x, y;
    for (int j = 0; j < m * n; ++j) {
      const double a = 2.0 * kPi * (j + 0.25) / n;  // no two points at one height within a turn
      x.push_back(std::cos(a));
      y.push_back(std::sin(a));
    }
    std::vector<double> levels(y.begin(), y.end());
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    EXPECT_EQ(detail::sweep_visits(x, y), 2 * static_cast<std::size_t>(m) * (levels.size() - 1));
  }
  EXPECT_EQ(detail::sweep_visits(std::vector<double>{0.0, 1.0}, std::vector<double>{0.0, 1.0}), 0u);
}

// The one-pair test of crossing chords against the slab sweep's crossings, on random polygons
// (random points: many crossings; no two points at one height, where the sweep reports none),
// and the cases it must refuse: edges that join, touch at an end, or run along one line.
TEST(EnclosedArea, ChordsCrossAsTheSweepFindsThem) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 5 + static_cast<std::size_t>(trial) * 3;
    std::vector<double> x(n), y(n);
    for (std::size_t k = 0; k < n; ++k) x[k] = u(rng), y[k] = u(rng);
    auto expected = detail::polygon_crossings(x, y);
    for (auto& [i, j] : expected)
      if (i > j) std::swap(i, j);
    std::sort(expected.begin(), expected.end());
    std::vector<std::pair<std::size_t, std::size_t>> found;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (detail::chords_cross(x, y, i, j)) found.emplace_back(i, j);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(found, expected) << "trial " << trial;
  }
  // A square's sides join or lie apart; its diagonals (a bow tie) cross.
  const std::vector<double> sx{0.0, 1.0, 1.0, 0.0}, sy{0.0, 0.0, 1.0, 1.0};
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) EXPECT_FALSE(detail::chords_cross(sx, sy, i, j));
  const std::vector<double> bx{0.0, 1.0, 0.0, 1.0}, by{0.0, 1.0, 1.0, 0.0};
  EXPECT_TRUE(detail::chords_cross(bx, by, 0, 2));
  EXPECT_TRUE(detail::chords_cross(bx, by, 2, 0));
  // An edge ending on another (a T), and two edges along one line, do not cross strictly.
  const std::vector<double> tx{0.0, 2.0, 1.0, 1.0, 3.0}, ty{0.0, 0.0, 0.0, 1.0, 1.0};
  EXPECT_FALSE(detail::chords_cross(tx, ty, 0, 2));
  const std::vector<double> lx{0.0, 2.0, 1.0, 3.0}, ly{0.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(detail::chords_cross(lx, ly, 0, 2));
}

// One closed polygon: outer circle, a bridge to an inner circle, the inner circle, back over the
// bridge. Inner loop reversed: winding 0 in the hole (excluded). Inner loop the same way: winding
// 2 in the hole (included).
TEST(EnclosedArea, HoleExcludedOnlyWhenItsWindingIsZero) {
  const int n = 200;
  const double r_out = 2.0, r_in = 0.8, start = 0.3;  // a slanted bridge: not a horizontal edge
  std::vector<double> ox, oy, ix, iy;
  for (int j = 0; j <= n; ++j) {  // closed loops: the start point is repeated at the end
    const double a = start + 2.0 * kPi * j / n;
    ox.push_back(r_out * std::cos(a));
    oy.push_back(r_out * std::sin(a));
    ix.push_back(r_in * std::cos(a));
    iy.push_back(r_in * std::sin(a));
  }
  const double outer = shoelace(ox, oy), inner = shoelace(ix, iy);
  ASSERT_GT(outer, 0.0);  // counter-clockwise
  for (bool reversed : {true, false}) {
    std::vector<double> x = ox, y = oy;
    if (reversed) {
      x.insert(x.end(), ix.rbegin(), ix.rend());
      y.insert(y.end(), iy.rbegin(), iy.rend());
    } else {
      x.insert(x.end(), ix.begin(), ix.end());
      y.insert(y.end(), iy.begin(), iy.end());
    }
    const double expected = reversed ? outer - inner : outer;
    EXPECT_NEAR(enclosed_area(x, y), expected, kIdentity) << "reversed = " << reversed;
  }
}

/// Winding number of (px, py) with respect to the closed polygon (crossing count of a ray to
/// +x, signed by edge direction): a brute-force reference independent of the slab sweep.
int winding_number(const std::vector<double>& x, const std::vector<double>& y, double px,
                   double py) {
  int w = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::size_t k = (i + 1) % x.size();
    const bool up = y[i] <= py && y[k] > py;
    const bool down = y[i] > py && y[k] <= py;
    if (!up && !down) continue;
    const double xc = x[i] + (py - y[i]) / (y[k] - y[i]) * (x[k] - x[i]);
    if (xc > px) w += up ? 1 : -1;
  }
  return w;
}

/// Midpoint-grid estimate of the non-zero-winding area and a bound on its error: only cells
/// cut by the boundary can be misclassified, and a boundary of length L cuts at most about
/// L / h + 4 * edges cells of a grid of spacing h (each at most h^2).
struct GridEstimate {
  double area, bound;
};
GridEstimate grid_area(const std::vector<double>& x, const std::vector<double>& y, int cells) {
  const auto [x0, x1] = std::minmax_element(x.begin(), x.end());
  const auto [y0, y1] = std::minmax_element(y.begin(), y.end());
  const double hx = (*x1 - *x0) / cells, hy = (*y1 - *y0) / cells;
  long inside = 0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      if (winding_number(x, y, *x0 + (i + 0.5) * hx, *y0 + (j + 0.5) * hy) != 0) ++inside;
    }
  }
  double perimeter = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::size_t k = (i + 1) % x.size();
    perimeter += std::abs(x[k] - x[i]) / hx + std::abs(y[k] - y[i]) / hy;  // cells crossed
  }
  const double cell = hx * hy;
  return {static_cast<double>(inside) * cell, (perimeter + 4.0 * double(x.size())) * cell};
}

/// Exact non-zero-winding area by brute force, independent of the slab sweep: the heights of all
/// vertices and of all pairwise edge crossings (O(n^2) pairs) cut the plane into bands in which
/// no edge starts, ends or crosses another, so the covered length L(y) along a horizontal line
/// is linear in y there and the band's area is its height times L at mid-height. L(y_mid) comes
/// from the crossings of that one line with every edge, sorted by x, with the winding summed.
double brute_force_area(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<double> levels(y.begin(), y.end());
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t i1 = (i + 1) % n;
    for (std::size_t k = i + 1; k < n; ++k) {
      const std::size_t k1 = (k + 1) % n;
      const double rx = x[i1] - x[i], ry = y[i1] - y[i], vx = x[k1] - x[k], vy = y[k1] - y[k];
      const double denom = rx * vy - ry * vx;
      if (denom == 0.0) continue;  // parallel: no crossing that changes the order
      const double qx = x[k] - x[i], qy = y[k] - y[i];
      const double s = (qx * vy - qy * vx) / denom, t = (qx * ry - qy * rx) / denom;
      if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0) levels.push_back(y[i] + s * ry);
    }
  }
  std::sort(levels.begin(), levels.end());
  double area = 0.0;
  for (std::size_t b = 0; b + 1 < levels.size(); ++b) {
    const double lo = levels[b], hi = levels[b + 1];
    if (!(hi > lo)) continue;
    const double mid = 0.5 * (lo + hi);
    std::vector<std::pair<double, int>> hits;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t i1 = (i + 1) % n;
      if ((y[i] < mid) == (y[i1] < mid)) continue;
      hits.emplace_back(x[i] + (mid - y[i]) / (y[i1] - y[i]) * (x[i1] - x[i]),
                        y[i1] > y[i] ? 1 : -1);
    }
    std::sort(hits.begin(), hits.end());
    int winding = 0;
    for (std::size_t h = 0; h + 1 < hits.size(); ++h) {
      winding += hits[h].second;
      if (winding != 0) area += (hi - lo) * (hits[h + 1].first - hits[h].first);
    }
  }
  return area;
}

// Pentagram {5/2}: the central pentagon has winding 2 and is included. Exact reference: the
// star's outline, a simple 10-gon through the tips and the inner crossings.
TEST(EnclosedArea, PentagramIncludesCentre) {
  const double r = 1.5;
  std::vector<double> x, y;
  for (int j = 0; j < 5; ++j) {
    const double a = kPi / 2.0 + 2.0 * kPi * (2 * j % 5) / 5.0;
    x.push_back(r * std::cos(a));
    y.push_back(r * std::sin(a));
  }
  const double r_inner = r * std::cos(2.0 * kPi / 5.0) / std::cos(kPi / 5.0);
  std::vector<double> sx, sy;
  for (int j = 0; j < 10; ++j) {
    const double a = kPi / 2.0 + kPi * j / 5.0;
    const double rr = (j % 2 == 0) ? r : r_inner;
    sx.push_back(rr * std::cos(a));
    sy.push_back(rr * std::sin(a));
  }
  const double star = shoelace(sx, sy);
  EXPECT_NEAR(enclosed_area(x, y), star, kIdentity);
  // The signed shoelace sum counts the centre twice: the two differ by the central pentagon.
  const double pentagon = 2.5 * r_inner * r_inner * std::sin(2.0 * kPi / 5.0);
  EXPECT_NEAR(shoelace(x, y), star + pentagon, kIdentity);
  const GridEstimate g = grid_area(x, y, 600);
  EXPECT_NEAR(enclosed_area(x, y), g.area, g.bound);
}

// Random self-intersecting polygons (many crossings, several inside one slab) against the exact
// brute-force reference and the grid estimate; scaling, translation, another start vertex and
// the reverse traversal act as they must.
TEST(EnclosedArea, RandomSelfIntersectingPolygons) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    const int n = 8 + 7 * trial;
    std::vector<double> x(static_cast<std::size_t>(n)), y(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
      x[static_cast<std::size_t>(j)] = u(rng);
      y[static_cast<std::size_t>(j)] = u(rng);
    }
    const double area = enclosed_area(x, y);
    EXPECT_NEAR(area, brute_force_area(x, y), kIdentity) << "trial " << trial;
    const GridEstimate g = grid_area(x, y, 300);
    EXPECT_NEAR(area, g.area, g.bound) << "trial " << trial;
    EXPECT_GE(area, std::abs(shoelace(x, y)) / n);  // non-trivial region found
    EXPECT_LE(area, 4.0);                           // inside the bounding box
    std::vector<double> xs = x, ys = y;
    for (std::size_t j = 0; j < xs.size(); ++j) {
      xs[j] = 50.0 * xs[j] + 7.0;
      ys[j] = 5.0 * ys[j] - 3.0;
    }
    EXPECT_NEAR(enclosed_area(xs, ys), 250.0 * area, 250.0 * kIdentity) << "trial " << trial;
    // Starting the traversal elsewhere or reversing it changes nothing.
    std::rotate(x.begin(), x.begin() + 3, x.end());
    std::rotate(y.begin(), y.begin() + 3, y.end());
    EXPECT_NEAR(enclosed_area(x, y), area, kIdentity);
    std::reverse(x.begin(), x.end());
    std::reverse(y.begin(), y.end());
    EXPECT_NEAR(enclosed_area(x, y), area, kIdentity);
  }
}

TEST(EnclosedArea, DegenerateInputs) {
  EXPECT_EQ(enclosed_area({}, {}), 0.0);
  const std::vector<double> one = {1.0}, two = {1.0, 2.0};
  EXPECT_EQ(enclosed_area(one, one), 0.0);
  EXPECT_EQ(enclosed_area(two, two), 0.0);
  const std::vector<double> line_x = {0, 1, 2, 3}, line_y = {0, 2, 4, 6};  // collinear
  EXPECT_NEAR(enclosed_area(line_x, line_y), 0.0, kIdentity);
  const std::vector<double> same = {4, 4, 4, 4};
  EXPECT_EQ(enclosed_area(same, same), 0.0);
  const std::vector<double> flat_x = {0, 1, 2}, flat_y = {3, 3, 3};  // horizontal only
  EXPECT_EQ(enclosed_area(flat_x, flat_y), 0.0);
  // A segment walked there and back encloses nothing.
  const std::vector<double> back_x = {0, 1, 2, 1}, back_y = {0, 1, 2, 1};
  EXPECT_NEAR(enclosed_area(back_x, back_y), 0.0, kIdentity);
}

// The area of a closed parametric curve (x(t), y(t)) from n points and the exact bulges of its
// arcs: bulge_j = integral of (x - x_mean) dy over the arc from t_j to t_j+1 (x_mean the mean of
// the chord's ends), by 20-point Gauss-Legendre (exact to round-off for these smooth arcs).
struct CurveArea {
  std::vector<double> x, y, bulge;
};
CurveArea curve_with_bulges(const std::function<std::pair<double, double>(double)>& r,
                            const std::function<std::pair<double, double>(double)>& dr,
                            const std::vector<double>& t) {
  // 20-point Gauss-Legendre nodes by Newton on P_20.
  constexpr int m = 20;
  std::vector<double> nodes, weights;
  for (int i = 1; i <= m; ++i) {
    double z = std::cos(kPi * (i - 0.25) / (m + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= m; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = m * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    nodes.push_back(z);
    weights.push_back(2.0 / ((1.0 - z * z) * dp * dp));
  }
  CurveArea c;
  const std::size_t n = t.size() - 1;  // t.back() closes the curve (the point of t.front())
  for (std::size_t j = 0; j < n; ++j) {
    const auto [xa, ya] = r(t[j]);
    const auto [xb, yb] = r(t[j + 1]);
    c.x.push_back(xa);
    c.y.push_back(ya);
    const double mean = 0.5 * (xa + xb), half = 0.5 * (t[j + 1] - t[j]),
                 mid = 0.5 * (t[j] + t[j + 1]);
    double sum = 0.0;
    for (int i = 0; i < m; ++i) {
      const double s = mid + half * nodes[i];
      sum += weights[i] * (r(s).first - mean) * dr(s).second;
    }
    c.bulge.push_back(half * sum);
  }
  return c;
}

std::vector<double> uniform(double a, double b, int n) {
  std::vector<double> t;
  for (int j = 0; j <= n; ++j) t.push_back(a + (b - a) * j / n);
  return t;
}

// An ellipse from 7 points (and, reversed, clockwise) with its bulges: exactly pi a b, where the
// polygon alone misses 14 % of it.
TEST(EnclosedAreaOfCurve, EllipseIsExact) {
  const double a = 3.0, b = 0.5;
  for (double sense : {1.0, -1.0}) {
    const auto c = curve_with_bulges(
        [&](double t) {
          return std::pair{a * std::cos(t), sense * b * std::sin(t)};
        },
        [&](double t) {
          return std::pair{-a * std::sin(t), sense * b * std::cos(t)};
        },
        uniform(0.3, 0.3 + 2.0 * kPi, 7));
    EXPECT_LT(enclosed_area(c.x, c.y), 0.9 * kPi * a * b);
    EXPECT_NEAR(enclosed_area(c.x, c.y, c.bulge), kPi * a * b, 1e-14 * kPi * a * b) << sense;
  }
}

// The Gerono lemniscate x = sin t, y = sin t cos t (a figure-eight, lobes of opposite
// orientation, 2/3 each) from 10 points with its node (t = 0 and pi) among them: exact. With the
// node inside an arc, the error is of the order of that arc's bulge.
TEST(EnclosedAreaOfCurve, FigureEightIsExactWhenTheNodeIsAPoint) {
  const auto r = [](double t) { return std::pair{std::sin(t), std::sin(t) * std::cos(t)}; };
  const auto dr = [](double t) { return std::pair{std::cos(t), std::cos(2.0 * t)}; };
  const auto c = curve_with_bulges(r, dr, uniform(0.0, 2.0 * kPi, 10));
  EXPECT_NEAR(enclosed_area(c.x, c.y, c.bulge), 4.0 / 3.0, 1e-14);
  // A crossing inside an arc of 400: off by about one arc's bulge, far better than the polygon.
  const auto d = curve_with_bulges(r, dr, uniform(0.001, 0.001 + 2.0 * kPi, 400));
  const double bulge = std::abs(d.bulge[0]);
  EXPECT_GT(std::abs(enclosed_area(d.x, d.y) - 4.0 / 3.0), 100.0 * bulge);
  EXPECT_LT(std::abs(enclosed_area(d.x, d.y, d.bulge) - 4.0 / 3.0), 4.0 * bulge);
}

// A curve with a horizontal chord (the ellipse sampled symmetrically: the chord through the top
// and another through the bottom) and a circle traversed twice (winding 2 inside: every chord
// borders the outside, each bulge counts once per pass... but the region once).
TEST(EnclosedAreaOfCurve, HorizontalChordsAndDoubleTraversal) {
  const double a = 2.0, b = 1.0;
  const auto r = [&](double t) { return std::pair{a * std::cos(t), b * std::sin(t)}; };
  const auto dr = [&](double t) { return std::pair{-a * std::sin(t), b * std::cos(t)}; };
  // t_j = pi/2 - pi/8 + 2 pi j / 8: the first chord joins two points of equal height.
  const auto c =
      curve_with_bulges(r, dr, uniform(kPi / 2 - kPi / 8, kPi / 2 - kPi / 8 + 2 * kPi, 8));
  ASSERT_EQ(c.y[0], c.y[1]);
  EXPECT_NEAR(enclosed_area(c.x, c.y, c.bulge), kPi * a * b, 1e-14 * kPi * a * b);
  // Twice around the unit circle in 2 x 5 points: every chord is on the boundary twice (the
  // two passes share their points), the region counts once.
  const auto d = curve_with_bulges(
      [](double t) {
        return std::pair{std::cos(t), std::sin(t)};
      },
      [](double t) {
        return std::pair{-std::sin(t), std::cos(t)};
      },
      uniform(0.0, 4.0 * kPi, 10));
  EXPECT_NEAR(enclosed_area(d.x, d.y, d.bulge), kPi, 1e-14 * kPi);
}

TEST(EnclosedAreaOfCurve, RejectsBadInput) {
  const std::vector<double> x = {0, 1, 1}, y = {0, 0, 1}, b = {0, 0};
  expect_error([&] { enclosed_area(x, y, b); }, {"bulge", "2", "3"});
}

TEST(EnclosedArea, RejectsBadInput) {
  const std::vector<double> x = {0, 1, 1}, y = {0, 0, 1}, y2 = {0, 0};
  expect_error([&] { enclosed_area(x, y2); }, {"same size", "3", "2"});
  const std::vector<double> bad = {0, std::nan(""), 1};
  expect_error([&] { enclosed_area(x, bad); }, {"finite", "point 1"});
  const std::vector<double> inf = {0, 1, INFINITY};
  expect_error([&] { enclosed_area(inf, y); }, {"finite", "point 2"});
}

// ---------------------------------------------------------------------------------------------
// compute_metrics

struct Synthetic {
  double f = 30.0;
  int periods = 2;
  int per_period = 256;
  double t0 = 37.0 / 30.0;
  double x_amp = 50.0, x_phase = 0.3;
  double z_amp = 5.0, z_phase = 0.9;
  double phi_amp = 1e-3, phi_phase = -0.84 * kPi;
  double drift = 2.0;  // net rotation rate [rad/s]
};

Result make_result(const Synthetic& s) {
  Result r;
  r.frequency = s.f;
  r.sample_periods = s.periods;
  r.samples_per_period = s.per_period;
  r.diagnostics.multiplicity = 1;
  const double nu = 2.0 * kPi * s.f;
  const int n = s.periods * s.per_period;
  for (int j = 0; j < n; ++j) {
    const double t = s.t0 + j / (s.f * s.per_period);
    r.samples.t.push_back(t);
    r.samples.ddx_M.push_back(s.x_amp * std::sin(nu * t + s.x_phase));
    r.samples.ddz_M.push_back(s.z_amp * std::sin(2.0 * nu * t + s.z_phase));
    r.samples.phi.push_back(0.3 + s.drift * t + s.phi_amp * std::sin(nu * t + s.phi_phase));
    r.samples.dphi.push_back(s.drift + s.phi_amp * nu * std::cos(nu * t + s.phi_phase));
    r.samples.phase.push_back(Phase::stick);
  }
  r.stick_time = 0.5;
  r.slip_positive_time = 0.3;
  r.slip_negative_time = 0.2;
  return r;
}

TEST(ComputeMetrics, SyntheticSinusoids) {
  for (double t0 : {37.0 / 30.0, 0.01234}) {  // a period multiple and an arbitrary start
    Synthetic s;
    s.t0 = t0;
    const Metrics m = compute_metrics(make_result(s), 10);
    SCOPED_TRACE("t0 = " + std::to_string(t0));
    // Sampled extremes: within the sampling's reach of the true peaks.
    const double reach = 1.0 - std::cos(2.0 * kPi / s.per_period);
    EXPECT_LE(m.ddx_max, 50.0);
    EXPECT_GE(m.ddx_max, 50.0 * (1.0 - reach));
    EXPECT_GE(m.ddx_min, -50.0);
    EXPECT_LE(m.ddx_min, -50.0 * (1.0 - reach));
    EXPECT_LE(m.ddz_max, 5.0);
    EXPECT_GE(m.ddz_max, 5.0 * (1.0 - reach));
    ASSERT_EQ(m.ddx_harmonics.size(), 11u);
    ASSERT_EQ(m.ddz_harmonics.size(), 11u);
    EXPECT_NEAR(m.ddx_harmonics[1].amplitude, 50.0, 50.0 * kIdentity);
    EXPECT_NEAR(angle_diff(m.ddx_harmonics[1].phase, 0.3), 0.0, kIdentity);
    EXPECT_NEAR(m.ddz_harmonics[2].amplitude, 5.0, 50.0 * kIdentity);
    EXPECT_NEAR(m.ddz_harmonics[1].amplitude, 0.0, 50.0 * kIdentity);
    EXPECT_NEAR(m.psi_xz, 0.9 - 2.0 * 0.3, kIdentity);
    // The ramp 0.3 + 2 t is removed; the lag of 1e-3 sin(nu t - 0.84 pi) is -0.84 pi.
    EXPECT_NEAR(m.phi_amplitude, 1e-3, 1e-3 * kIdentity);
    EXPECT_NEAR(m.phi_lag, -0.84, kIdentity);
    EXPECT_DOUBLE_EQ(m.stick_fraction, 0.5);
    EXPECT_DOUBLE_EQ(m.slip_positive_fraction, 0.3);
    EXPECT_DOUBLE_EQ(m.slip_negative_fraction, 0.2);
    EXPECT_GT(m.area, 0.0);
  }
}

// The Kb-type soil stiffness Re(F_v(f) / z_M(f)), F_v = N cos(delta) + T sin(delta) (25), by hand:
// z_M = 1e-3 sin(nu t + 0.2) + 0.5e-3 sin(2 nu t) (an overtone, which does not count), the drum
// tilted by delta = 0.1 rad with N and T chosen so that F_v = 4e4 + 6e4 sin(nu t + 0.2 + 0.7)
// (leading by 0.7 rad): kb = 6e4 / 1e-3 cos(0.7) = 6e7 cos(0.7) N/m. Without N, T or delta
// (a record of accelerations) it is unavailable.
TEST(ComputeMetrics, SoilStiffnessOfSyntheticForceAndDisplacement) {
  Synthetic s;
  Result r = make_result(s);
  const double nu = 2.0 * kPi * s.f, d = 0.1;
  EXPECT_TRUE(std::isnan(compute_metrics(r).kb));
  for (double t : r.samples.t) {
    const double Fv = 4e4 + 6e4 * std::sin(nu * t + 0.9), Fh = 1e4 * std::cos(3.0 * nu * t);
    // F_v = N cos + T sin and the horizontal part N sin - T cos = Fh (24): solved for N, T.
    r.samples.N.push_back(Fv * std::cos(d) + Fh * std::sin(d));
    r.samples.T.push_back(Fv * std::sin(d) - Fh * std::cos(d));
    r.samples.delta.push_back(d);
    r.samples.z_M.push_back(1e-3 * std::sin(nu * t + 0.2) + 0.5e-3 * std::sin(2.0 * nu * t));
  }
  EXPECT_NEAR(compute_metrics(r).kb, 6e7 * std::cos(0.7), 6e7 * kIdentity);
}

// Without a fundamental in z_M (the oscillation drum without driving torque: even harmonics only)
// kb is unavailable, also where z_M's 2f component passes zero: a z_M of its static mean, a
// round-off fundamental (1e-13 m) and no 2f component gave F_v(f) / 1e-13, a number of pure
// round-off, when the test compared the fundamental with the 2f component alone.
TEST(ComputeMetrics, SoilStiffnessWithoutAFundamentalIsUnavailable) {
  Synthetic s;
  Result r = make_result(s);
  const double nu = 2.0 * kPi * s.f, d = 0.1;
  for (double t : r.samples.t) {
    const double Fv = 4e4 + 6e4 * std::sin(nu * t + 0.9);
    r.samples.N.push_back(Fv * std::cos(d));
    r.samples.T.push_back(Fv * std::sin(d));
    r.samples.delta.push_back(d);
    r.samples.z_M.push_back(-2e-3 + 1e-13 * std::sin(nu * t) + 1e-4 * std::sin(4.0 * nu * t));
  }
  EXPECT_TRUE(std::isnan(compute_metrics(r).kb));
  // A fundamental of 1e-6 of the mean is one: kb from it.
  for (std::size_t j = 0; j < r.samples.t.size(); ++j)
    r.samples.z_M[j] += 1e-8 * std::sin(nu * r.samples.t[j] + 0.2);
  EXPECT_TRUE(std::isfinite(compute_metrics(r).kb));
}

// phi_lag lies in (-2, 0]: a fundamental with phase +0.16 pi (e.g. -1e-3 sin(nu t - 0.84 pi))
// reads -1.84; phase pi reads -1 (the no-soil limit of paper Fig. 10).
TEST(ComputeMetrics, PhiLagRange) {
  Synthetic s;
  s.phi_phase = 0.16 * kPi;
  EXPECT_NEAR(compute_metrics(make_result(s)).phi_lag, -1.84, kIdentity);
  s.phi_phase = kPi;
  EXPECT_NEAR(compute_metrics(make_result(s)).phi_lag, -1.0, kIdentity);
  s.phi_phase = -0.01 * kPi;
  s.drift = 0.0;
  EXPECT_NEAR(compute_metrics(make_result(s)).phi_lag, -0.01, kIdentity);
  s.phi_phase = 0.01 * kPi;  // just above 0: wraps to the far end of the range
  EXPECT_NEAR(compute_metrics(make_result(s)).phi_lag, -1.99, kIdentity);
  // With a torque column: a lag behind M0 sin(nu t) where it oscillates, NaN where it is
  // constant (the vibratory drum: M0 = 0; a driving torque MMd alone).
  Result r = make_result(s);
  const double nu = 2.0 * kPi * s.f;
  for (double MMd : {0.0, 2.5e3}) {
    r.samples.torque.assign(r.samples.t.size(), MMd);
    EXPECT_TRUE(std::isnan(compute_metrics(r).phi_lag)) << MMd;
    for (std::size_t j = 0; j < r.samples.t.size(); ++j)
      r.samples.torque[j] += 5e4 * std::sin(nu * r.samples.t[j]);
    EXPECT_NEAR(compute_metrics(r).phi_lag, -1.99, kIdentity) << MMd;
  }
}

// psi = 0: x = X sin(u), z = Z sin(2u) is a scaled Gerono lemniscate (x = X sin u,
// z / (2 Z) = sin u cos u): continuous area 2 X Z * 4/3. Its node lies at z = Z sin(psi) = 0.
TEST(ComputeMetrics, AreaOfSymmetricFigureEight) {
  Synthetic s;
  s.x_phase = 0.4;
  s.z_phase = 0.8;  // psi = 0
  const Metrics m = compute_metrics(make_result(s));
  EXPECT_NEAR(m.psi_xz, 0.0, kIdentity);
  const double continuous = 8.0 / 3.0 * s.x_amp * s.z_amp;
  // Polygon error O((2 pi / N)^2) relative (see the Gerono test): about 1e-3 of the area here.
  EXPECT_NEAR(m.area, continuous, continuous * 20.0 / (s.per_period * s.per_period));
}

// The area is taken over the first `multiplicity` periods only.
TEST(ComputeMetrics, AreaOverOneSteadyPeriod) {
  Synthetic s;
  s.periods = 3;
  Result r = make_result(s);
  // Periods 2 and 3 are scaled up: they must not enter when the steady period is one.
  const std::size_t per = static_cast<std::size_t>(s.per_period);
  for (std::size_t j = per; j < r.samples.size(); ++j) {
    r.samples.ddx_M[j] *= 3.0;
    r.samples.ddz_M[j] *= 3.0;
  }
  const std::vector<double> x1(r.samples.ddx_M.begin(), r.samples.ddx_M.begin() + per);
  const std::vector<double> z1(r.samples.ddz_M.begin(), r.samples.ddz_M.begin() + per);
  r.diagnostics.multiplicity = 1;
  EXPECT_DOUBLE_EQ(compute_metrics(r).area, enclosed_area(x1, z1));
  r.diagnostics.multiplicity = 0;  // none found: one period
  EXPECT_DOUBLE_EQ(compute_metrics(r).area, enclosed_area(x1, z1));
  r.diagnostics.multiplicity = 2;
  const std::vector<double> x2(r.samples.ddx_M.begin(), r.samples.ddx_M.begin() + 2 * per);
  const std::vector<double> z2(r.samples.ddz_M.begin(), r.samples.ddz_M.begin() + 2 * per);
  EXPECT_DOUBLE_EQ(compute_metrics(r).area, enclosed_area(x2, z2));
  r.diagnostics.multiplicity = 5;  // more than sampled: all samples
  EXPECT_DOUBLE_EQ(compute_metrics(r).area, enclosed_area(r.samples.ddx_M, r.samples.ddz_M));
}

// n_max < 2 still yields psi (the 2f harmonic is computed internally), and only n_max + 1
// harmonics are stored.
TEST(ComputeMetrics, SmallNMaxStillGivesPsi) {
  Synthetic s;
  for (int n_max : {0, 1}) {
    const Metrics m = compute_metrics(make_result(s), n_max);
    EXPECT_EQ(m.ddx_harmonics.size(), static_cast<std::size_t>(n_max) + 1);
    EXPECT_EQ(m.ddz_harmonics.size(), static_cast<std::size_t>(n_max) + 1);
    EXPECT_NEAR(m.psi_xz, 0.3, kIdentity);
  }
}

// No phase times recorded: the fractions come from the sampled phases.
TEST(ComputeMetrics, PhaseFractionsFromSamplesWhenNoTimes) {
  Synthetic s;
  Result r = make_result(s);
  r.stick_time = r.slip_positive_time = r.slip_negative_time = 0.0;
  const std::size_t n = r.samples.size();  // 512
  for (std::size_t j = 0; j < n; ++j) {
    r.samples.phase[j] =
        j < n / 2 ? Phase::stick : (j < 3 * n / 4 ? Phase::slip_positive : Phase::slip_negative);
  }
  const Metrics m = compute_metrics(r);
  EXPECT_DOUBLE_EQ(m.stick_fraction, 0.5);
  EXPECT_DOUBLE_EQ(m.slip_positive_fraction, 0.25);
  EXPECT_DOUBLE_EQ(m.slip_negative_fraction, 0.25);
}

TEST(ComputeMetrics, RejectsBadInput) {
  expect_error([] { compute_metrics(Result{}); }, {"no samples"});
  Synthetic s;
  {
    Result r = make_result(s);
    r.samples.ddz_M.pop_back();
    expect_error([&] { compute_metrics(r); }, {"ddz_M", "511", "512"});
  }
  {
    Result r = make_result(s);
    r.sample_periods = 3;
    expect_error([&] { compute_metrics(r); }, {"sample_periods * samples_per_period", "512"});
  }
  {
    Result r = make_result(s);
    r.samples_per_period = 0;
    expect_error([&] { compute_metrics(r); }, {"samples_per_period", ">= 1"});
  }
  {
    Result r = make_result(s);
    r.frequency = 0.0;
    expect_error([&] { compute_metrics(r); }, {"frequency"});
  }
  {
    Result r = make_result(s);
    r.stick_time = r.slip_positive_time = r.slip_negative_time = 0.0;
    r.samples.phase.clear();
    expect_error([&] { compute_metrics(r); }, {"samples.phase"});
  }
  expect_error([&] { compute_metrics(make_result(s), -1); }, {"n_max", ">= 0"});
  expect_error([&] { compute_metrics(make_result(s), 128); }, {"Nyquist"});
}

}  // namespace
}  // namespace oscidrum

namespace oscidrum {
namespace {

// delta's extremes come from the samples when they hold delta, and are NaN (no data) otherwise.
TEST(ComputeMetrics, DeltaExtremesAreOptional) {
  Result r;
  r.frequency = 39.0;
  r.sample_periods = 1;
  r.samples_per_period = 64;
  Samples& s = r.samples;
  for (int j = 0; j < 64; ++j) {
    const double t = j / (39.0 * 64);
    s.t.push_back(t);
    s.phi.push_back(0.0);
    s.dphi.push_back(0.0);
    s.ddx_M.push_back(std::sin(2 * M_PI * 39.0 * t));
    s.ddz_M.push_back(std::sin(4 * M_PI * 39.0 * t));
    s.phase.push_back(Phase::stick);
  }
  Metrics m = compute_metrics(r, 4);
  EXPECT_TRUE(std::isnan(m.delta_max));
  EXPECT_TRUE(std::isnan(m.delta_min));
  for (int j = 0; j < 64; ++j) s.delta.push_back(0.3 * std::sin(2 * M_PI * j / 64.0) + 0.01);
  m = compute_metrics(r, 4);
  EXPECT_NEAR(m.delta_max, 0.31, 1e-12);
  EXPECT_NEAR(m.delta_min, -0.29, 1e-12);
  s.delta.pop_back();
  EXPECT_THROW(compute_metrics(r, 4), Error);
}

// ---------------------------------------------------------------------------------------------
// Compaction indicators (docs/outputs.md) on band-limited signals, where each is known exactly.

TEST(Indicators, HarmonicRatiosCmvAndThdOfKnownSignals) {
  Synthetic s;
  Result r = make_result(s);
  const double nu = 2.0 * kPi * s.f;
  const std::size_t n = r.samples.size();
  r.samples.T.resize(n);
  r.samples.N.resize(n);
  r.samples.v_rel.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double t = r.samples.t[j];
    r.samples.ddx_M[j] = 0.7 + 40.0 * std::sin(nu * t + 0.2) + 6.0 * std::sin(2 * nu * t) +
                         9.0 * std::sin(3 * nu * t - 1.0) + 2.0 * std::sin(5 * nu * t);
    r.samples.ddz_M[j] =
        4.0 * std::sin(nu * t) + 3.0 * std::sin(2 * nu * t + 0.5) + 1.0 * std::sin(3 * nu * t);
    // Slip with T = -mu N, mu = 0.4, and v_rel = 0.05 (1 + sin) >= 0: mean |T v_rel| = 0.4 N 0.05.
    r.samples.N[j] = 40e3;
    r.samples.T[j] = -0.4 * 40e3;
    r.samples.v_rel[j] = 0.05 * (1.0 + std::sin(nu * t));
  }
  r.samples.T[7] = 0.45 * 40e3;  // one sample with a larger |T|/N
  r.samples.v_rel[7] = 0.05 * (1.0 + std::sin(nu * r.samples.t[7]));
  const Metrics m = compute_metrics(r, 10);
  EXPECT_NEAR(m.ddx_A2_A1, 6.0 / 40.0, kIdentity);
  EXPECT_NEAR(m.ddx_A3_A1, 9.0 / 40.0, kIdentity);
  EXPECT_NEAR(m.ddz_A2_A1, 3.0 / 4.0, kIdentity);
  EXPECT_NEAR(m.ddz_A3_A1, 1.0 / 4.0, kIdentity);
  EXPECT_NEAR(m.cmv, 300.0 * 3.0 / 4.0, 300.0 * kIdentity);
  // THD: sqrt(6^2 + 9^2 + 2^2) / 40; the mean 0.7 is no distortion.
  EXPECT_NEAR(m.ddx_thd, std::sqrt(36.0 + 81.0 + 4.0) / 40.0, kIdentity);
  EXPECT_NEAR(m.mu_required, 0.45, kIdentity);
  // Friction work per period: (mean of |T v_rel|) / f; sample 7 changes |T| there by 0.45/0.4.
  double power = 0.0;
  for (std::size_t j = 0; j < n; ++j) power += std::abs(r.samples.T[j] * r.samples.v_rel[j]);
  EXPECT_NEAR(m.friction_work, power / static_cast<double>(n) / s.f, 1e-12 * m.friction_work);
  EXPECT_NEAR(m.friction_work, 0.4 * 40e3 * 0.05 / s.f, 1e-3 * m.friction_work);
  EXPECT_DOUBLE_EQ(m.slip_fraction, 0.5);  // slip+ 0.3 + slip- 0.2 of make_result
}

TEST(Indicators, RatioToAnAbsentFundamentalIsNaN) {
  // z_M'' of a symmetric stick-slip cycle has only even harmonics (paper Fig. 19b): its
  // fundamental is noise, and a ratio to it is undefined, not a huge number.
  Synthetic s;
  Result r = make_result(s);  // ddz_M = 5 sin(2 nu t + 0.9): no f component
  const std::size_t n = r.samples.size();
  for (std::size_t j = 0; j < n; ++j)
    r.samples.ddz_M[j] += 1e-9 * std::sin(0.37 * static_cast<double>(j));
  const Metrics m = compute_metrics(r, 10);
  EXPECT_TRUE(std::isnan(m.ddz_A2_A1));
  EXPECT_TRUE(std::isnan(m.ddz_A3_A1));
  EXPECT_TRUE(std::isnan(m.cmv));
  EXPECT_NEAR(m.ddx_A2_A1, 0.0, kIdentity);  // x_M'' = 50 sin(nu t + 0.3): defined, zero
  EXPECT_NEAR(m.ddx_thd, 0.0, 1e-6);
  // Without T, N, v_rel (e.g. a record loaded as a Result) the friction metrics are NaN.
  EXPECT_TRUE(std::isnan(m.mu_required));
  EXPECT_TRUE(std::isnan(m.friction_work));
}

TEST(Indicators, ThdCountsSubharmonicsOfAMultiPeriodState) {
  // A 2-periodic steady state: the f/2 content of x_M'' is distortion too (everything but the
  // mean and the fundamental), as Parseval counts it.
  Synthetic s;
  s.periods = 2;
  Result r = make_result(s);
  r.diagnostics.multiplicity = 2;
  const double nu = 2.0 * kPi * s.f;
  for (std::size_t j = 0; j < r.samples.size(); ++j) {
    const double t = r.samples.t[j];
    r.samples.ddx_M[j] = 10.0 * std::sin(nu * t) + 3.0 * std::sin(0.5 * nu * t + 0.1);
  }
  const Metrics m = compute_metrics(r, 10);
  EXPECT_NEAR(m.ddx_thd, 0.3, kIdentity);
}

}  // namespace
}  // namespace oscidrum
