// Internal: the registry of roller types. with_roller(model, f) calls f.template operator()<R>()
// with the roller type R the model describes, so that a driver written once for any R (simulate,
// the continuation of studies) runs the right instantiation. A new roller adds its header and
// its case here (and its line in src/roller/engine.cpp).
#pragma once

#include "oscidrum/model.hpp"
#include "roller/oscillation_drum.hpp"
#include "roller/unilateral_drum.hpp"

namespace oscidrum::detail {

template <class F>
decltype(auto) with_roller(const Model& model, F&& f) {
  // The paper's oscillation drum, with permanent contact or with contact that can open.
  if (model.parameters().contact.unilateral) return f.template operator()<UnilateralDrum>();
  return f.template operator()<OscillationDrum>();
}

}  // namespace oscidrum::detail
