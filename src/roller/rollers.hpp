// Internal: the registry of roller types. with_roller(model, f) calls f.template operator()<R>()
// with the roller type R the model describes, so that a driver written once for any R (simulate,
// the continuation of studies) runs the right instantiation. A new roller adds its header and
// its case here (and its line in src/roller/engine.cpp).
#pragma once

#include "oscidrum/model.hpp"
#include "roller/oscillation_drum.hpp"

namespace oscidrum::detail {

template <class F>
decltype(auto) with_roller(const Model& /*model*/, F&& f) {
  // One roller so far: the paper's oscillation drum.
  return f.template operator()<OscillationDrum>();
}

}  // namespace oscidrum::detail
