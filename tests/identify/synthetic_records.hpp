// Synthetic records for the identification tests (tests only): a record made by oscidrum itself
// with 5 % noise, a 5 % slow drift and 10 % timing jitter, and the identification of a record
// taken as one window.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "oscidrum/oscidrum.hpp"

namespace oscidrum {

inline RecordSamples noisy_record(const Case& c, double duration, double rate, unsigned seed = 7) {
  SyntheticRecord o;
  o.duration = duration;
  o.sample_rate = rate;
  o.noise = 0.05;
  o.drift = 0.05;
  o.jitter = 0.1;
  o.seed = seed;
  return synthetic_record({c}, o);
}

inline Identification identify_whole(const Case& b, const RecordSamples& r,
                                     const IdentifyOptions& o) {
  WindowOptions wo;
  const std::vector<PassEstimate> pass = identify_pass(b, r.t, r.ddx_M, r.ddz_M, {}, wo, o);
  EXPECT_EQ(pass.size(), 1u);
  EXPECT_TRUE(pass.front().valid) << pass.front().reason;
  return pass.front().identification;
}

}  // namespace oscidrum
