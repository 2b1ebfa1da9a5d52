// Synthetic records made by oscidrum itself (identify.hpp, synthetic_record), for tests and
// benchmarks: the model's steady state of each segment sampled at the record's times, with
// noise, drift and jitter.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>

#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/simulate.hpp"
#include "util/format.hpp"

namespace oscidrum {

RecordSamples synthetic_record(const std::vector<Case>& segments, const SyntheticRecord& o) {
  if (segments.empty()) throw Error("synthetic_record: no case given");
  if (!(o.duration > 0 && o.sample_rate > 0))
    throw Error("synthetic_record: duration and sample_rate must be > 0");
  // At most 1e8 samples (2.4 GB of columns): a sample rate of 1e12/s asked for more memory than
  // any machine has and ended in std::bad_alloc.
  if (!(o.duration * o.sample_rate <= 1e8))
    throw Error("synthetic_record: duration * sample_rate must be <= 1e8 samples; got " +
                    detail::shortest(o.duration * o.sample_rate),
                "sample_rate", o.sample_rate);
  for (const auto& [name, value] :
       {std::pair{"noise", o.noise}, std::pair{"drift", o.drift}, std::pair{"jitter", o.jitter}})
    if (!(std::isfinite(value) && value >= 0))
      throw Error(std::string("synthetic_record: ") + name + " must be finite and >= 0; got " +
                      detail::shortest(value),
                  name, value);
  // Each time moves by up to half the jitter of an interval: at 1 or more, neighbours swap and
  // the record's times go back (which every record function refuses).
  if (!(o.jitter < 1.0))
    throw Error(
        "synthetic_record: jitter must be in [0, 1) sample intervals (times must increase); "
        "got " +
            detail::shortest(o.jitter),
        "jitter", o.jitter);
  for (const auto& [name, value] : {std::pair{"start", o.start}, std::pair{"speed", o.speed}})
    if (!std::isfinite(value))
      throw Error(std::string("synthetic_record: ") + name + " must be finite; got " +
                      detail::shortest(value),
                  name, value);
  std::size_t n = static_cast<std::size_t>(std::floor(o.duration * o.sample_rate)) + 1;
  RecordSamples rec;
  rec.t.resize(n);
  rec.ddx_M.resize(n);
  rec.ddz_M.resize(n);
  rec.position.resize(n);
  if (!(o.dropped >= 0 && o.dropped < 1))
    throw Error("synthetic_record: dropped must be in [0, 1)");
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> uni(-0.5, 0.5);
  for (std::size_t i = 0; i < n; ++i)
    rec.t[i] =
        (static_cast<double>(i) + (i > 0 && i + 1 < n ? o.jitter * uni(rng) : 0.0)) / o.sample_rate;
  if (o.dropped > 0) {  // samples lost at random (never the first or the last)
    std::vector<double> kept;
    for (std::size_t i = 0; i < n; ++i)
      if (i == 0 || i + 1 == n || uni(rng) + 0.5 >= o.dropped) kept.push_back(rec.t[i]);
    rec.t = std::move(kept);
    n = rec.t.size();
    rec.ddx_M.resize(n);
    rec.ddz_M.resize(n);
    rec.position.resize(n);
  }
  for (double& ti : rec.t) ti += o.start;
  const double seg = o.duration / static_cast<double>(segments.size());
  double peak_x = 0, peak_z = 0;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    Case c = segments[s];
    c.numerics.samples_per_period = 8192;  // linear interpolation to about 1e-7 of a peak
    c.numerics.output_periods = 1;
    const Result r = simulate(c);
    if (!ok(r.status))
      throw Error("synthetic_record: segment " + std::to_string(s) + " did not reach its steady " +
                  "state: " + r.message);
    const std::size_t m = r.samples.size();
    const double T = static_cast<double>(m) / (c.roller.f * r.samples_per_period);  // its period
    const double t0 = r.samples.t.front();
    for (std::size_t i = 0; i < n; ++i) {
      const double ti = rec.t[i];
      const double from_start = ti - o.start;
      if (from_start < seg * static_cast<double>(s) - 1e-12 ||
          (s + 1 < segments.size() && from_start >= seg * static_cast<double>(s + 1)))
        continue;
      double u = std::fmod(ti - t0, T);
      if (u < 0) u += T;
      const double x = u / T * static_cast<double>(m);
      const std::size_t j = static_cast<std::size_t>(std::floor(x)) % m;
      const double w = x - std::floor(x);
      const std::size_t j1 = (j + 1) % m;
      rec.ddx_M[i] = (1 - w) * r.samples.ddx_M[j] + w * r.samples.ddx_M[j1];
      rec.ddz_M[i] = (1 - w) * r.samples.ddz_M[j] + w * r.samples.ddz_M[j1];
    }
    for (std::size_t j = 0; j < m; ++j) {
      peak_x = std::max(peak_x, std::abs(r.samples.ddx_M[j]));
      peak_z = std::max(peak_z, std::abs(r.samples.ddz_M[j]));
    }
  }
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double slow = std::sin(2.0 * M_PI * (rec.t[i] - o.start) / o.duration + 0.3);
    rec.ddx_M[i] += peak_x * (o.noise * gauss(rng) + o.drift * slow);
    rec.ddz_M[i] += peak_z * (o.noise * gauss(rng) + o.drift * slow);
    rec.position[i] = o.speed * (rec.t[i] - o.start);
  }
  return rec;
}

}  // namespace oscidrum
