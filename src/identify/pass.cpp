// Identification along a pass (identify.hpp, identify_pass): every window of the record, each
// started from the previous valid estimate.
#include <utility>

#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"

namespace oscidrum {

std::vector<PassEstimate> identify_pass(const Case& base, std::span<const double> t,
                                        std::span<const double> ddx, std::span<const double> ddz,
                                        std::span<const double> position,
                                        const WindowOptions& windows, const IdentifyOptions& o,
                                        const PassProgress& progress) {
  const std::vector<RecordWindow> ws = analyze_windows(t, ddx, ddz, position, windows);
  std::vector<PassEstimate> out;
  const Identification* previous = nullptr;
  for (std::size_t k = 0; k < ws.size(); ++k) {
    PassEstimate pe;
    pe.window = ws[k];
    pe.identification.f = ws[k].f;
    if (!ws[k].valid) {
      pe.reason = ws[k].reason;
    } else {
      try {
        const MeasuredResponse d = measured_response(ws[k].metrics, ws[k].f, ws[k].count);
        pe.identification = identify(base, d, o, previous);
        pe.valid = true;
      } catch (const Error& e) {
        pe.reason = e.what();
      }
    }
    out.push_back(std::move(pe));
    if (out.back().valid) previous = &out.back().identification;
    if (progress && !progress(k, ws.size())) break;
  }
  return out;
}

}  // namespace oscidrum
