// oscidrum_io/json.hpp: JSON summaries (nlohmann/json stays private to this library). The
// schemas are documented in docs/outputs.md.
#pragma once

#include <string>
#include <vector>

#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum_io/case_spec.hpp"

namespace oscidrum::io {

/// Schema "oscidrum-case/1": status, message, diagnostics, every parameter by field key, the
/// derived soil coefficients, sampling, phase times and metrics (null without samples).
/// `config` is the case file ("" for none).
std::string case_json(const CaseSpec& spec, const Case& c, const Result& result,
                      const Metrics* metrics, const std::string& config);

/// Schema "oscidrum-sweep/1" from a sweep's CSV header and rows (docs/outputs.md): numbers
/// become numbers, empty cells null.
std::string study_json(const std::string& header, const std::vector<std::string>& rows);

}  // namespace oscidrum::io
