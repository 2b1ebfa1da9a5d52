// Internal: the checks of a parameter that a driver varies through a range (continue_branch,
// bifurcation_diagram): a real field of the model, in effect in the case, both ends within its
// rule.
#pragma once

#include <string>

#include "oscidrum/fields.hpp"
#include "oscidrum/parameters.hpp"

namespace oscidrum::detail {

/// The field `key` names, checked: throws oscidrum::Error "WHO: ..." for an unknown key, one that
/// is not real-valued, a numerics.* key, a key without effect in `c`, or `from` / `to` outside
/// the field's rule (named as --from / --to).
const Field& varied_field(const Case& c, const std::string& key, double from, double to,
                          const std::string& who);

}  // namespace oscidrum::detail
