// estimate_json.hpp: one estimate (identify, calibrate) as the JSON object both commands write.
#pragma once

#include <nlohmann/json.hpp>

#include "oscidrum/identify.hpp"

namespace oscidrum::cli {

/// name, unit, value, standard_uncertainty (and its part from the channels' gain uncertainty),
/// the 95 % interval's lower and upper, and whether each end stayed open.
inline nlohmann::ordered_json estimate_json(const Estimate& e) {
  return {{"name", e.name},
          {"unit", e.unit},
          {"value", e.value},
          {"standard_uncertainty", e.standard_uncertainty},
          {"gain_uncertainty", e.gain_uncertainty},
          {"lower", e.lower},
          {"upper", e.upper},
          {"lower_open", e.lower_open},
          {"upper_open", e.upper_open}};
}

}  // namespace oscidrum::cli
