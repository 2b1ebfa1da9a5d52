// run_summary.hpp: the readable summary `oscidrum run` prints on stdout (--format table).
#pragma once

#include <string>

#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum_io/case_spec.hpp"

namespace oscidrum::cli {

/// The case in brief, status, diagnostics and the key metrics, each with its unit. `metrics` may
/// be null (no samples).
std::string run_summary(const io::CaseSpec& spec, const Case& c, const Result& result,
                        const Metrics* metrics, const std::string& config);

}  // namespace oscidrum::cli
