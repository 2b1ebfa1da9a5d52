// Internal: the event functions of the hybrid flow. Each is scaled to O(1) and an event happens
// when one of them falls through zero (docs/model.md section 6).
#pragma once

#include <array>

#include "oscidrum/model.hpp"

namespace oscidrum {

/// In stick: 0 is mu N - T and 1 is mu N + T (the friction cone (28) on each side, over W); in
/// slip: 0 is s v_rel (the slip velocity (13) returning to zero, over a 1 mrad amplitude at nu)
/// and 1 is unused (1). Always: 2 is N / W (contact).
inline constexpr int kEventCount = 3;
inline constexpr int kEventConeNegative = 0;  ///< stick: mu N - T reaches 0 (T > 0: slip-)
inline constexpr int kEventConePositive = 1;  ///< stick: mu N + T reaches 0 (T < 0: slip+)
inline constexpr int kEventSlipVelocity = 0;  ///< slip: s v_rel reaches 0
inline constexpr int kEventContact = 2;       ///< N reaches 0
using EventValues = std::array<double, kEventCount>;

/// The event functions at state q in the given phase; N (optional) receives the normal force
/// they were computed from [N].
EventValues event_values(const Model& model, Phase phase, const State& q, double* N = nullptr);

/// event_values at the n states x[i] (the state vector (54)) into e[i] and N[i]: the same values,
/// evaluated in lanes (the samples of a step before its events are sought).
void event_values(const Model& model, Phase phase, const std::array<double, 8>* x, int n,
                  EventValues* e, double* N);

}  // namespace oscidrum
