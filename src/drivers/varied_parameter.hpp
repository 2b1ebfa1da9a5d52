// Internal: the checks of a parameter that a driver varies through a range (continue_branch,
// bifurcation_diagram): a real field of the model, in effect in the case, both ends within its
// rule.
#pragma once

#include <string>

#include "oscidrum/fields.hpp"
#include "oscidrum/parameters.hpp"

namespace oscidrum::detail {

/// The case with the varied field at `value`: the field set, and where `MMd_fraction` is finite
/// (a case file's MMd_fraction or --MMd-fraction, which a study evaluates for each case) MMd =
/// MMd_fraction * M0 with the M0 in effect there, so that it follows roller.M0, or roller.f with
/// roller.unbalance (NaN: the case's MMd throughout).
void set_varied(Case& c, const Field& field, double value, double MMd_fraction);

/// The field `key` names, checked: throws oscidrum::Error "WHO: ..." for an unknown key, one that
/// is not real-valued, a numerics.* key, a key without effect in `c`, or `from` / `to` outside
/// the field's rule (named as --from / --to); a finite `MMd_fraction` with key MMd (which it
/// would set) or a roller without an oscillation moment (roller.type = vibratory).
const Field& varied_field(const Case& c, const std::string& key, double from, double to,
                          const std::string& who, double MMd_fraction);

/// A value of the field as people read it: in its display unit, with the unit ("100 MN/m^2" for
/// soil.G = 1e8 Pa, "0.5" for a dimensionless one).
std::string quoted_value(const Field& field, double value);

/// Why the case `c` with the field set to `value` is not valid (the field's rule, then the
/// model's checks of the whole case), or "" where it is.
std::string invalid_at(const Case& c, const Field& field, double value, double MMd_fraction);

/// For a parameter varied continuously from `from` to `to` (a branch): throws oscidrum::Error
/// "WHO: ..." when the case is not valid at a value between them (values just inside each end and
/// on a grid of kRangeChecks intervals): contact.mu_static from -1 ("equal to mu") to 0.6 passes
/// values below mu, which no case can have.
inline constexpr int kRangeChecks = 64;
void check_range_interior(const Case& c, const Field& field, double from, double to,
                          const std::string& who, double MMd_fraction);

}  // namespace oscidrum::detail
