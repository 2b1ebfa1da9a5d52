// Identification along a pass (identify.hpp, identify_pass): every window of the record, each
// started from the previous valid estimate.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "identify/problem.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace detail {}  // namespace detail

namespace {

// Overlapping windows (--hop shorter than --window; the record's end window) share samples:
// where both are valid and their 95 % intervals of the first unknown do not meet, the soil or a
// setting changes within the part one of them holds alone, and one of the two is a confident
// value of neither side. The change gate (5 % of the response's RMS) passes a window with 1 of its
// 40 periods on another soil (G = 17.50 +- 0.02 for 17.3 beside 30: docs/identify.md).
void warn_disjoint_overlaps(std::vector<PassEstimate>& pass) {
  for (std::size_t k = 0; k + 1 < pass.size(); ++k) {
    PassEstimate &a = pass[k], &b = pass[k + 1];
    if (!a.valid || !b.valid || !(b.window.t_start < a.window.t_end)) continue;
    if (a.identification.estimates.empty() || b.identification.estimates.empty()) continue;
    const Estimate &ea = a.identification.estimates.front(),
                   &eb = b.identification.estimates.front();
    if (!(ea.upper < eb.lower || eb.upper < ea.lower)) continue;  // they meet (or NaN)
    const auto interval = [](const Estimate& e) {
      return detail::format("[%.6g, %.6g] ", e.lower, e.upper) + e.unit;
    };
    const auto say = [&](PassEstimate& p, const PassEstimate& other, const Estimate& own,
                         const Estimate& theirs) {
      p.identification.warnings.push_back(
          "window " + std::to_string(other.window.index) +
          " shares samples with this one (from t = " +
          detail::format("%.6g", std::max(a.window.t_start, b.window.t_start)) + " to " +
          detail::format("%.6g", std::min(a.window.t_end, b.window.t_end)) +
          " s), and its 95 % interval of " + own.name + " " + interval(theirs) +
          " does not meet this one's " + interval(own) +
          ": the soil or a setting changes within one of them (the change gate, 5 % of the "
          "response's RMS, passes a small change; --max-change 0.02 or a shorter --window "
          "tells which; docs/identify.md)");
    };
    say(a, b, ea, eb);
    say(b, a, eb, ea);
  }
}

}  // namespace

std::vector<PassEstimate> identify_pass(const Case& base, std::span<const double> t,
                                        std::span<const double> ddx, std::span<const double> ddz,
                                        std::span<const double> position,
                                        const WindowOptions& windows, const IdentifyOptions& o,
                                        const PassProgress& progress) {
  // Refused before any window (per window they would only fail each one): the harmonics
  // compared, as the CLI's --compare allows them.
  if (o.harmonics < 1 || o.harmonics > kMaxComparedHarmonics)
    throw Error("identify: compare (--compare) must be in [1, " +
                std::to_string(kMaxComparedHarmonics) + "] harmonics; got " +
                std::to_string(o.harmonics));
  detail::check_gain_uncertainty(o.gain_uncertainty);
  if (windows.n_max > 0 && o.harmonics > windows.n_max)
    throw Error(
        "identify: compare (--compare) must be <= the harmonics fitted (n_max, "
        "--harmonics) = " +
        std::to_string(windows.n_max) + "; got " + std::to_string(o.harmonics));
  // The record's times from its first sample: phases of n 2 pi f t at t ~ 1e9 s would keep
  // only a few digits.
  const double t0 = t.empty() ? 0.0 : t.front();
  std::vector<double> local(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) local[i] = t[i] - t0;
  WindowOptions wo = windows;
  wo.time_origin += t0;  // the reasons quote the record's times
  std::vector<RecordWindow> ws = analyze_windows(local, ddx, ddz, position, wo);
  MeasureOptions mo = o.measure;
  mo.covariance = std::max(mo.covariance, o.harmonics);
  std::vector<PassEstimate> out;
  out.reserve(ws.size());
  // The previous valid window, by index: a pointer into `out` would dangle when it grows.
  std::optional<std::size_t> previous;
  // Windows measured, and those of them measuring fewer harmonics than are compared (their
  // sampling's limit: the same for every window of a uniformly sampled record).
  std::size_t measured = 0, too_few = 0;
  std::size_t most_resolved = 0;
  for (std::size_t k = 0; k < ws.size(); ++k) {
    PassEstimate pe;
    RecordWindow& w = ws[k];
    pe.identification.f = w.f;
    if (!w.valid) {
      pe.reason = w.reason;
    } else {
      try {
        const std::span<const double> tw = std::span<const double>(local).subspan(w.first, w.count);
        // A channel of one value (analyze's window is valid with the other alone).
        try {
          detail::require_live_channels(ddx.subspan(w.first, w.count),
                                        ddz.subspan(w.first, w.count), "the window");
        } catch (const Error& e) {
          throw Error(std::string("identify: ") + e.what());
        }
        // A period-p window (analyze's fitted_periods): its subharmonics are fitted, not noise.
        MeasureOptions mw = mo;
        mw.period = std::clamp(static_cast<int>(w.metrics.fitted_periods), 1, 4);
        MeasuredResponse d = measure_window(tw, ddx.subspan(w.first, w.count),
                                            ddz.subspan(w.first, w.count), w.f, mw);
        ++measured;
        const std::size_t resolved = std::min(d.ddx.size(), d.ddz.size());
        if (static_cast<int>(resolved) < o.harmonics) {
          ++too_few;
          most_resolved = std::max(most_resolved, resolved);
        }
        d.t_ref += t0;
        d.t_first += t0;
        d.t_last += t0;
        pe.identification =
            identify(base, d, o, previous ? &out[*previous].identification : nullptr);
        pe.valid = true;
        if (mw.period > 1) {
          // What the model is compared on: the harmonics of f alone.
          const std::string p = std::to_string(mw.period);
          pe.identification.warnings.push_back(
              "the record repeats every " + p + " excitation periods (a period-" + p +
              " response: its subharmonics f/" + p + ", ... fitted as signal, rmv " +
              detail::format("%.3g", w.metrics.rmv) +
              "): the model is compared on the harmonics of f alone, which a period-1 steady "
              "state near the estimate may match as well; check the estimate with `oscidrum run` "
              "(its multiplicity should be " +
              p + ")");
          if (d.subharmonics_of != mw.period)
            pe.identification.warnings.push_back(
                "the window's samples are too few to fit the subharmonics beside its " +
                std::to_string(d.ddx.size()) +
                " harmonics: they count as noise, which makes the fit look better and the "
                "interval wider than they are; a longer window (--window) fits them");
        }
      } catch (const Error& e) {
        pe.reason = e.what();
      }
    }
    w.t_start += t0;
    w.t_end += t0;
    w.t_mid += t0;
    pe.window = std::move(w);
    out.push_back(std::move(pe));
    if (out.back().valid) previous = out.size() - 1;
    if (progress && !progress(k, ws.size())) break;
  }
  warn_disjoint_overlaps(out);
  // Every window failed for the harmonics asked alone (so none is valid): the request, not the
  // record, is wrong (a bad input, said once, rather than a failure repeated for each window).
  if (measured > 0 && too_few == measured)
    throw Error(
        "identify: compare (--compare) = " + std::to_string(o.harmonics) +
        " is more harmonics than the record's windows measure: " + std::to_string(most_resolved) +
        " (as many as their sampling resolves, N harmonics needing 2 N + 2 samples per "
        "period); give --compare " +
        std::to_string(most_resolved) + " or less");
  return out;
}

}  // namespace oscidrum
