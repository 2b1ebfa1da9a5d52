// Tests of the measured response of a window (src/identify/measured.cpp, measure_window):
// signals made of known harmonics, sampled irregularly with samples lost, with offsets, drifts
// and noise.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

constexpr double kF = 39.39;  // [Hz]

// C_n of the test signal, n = 1 ... 15: decaying like a signal with kinks.
std::complex<double> coefficient(int n) { return std::polar(10.0 / (n * n), 0.3 + 0.7 * n); }

struct Signal {
  std::vector<double> t, x, z;
};

// sum_n A_n sin(n w (t - t_ref) + theta_n) of x (and of z with other phases), sampled at
// rate [1/s] with 10 % jitter and 2 % of the samples lost, from t_start.
Signal make(double rate, double t_start, unsigned seed, int n_max = 15) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Signal s;
  const int samples = static_cast<int>(40.3 / kF * rate);
  for (int i = 0; i < samples; ++i) {
    if (i > 0 && u(rng) < 0.02) continue;
    const double t = t_start + (i + (i > 0 ? 0.1 * (u(rng) - 0.5) : 0.0)) / rate;
    double x = 0, z = 0;
    for (int n = 1; n <= n_max; ++n) {
      const std::complex<double> c = coefficient(n);
      const double w = n * 2 * M_PI * kF * (t - t_start);
      x += std::abs(c) * std::sin(w + std::arg(c));
      z += 0.5 * std::abs(c) * std::sin(w + std::arg(c) + 1.0);
    }
    s.t.push_back(t);
    s.x.push_back(x);
    s.z.push_back(z);
  }
  return s;
}

// The squared Mahalanobis distance of the first four harmonics of x_M'' (x) or z_M'' (!x) in m
// from those of the noise-free window `clean`, in m's covariance (measure_window's covariance 4):
// chi^2 with 8 degrees of freedom where that covariance is what the noise does.
double chi2_of_first_four(const MeasuredResponse& m, const MeasuredResponse& clean, bool x) {
  Eigen::MatrixXd C(8, 8);
  Eigen::VectorXd e(8);
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      C(a, b) = (x ? m.cov_x : m.cov_z)[static_cast<std::size_t>(a * 8 + b)];
  for (int n = 0; n < 4; ++n) {
    const auto i = static_cast<std::size_t>(n);
    const std::complex<double> d = x ? m.ddx[i] - clean.ddx[i] : m.ddz[i] - clean.ddz[i];
    e[2 * n] = d.real();
    e[2 * n + 1] = d.imag();
  }
  return e.dot(C.ldlt().solve(e));
}

TEST(MeasureWindow, RecoversTheHarmonicsOfAnIrregularRecordExactly) {
  const Signal s = make(2000, 3.0, 1);
  MeasureOptions o;
  o.harmonics = 20;  // every harmonic of the signal is fitted
  const MeasuredResponse m = measure_window(s.t, s.x, s.z, kF, o);
  EXPECT_EQ(m.t_ref, s.t.front());
  ASSERT_EQ(m.ddx.size(), 20u);
  for (int n = 1; n <= 15; ++n) {
    EXPECT_LT(std::abs(m.ddx[n - 1] - coefficient(n)), 1e-9) << n;
    EXPECT_LT(std::abs(m.ddz[n - 1] - 0.5 * coefficient(n) * std::polar(1.0, 1.0)), 1e-9) << n;
  }
  EXPECT_LT(m.noise_x, 1e-9);
}

// "Constant offsets ignored": an offset (gravity in a vertical channel, a sensor's bias) and a
// slow drift do not change the harmonics; they are the trend's.
TEST(MeasureWindow, OffsetsAndSlowDriftsGoToTheTrend) {
  const Signal s = make(1000, 1.2345, 2);
  MeasureOptions o;
  o.harmonics = 10;
  const MeasuredResponse clean = measure_window(s.t, s.x, s.z, kF, o);
  Signal d = s;
  for (std::size_t i = 0; i < d.t.size(); ++i) {
    const double v = d.t[i] - d.t.front();
    d.x[i] += 3.0 + 0.4 * v - 0.2 * v * v;
    d.z[i] += 9.80665 - 0.1 * v * v * v;
  }
  const MeasuredResponse shifted = measure_window(d.t, d.x, d.z, kF, o);
  for (std::size_t n = 0; n < clean.ddx.size(); ++n) {
    EXPECT_LT(std::abs(shifted.ddx[n] - clean.ddx[n]), 1e-10) << n;
    EXPECT_LT(std::abs(shifted.ddz[n] - clean.ddz[n]), 1e-10) << n;
  }
  EXPECT_NEAR(shifted.trend_z[0] - clean.trend_z[0], 9.80665 - 0.1 * std::pow(0.5 * 40.3 / kF, 3),
              0.2);
}

// The covariance is what the noise does: over 400 noise realisations the squared Mahalanobis
// distance of the first 4 harmonics (8 numbers per signal) has the chi^2 mean 8 and variance 16.
TEST(MeasureWindow, TheCovarianceIsCalibrated) {
  const Signal s = make(1500, 0.0, 3);
  std::mt19937 rng(4);
  std::normal_distribution<double> g(0.0, 1.0);
  MeasureOptions o;  // harmonics from the sampling
  o.covariance = 4;
  double sum = 0, sum2 = 0;
  const int trials = 400;
  const MeasuredResponse clean = measure_window(s.t, s.x, s.z, kF, o);
  for (int k = 0; k < trials; ++k) {
    Signal noisy = s;
    for (double& x : noisy.x) x += 0.3 * g(rng);
    for (double& z : noisy.z) z += 0.1 * g(rng);
    const MeasuredResponse m = measure_window(noisy.t, noisy.x, noisy.z, kF, o);
    const double d2 = chi2_of_first_four(m, clean, true);
    sum += d2;
    sum2 += d2 * d2;
  }
  const double mean = sum / trials, var = sum2 / trials - mean * mean;
  // The mean of 400 draws of chi^2_8 has a standard deviation of 4 / 20 = 0.2.
  EXPECT_NEAR(mean, 8.0, 0.8);
  EXPECT_NEAR(var, 16.0, 6.0);
}

// The noise is not the harmonics beyond those compared: a signal whose harmonics decay as 1/n
// (x_M'' of stick-slip jumps at each switch) up to n = 50, sampled at 1 kHz (11 harmonics
// fitted), left about four times the noise's power in x's residual and none in z's; counted as
// noise, it made the covariance of x's harmonics four times too large, and x's weight against
// z's wrong. With the separable harmonics beyond N fitted for the noise, the covariance is again
// what the noise does (as in TheCovarianceIsCalibrated, where every harmonic is fitted). (In
// this window, orders beyond about 63 fold onto lower ones within two frequency bins, n and
// 127 - n: content there would stay in the noise.)
TEST(MeasureWindow, TheNoiseIsNotTheHarmonicsBeyondThoseCompared) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Signal s;
  for (int i = 0; i < 1023; ++i) {
    const double t = (i + (i > 0 ? 0.1 * (u(rng) - 0.5) : 0.0)) / 1000.0;
    double x = 0, z = 0;
    for (int n = 1; n <= 50; ++n) {
      const double w = n * 2 * M_PI * kF * t;
      x += 3.0 / n * std::sin(w + 0.7 * n);
      z += (n <= 11 ? 0.5 / (n * n) : 0.0) * std::sin(w + 0.3 * n);
    }
    s.t.push_back(t);
    s.x.push_back(x);
    s.z.push_back(z);
  }
  std::normal_distribution<double> g(0.0, 1.0);
  MeasureOptions o;
  o.covariance = 4;
  const MeasuredResponse clean = measure_window(s.t, s.x, s.z, kF, o);
  ASSERT_EQ(clean.ddx.size(), 11u);
  double sum_x = 0, sum_z = 0, noise_x = 0;
  const int trials = 200;
  for (int k = 0; k < trials; ++k) {
    Signal noisy = s;
    for (double& x : noisy.x) x += 0.3 * g(rng);
    for (double& z : noisy.z) z += 0.1 * g(rng);
    const MeasuredResponse m = measure_window(noisy.t, noisy.x, noisy.z, kF, o);
    noise_x += m.noise_x / trials;
    sum_x += chi2_of_first_four(m, clean, true) / trials;
    sum_z += chi2_of_first_four(m, clean, false) / trials;
  }
  EXPECT_GT(noise_x, 1.8 * 0.3);  // the fit's residual holds the harmonics beyond 11
  // The mean of 200 draws of chi^2_8 has a standard deviation of 4 / sqrt(200) = 0.28.
  EXPECT_NEAR(sum_x, 8.0, 1.0);
  EXPECT_NEAR(sum_z, 8.0, 1.0);
}

// A record sampled in step with the excitation at an even number of samples per period (a logger
// at 16 f): the harmonics of orders 8, 24, ... fold exactly onto half the sampling rate, where no
// fitted or separable harmonic takes them, and what they leave (+a, -a, ... the same every period)
// counted as noise. z_M'' with its even harmonics had a noise 9.7 times the true one in the
// synthetic records of G = 10 MN/m^2 at 624 samples/s: z hardly counted in the fit, the reduced
// chi^2 was 0.45, and the 95 % intervals of G covered the truth in 82 % of windows (99 % now; at
// 14 samples per period, x_M'' with its odd harmonics: 81 % before). The compared harmonics'
// covariance is checked as in the test above, at 16 and 14 samples per period.
TEST(MeasureWindow, TheHarmonicOnHalfTheSamplingRateIsNotNoise) {
  std::mt19937 rng(17);
  std::normal_distribution<double> g(0.0, 1.0);
  for (const int per_period : {16, 14}) {
    Signal s;
    const double rate = per_period * kF;
    for (int i = 0; i < 40 * per_period; ++i) {
      const double t = i / rate;
      double x = 0, z = 0;
      for (int n = 1; n <= 30; ++n) {
        const double w = n * 2 * M_PI * kF * t, a = 3.0 / (n * n);
        if (n % 2 == 1) x += a * std::sin(w + 0.7 * n);
        if (n % 2 == 0) z += a * std::sin(w + 0.3 * n);
      }
      s.t.push_back(t);
      s.x.push_back(x);
      s.z.push_back(z);
    }
    MeasureOptions o;
    o.covariance = 4;
    const MeasuredResponse clean = measure_window(s.t, s.x, s.z, kF, o);
    ASSERT_GE(clean.ddx.size(), 4u);
    double sum_x = 0, sum_z = 0;
    const int trials = 200;
    for (int k = 0; k < trials; ++k) {
      Signal noisy = s;
      for (double& x : noisy.x) x += 0.02 * g(rng);
      for (double& z : noisy.z) z += 0.01 * g(rng);
      const MeasuredResponse m = measure_window(noisy.t, noisy.x, noisy.z, kF, o);
      sum_x += chi2_of_first_four(m, clean, true) / trials;
      sum_z += chi2_of_first_four(m, clean, false) / trials;
    }
    // The mean of 200 draws of chi^2_8 has a standard deviation of 4 / sqrt(200) = 0.28.
    EXPECT_NEAR(sum_x, 8.0, 1.0) << per_period << " samples per period";
    EXPECT_NEAR(sum_z, 8.0, 1.0) << per_period << " samples per period";
  }
}

// A period-2 window (analyze's fitted_periods 2: a drum that lifts off every second period):
// its subharmonics f/2, 3f/2, ... are the motion's, and with the window's period given they are
// fitted, not counted as noise. Counted as noise they inflated it twelve-fold on such a record
// (17 m/s^2 for 1.4), and a G 1.5 % off passed with an interval of 0.04 % and no warning. The
// compared harmonics of f come from the joint fit too (the subharmonics are orthogonal to them
// over whole pairs of periods, but not to the trend, which biased a fit without them).
TEST(MeasureWindow, APeriodTwoWindowsSubharmonicsAreNotNoise) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  Signal s;
  const double sigma = 0.05;
  for (int i = 0; i < 40 * 40; ++i) {  // 40 periods at 40 samples per period
    const double t = i / (40.0 * kF);
    const double w = 2 * M_PI * kF * t;
    s.t.push_back(t);
    s.x.push_back(3.0 * std::sin(w) + 0.8 * std::sin(0.5 * w + 0.2) + sigma * g(rng));
    s.z.push_back(0.5 * std::sin(2 * w) + 0.4 * std::sin(1.5 * w + 1.0) + sigma * g(rng));
  }
  MeasureOptions o;
  o.harmonics = 8;
  const MeasuredResponse one = measure_window(s.t, s.x, s.z, kF, o);
  o.period = 2;
  const MeasuredResponse two = measure_window(s.t, s.x, s.z, kF, o);
  EXPECT_GT(one.noise_x, 5 * sigma);  // the subharmonic f/2 of 0.8 taken for noise
  EXPECT_NEAR(two.noise_x / sigma, 1.0, 0.1);
  EXPECT_NEAR(two.noise_z / sigma, 1.0, 0.1);
  // The harmonics of f from the joint fit: the record's own (x: 3 sin(w), z: 0.5 sin(2 w); C_n =
  // A e^{i theta}) to a few of their standard uncertainties, which the subharmonics no longer
  // inflate.
  for (std::size_t n = 0; n < 4; ++n) {
    const std::complex<double> cx = n == 0 ? 3.0 : 0.0, cz = n == 1 ? 0.5 : 0.0;
    EXPECT_LT(std::abs(two.ddx[n] - cx), 4.0 * two.sigma_x) << n;
    EXPECT_LT(std::abs(two.ddz[n] - cz), 4.0 * two.sigma_z) << n;
  }
  EXPECT_LT(two.sigma_x, 0.5 * one.sigma_x);
  EXPECT_EQ(one.subharmonics_of, 1);
  EXPECT_EQ(two.subharmonics_of, 2);
  // A window too short for the subharmonics beside its harmonics (dof below half the samples):
  // they count as noise, and the window says so (identify_pass warns).
  const std::span<const double> t4(s.t.data(), 120), x4(s.x.data(), 120), z4(s.z.data(), 120);
  o.harmonics = 18;
  EXPECT_EQ(measure_window(t4, x4, z4, kF, o).subharmonics_of, 1);
  o.harmonics = 8;
  EXPECT_EQ(measure_window(t4, x4, z4, kF, o).subharmonics_of, 2);
  o.period = 5;
  EXPECT_THROW(measure_window(s.t, s.x, s.z, kF, o), Error);
}

// The same for a period-2 window's orders beyond those fitted: the subharmonics beyond its 2 N
// orders of f / 2 are the motion's too. Separable ones (order 6.5 at 15 samples per period, 6
// harmonics fitted) and the one on half the sampling rate (order 7.5, exactly in step) were left
// in the noise, which they made 5 to 8 times too large (the compared harmonics' covariance with
// it); now the noise is the record's, as without them.
TEST(MeasureWindow, APeriodTwoWindowsSubharmonicsBeyondThoseFittedAreNotNoise) {
  const double sigma = 0.05;
  auto window = [&](bool beyond) {
    std::mt19937 rng(23);
    std::normal_distribution<double> g(0.0, 1.0);
    Signal s;
    for (int i = 0; i < 40 * 15; ++i) {  // 40 periods at 15 samples per period
      const double t = i / (15.0 * kF);
      const double w = 2 * M_PI * kF * t;
      double x = 3.0 * std::sin(w) + 0.8 * std::sin(0.5 * w + 0.2) + sigma * g(rng);
      double z = 0.5 * std::sin(2 * w) + 0.4 * std::sin(1.5 * w + 1.0) + sigma * g(rng);
      if (beyond) {
        x += 0.4 * std::sin(6.5 * w + 0.5) + 0.3 * std::cos(7.5 * w + 0.1);
        z += 0.3 * std::sin(6.5 * w + 1.5) + 0.2 * std::cos(7.5 * w + 0.7);
      }
      s.t.push_back(t);
      s.x.push_back(x);
      s.z.push_back(z);
    }
    MeasureOptions o;
    o.period = 2;
    return measure_window(s.t, s.x, s.z, kF, o);
  };
  const MeasuredResponse with = window(true), without = window(false);
  ASSERT_EQ(with.ddx.size(), 6u);
  ASSERT_EQ(with.subharmonics_of, 2);
  EXPECT_NEAR(without.sigma_x / (sigma * std::sqrt(2.0 / 600.0)), 1.0, 0.15);
  EXPECT_NEAR(with.sigma_x / without.sigma_x, 1.0, 0.1);
  EXPECT_NEAR(with.sigma_z / without.sigma_z, 1.0, 0.1);
}

TEST(MeasureWindow, HarmonicsFromTheSampling) {
  const Signal s = make(1000, 0.0, 5);  // 25.4 samples per period: 11 harmonics
  EXPECT_EQ(measure_window(s.t, s.x, s.z, kF).ddx.size(), 11u);
  const Signal fast = make(5000, 0.0, 5);  // 127 per period: at most kMaxMeasuredHarmonics
  EXPECT_EQ(measure_window(fast.t, fast.x, fast.z, kF).ddx.size(),
            static_cast<std::size_t>(kMaxMeasuredHarmonics));
  MeasureOptions o;
  o.harmonics = 12;  // 2 * 12 + 2 = 26 > 25.4
  try {
    measure_window(s.t, s.x, s.z, kF, o);
    ADD_FAILURE() << "12 harmonics at 25.4 samples per period accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("too few for 12 harmonics"), std::string::npos)
        << e.what();
  }
}

// A window sampled in step with the excitation (16 samples a period: 7 harmonics fitted, 8 ... 15
// alias onto them the same way in every period) keeps the fit as a linear map of its samples,
// whose weights give the fitted harmonics again; a window at another rate (or jittered) does not.
TEST(MeasureWindow, InStepWindowsKeepTheFitAsAMapOfTheSamples) {
  Signal s;
  const double rate = 16.0 * kF;
  for (int i = 0; i < 16 * 40; ++i) {
    const double t = 2.0 + i / rate;
    double x = 0, z = 0;
    for (int n = 1; n <= 15; ++n) {
      const std::complex<double> c = coefficient(n);
      const double w = n * 2 * M_PI * kF * (t - 2.0);
      x += std::abs(c) * std::sin(w + std::arg(c));
      z += 0.5 * std::abs(c) * std::sin(w + std::arg(c) + 1.0);
    }
    s.t.push_back(t);
    s.x.push_back(x);
    s.z.push_back(z);
  }
  const MeasuredResponse m = measure_window(s.t, s.x, s.z, kF);
  ASSERT_EQ(m.ddx.size(), 7u);
  const std::size_t K =
      m.cov_x.empty() ? 0 : static_cast<std::size_t>(std::sqrt(m.cov_x.size())) / 2;
  ASSERT_EQ(K, 4u);
  ASSERT_EQ(m.alias_t.size(), s.t.size());
  ASSERT_EQ(m.alias_w.size(), s.t.size() * 2 * K);
  for (std::size_t n = 0; n < K; ++n) {
    std::complex<double> cx = 0, cz = 0;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
      const double* w = &m.alias_w[i * 2 * K];
      cx += std::complex<double>(w[2 * n] * s.x[i], w[2 * n + 1] * s.x[i]);
      cz += std::complex<double>(w[2 * n] * s.z[i], w[2 * n + 1] * s.z[i]);
    }
    EXPECT_LT(std::abs(cx - m.ddx[n]), 1e-12 * std::abs(coefficient(1))) << n;
    EXPECT_LT(std::abs(cz - m.ddz[n]), 1e-12 * std::abs(coefficient(1))) << n;
    EXPECT_DOUBLE_EQ(m.alias_t[n], s.t[n] - s.t.front());
  }
  // The aliases are there: C_1 is off by about |C_15| (harmonic 15 lands on 1).
  EXPECT_GT(std::abs(m.ddx[0] - coefficient(1)), 0.5 * std::abs(coefficient(15)));
  // Not in step: 1 kHz with jitter, and 16.1 samples a period over 40 periods.
  const Signal jittered = make(1000, 0.0, 5);
  EXPECT_TRUE(measure_window(jittered.t, jittered.x, jittered.z, kF).alias_t.empty());
  std::vector<double> t_off(s.t.size());
  for (std::size_t i = 0; i < t_off.size(); ++i)
    t_off[i] = 2.0 + static_cast<double>(i) / (16.1 * kF);
  EXPECT_TRUE(measure_window(t_off, s.x, s.z, kF).alias_t.empty());
}

}  // namespace
}  // namespace oscidrum
