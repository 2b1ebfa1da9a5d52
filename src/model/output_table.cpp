// The output tables of oscidrum/output_table.hpp, generated from the lists of oscidrum/outputs.hpp.
#include "oscidrum/output_table.hpp"

#include <limits>
#include <string>

namespace oscidrum {
namespace {

#define OSCIDRUM_ROW(Struct, name, unit, label, description) \
  {#name, unit, label, description, &Struct::name},
#define OSCIDRUM_SAMPLE_ROW(type, name, unit, label, description) \
  OSCIDRUM_ROW(Samples, name, unit, label, description)
#define OSCIDRUM_DIAGNOSTIC_ROW(type, name, initial, unit, label, description) \
  OSCIDRUM_ROW(Diagnostics, name, unit, label, description)
#define OSCIDRUM_METRIC_ROW(type, name, unit, label, description) \
  OSCIDRUM_ROW(Metrics, name, unit, label, description)
#define OSCIDRUM_RECORD_ROW(type, name, unit, label, description) \
  OSCIDRUM_ROW(RecordMetrics, name, unit, label, description)
#define OSCIDRUM_STATUS_ROW(name, description) {Status::name, #name, description},
#define OSCIDRUM_NAME(type, name, unit, label, description) #name,

const SampleOutput kSamples[] = {OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_SAMPLE_ROW)};
const DiagnosticOutput kDiagnostics[] = {OSCIDRUM_DIAGNOSTICS(OSCIDRUM_DIAGNOSTIC_ROW)};
const MetricOutput kMetrics[] = {OSCIDRUM_METRICS(OSCIDRUM_METRIC_ROW)};
const RecordOutput kRecord[] = {OSCIDRUM_RECORD_METRICS(OSCIDRUM_RECORD_ROW)};
const StatusInfo kStatuses[] = {OSCIDRUM_STATUSES(OSCIDRUM_STATUS_ROW)};
const std::string_view kAccelerationNames[] = {OSCIDRUM_ACCELERATION_METRICS(OSCIDRUM_NAME)};

#undef OSCIDRUM_ROW
#undef OSCIDRUM_SAMPLE_ROW
#undef OSCIDRUM_DIAGNOSTIC_ROW
#undef OSCIDRUM_METRIC_ROW
#undef OSCIDRUM_RECORD_ROW
#undef OSCIDRUM_STATUS_ROW
#undef OSCIDRUM_NAME

}  // namespace

std::span<const SampleOutput> sample_outputs() { return kSamples; }
std::span<const DiagnosticOutput> diagnostic_outputs() { return kDiagnostics; }
std::span<const MetricOutput> metric_outputs() { return kMetrics; }
std::span<const RecordOutput> record_outputs() { return kRecord; }
std::span<const StatusInfo> statuses() { return kStatuses; }

bool is_text_column(std::string_view name) {
  if (name == "status" || name == "message") return true;
  for (const DiagnosticOutput& d : kDiagnostics)
    if (d.name == name) return is_text(d);
  return false;
}

bool is_acceleration_metric(std::string_view name) {
  for (std::string_view n : kAccelerationNames)
    if (n == name) return true;
  return false;
}

std::string spectrum_prefix(std::string_view name) {
  constexpr std::string_view suffix = "_harmonics";
  if (name.size() > suffix.size() && name.substr(name.size() - suffix.size()) == suffix)
    name.remove_suffix(suffix.size());
  return std::string(name);
}

double harmonic_amplitude(const Metrics& m, const MetricOutput& out, std::size_t n) {
  const auto* member = std::get_if<Spectrum Metrics::*>(&out.member);
  if (member == nullptr) return std::numeric_limits<double>::quiet_NaN();
  const Spectrum& h = m.**member;
  return n < h.size() ? h[n].amplitude : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace oscidrum
