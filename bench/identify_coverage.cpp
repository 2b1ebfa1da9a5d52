// The coverage study of the identification's 95 % intervals (docs/identify.md, "Do the
// intervals hold?"): for each setting, records of one 40-period window each, made with their own
// noise, drift, jitter and lost samples (seeds 1 ... windows), identified as `oscidrum identify`
// would; the table gives the mean and standard deviation of the relative error of each estimate,
// its mean standard uncertainty and the share of windows whose 95 % interval holds the truth.
// Usage: identify_coverage [--windows N] [--only TEXT]  (about 2.5 min for 100 windows each)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "oscidrum/oscidrum.hpp"

namespace {

using namespace oscidrum;

struct Setting {
  std::string name;
  double G;      // [Pa], through Appendix B
  bool rolling;  // pure rolling
  double mu;     // [-]
  double MMd;    // driving torque / M0 of the paper's roller [-]
  double rate;   // sampling rate [1/s]
  double noise;  // white noise / peak [-]
  bool fit_mu = false, fit_MMd = false;
  bool table2 = false;  // the soil of Table 2 (interpolated), identified on that scale
  double sensor = 0.0;  // white noise of the same standard deviation in both channels [m/s^2]
};

constexpr double kF = 39.0 * 1.01;  // the record's excitation frequency [Hz]

Case truth(const Setting& s) {
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = s.G;
  if (s.table2) {
    const SoilCoefficients k = table2_coefficients(s.G);
    c.soil.input = SoilInput::coefficients;
    c.soil.ksh = k.ksh;
    c.soil.ksv = k.ksv;
    c.soil.csh = k.csh;
    c.soil.csv = k.csv;
  }
  c.contact.pure_rolling = s.rolling;
  c.contact.mu = s.mu;
  c.MMd = s.MMd * Roller{}.M0;
  c.roller.M0 *= (kF / 39.0) * (kF / 39.0);  // (5)
  c.roller.f = kF;
  return c;
}

// What the identification assumes: the paper's roller at 39 Hz, the truth's mu and MMd unless
// they are estimated.
Case base(const Setting& s) {
  Case c;
  c.contact.pure_rolling = s.rolling;
  c.contact.mu = s.fit_mu ? 0.5 : s.mu;
  c.MMd = s.fit_MMd ? 0.0 : s.MMd * Roller{}.M0;
  return c;
}

struct Tally {
  int n = 0, covered = 0;
  double sum = 0, sum2 = 0, u = 0;
  void add(double err, double rel_u, bool in) {
    ++n;
    sum += err;
    sum2 += err * err;
    u += rel_u;
    covered += in ? 1 : 0;
  }
};

}  // namespace

int main(int argc, char** argv) {
  int windows = 100;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--windows") && i + 1 < argc) windows = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
  }
  const std::vector<Setting> settings = {
      {"stick-slip G 17.3, 1 kHz, 1 %", 17.3e6, false, 0.5, 0.0, 1000, 0.01},
      {"stick-slip G 17.3, 1 kHz, 5 %", 17.3e6, false, 0.5, 0.0, 1000, 0.05},
      {"stick-slip G 17.3, 2 kHz, 2 %", 17.3e6, false, 0.5, 0.0, 2000, 0.02},
      {"stick-slip G 17.3, 5 kHz, 1 %", 17.3e6, false, 0.5, 0.0, 5000, 0.01},
      {"stick-slip G 17.3, 5 kHz, 5 %", 17.3e6, false, 0.5, 0.0, 5000, 0.05},
      {"stick-slip G 8.1, MMd 0.03 M0, 2 kHz, 2 %", 8.1e6, false, 0.5, 0.03, 2000, 0.02},
      {"stick-slip G 42.7, MMd 0.03 M0, 5 kHz, 1 %", 42.7e6, false, 0.5, 0.03, 5000, 0.01},
      {"pure rolling G 42.7, MMd 0.03 M0, 1 kHz, 1 %", 42.7e6, true, 0.5, 0.03, 1000, 0.01},
      {"pure rolling G 42.7, MMd 0.03 M0, 5 kHz, 1 %", 42.7e6, true, 0.5, 0.03, 5000, 0.01},
      {"pure rolling G 25.3, 1 kHz, 5 %", 25.3e6, true, 0.5, 0.0, 1000, 0.05},
      {"G and mu: stick-slip G 17.3, mu 0.42, 2 kHz, 2 %", 17.3e6, false, 0.42, 0.0, 2000, 0.02,
       true, false},
      {"G, mu and MMd: stick-slip G 17.3, mu 0.42, MMd 0.03 M0, 2 kHz, 2 %", 17.3e6, false, 0.42,
       0.03, 2000, 0.02, true, true},
      {"Table 2 soil G 30 (a row), table2 scale, 1 kHz, 2 %", 30e6, false, 0.5, 0.0, 1000, 0.02,
       false, false, true},
      {"Table 2 soil G 47.5 (between rows), table2 scale, 5 kHz, 1 %", 47.5e6, false, 0.5, 0.03,
       5000, 0.01, false, false, true},
      // An accelerometer's noise, the same in both channels (x_M'' peaks at about 12 m/s^2,
      // z_M'' at about 1): the channels' shares of noise differ, as in a field record.
      {"stick-slip G 17.3, 1 kHz, sensor noise 0.1 m/s^2", 17.3e6, false, 0.5, 0.0, 1000, 0.0,
       false, false, false, 0.1},
      {"stick-slip G 17.3, 2 kHz, sensor noise 0.05 m/s^2", 17.3e6, false, 0.5, 0.0, 2000, 0.0,
       false, false, false, 0.05},
  };
  std::printf(
      "| setting | unknown | windows | mean error [%%] | sd [%%] | mean u [%%] | coverage [%%] "
      "|\n|---|---|---|---|---|---|---|\n");
  const auto begin = std::chrono::steady_clock::now();
  int total = 0;
  for (const Setting& s : settings) {
    if (!only.empty() && s.name.find(only) == std::string::npos) continue;
    const Case t = truth(s), b = base(s);
    const double truths[3] = {s.G, s.mu, s.MMd * Roller{}.M0};
    Tally tally[3];
    int failed = 0;
    for (int k = 1; k <= windows; ++k) {
      SyntheticRecord o;
      o.duration = 40.6 / kF;
      o.sample_rate = s.rate;
      o.noise = s.noise;
      o.drift = 0.05;  // a sine of the record's length: the slowest drift a window sees whole
      o.jitter = 0.1;
      o.dropped = 0.01;
      o.start = 1234.5;
      o.seed = static_cast<unsigned>(k);
      RecordSamples r = synthetic_record({t}, o);
      if (s.sensor > 0.0) {
        std::mt19937 rng(1000u + static_cast<unsigned>(k));
        std::normal_distribution<double> g(0.0, s.sensor);
        for (double& v : r.ddx_M) v += g(rng);
        for (double& v : r.ddz_M) v += g(rng);
      }
      WindowOptions w;
      w.window_periods = 40;
      IdentifyOptions io;
      io.fit_mu = s.fit_mu;
      io.fit_MMd = s.fit_MMd;
      if (s.table2) io.soil_scale = SoilScale::table2;
      const std::vector<PassEstimate> pass = identify_pass(b, r.t, r.ddx_M, r.ddz_M, {}, w, io);
      if (pass.empty() || !pass.front().valid) {
        ++failed;
        continue;
      }
      const std::vector<Estimate>& e = pass.front().identification.estimates;
      for (std::size_t j = 0; j < e.size() && j < 3; ++j) {
        const double truth_j = truths[e[j].name == "G" ? 0 : e[j].name == "mu" ? 1 : 2];
        const double scale = e[j].name == "MMd" ? Roller{}.M0 : truth_j;  // MMd relative to M0
        tally[j].add((e[j].value - truth_j) / scale, e[j].standard_uncertainty / scale,
                     e[j].lower <= truth_j && truth_j <= e[j].upper);
      }
    }
    total += windows;
    const char* names[3] = {"G", "mu", "MMd"};
    for (int j = 0; j < 3; ++j) {
      const Tally& x = tally[j];
      if (x.n == 0) continue;
      const double mean = x.sum / x.n, sd = std::sqrt(std::max(0.0, x.sum2 / x.n - mean * mean));
      std::printf("| %s | %s%s | %d | %+.3f | %.3f | %.3f | %.1f |\n", s.name.c_str(), names[j],
                  j == 2 ? " (/ M0)" : "", x.n, 100 * mean, 100 * sd, 100 * x.u / x.n,
                  100.0 * x.covered / x.n);
    }
    if (failed) std::printf("| %s | (failed windows) | %d | | | | |\n", s.name.c_str(), failed);
    std::fflush(stdout);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  std::printf("\n%d windows in %.1f s (%.1f ms per window)\n", total, seconds,
              1e3 * seconds / total);
  return 0;
}
