// The checks of a varied parameter (drivers/varied_parameter.hpp).
#include "drivers/varied_parameter.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/model.hpp"
#include "util/format.hpp"

namespace oscidrum::detail {

void set_varied(Case& c, const Field& field, double value, double MMd_fraction) {
  field.set(c, value);
  if (std::isfinite(MMd_fraction)) c.MMd = MMd_fraction * oscillation_moment(c.roller);
}

const Field& varied_field(const Case& c, const std::string& key, double from, double to,
                          const std::string& who, double MMd_fraction) {
  const Field* field = find_field(key);
  if (!field) throw Error(who + ": unknown key '" + key + "' (oscidrum fields lists them)");
  if (!std::isnan(MMd_fraction)) {
    if (!std::isfinite(MMd_fraction))
      throw Error(who + ": MMd_fraction must be finite; got " + shortest(MMd_fraction),
                  "MMd_fraction", MMd_fraction);
    if (key == "MMd")
      throw Error(who +
                      ": MMd is the varied parameter, and MMd_fraction (--MMd-fraction) would "
                      "set it at every value: give one of them",
                  "MMd_fraction", MMd_fraction);
    if (c.roller.type == RollerType::vibratory)
      throw Error(who +
                      ": MMd_fraction has no effect while roller.type = \"vibratory\" (it "
                      "has no oscillation moment M0); give MMd in N m",
                  "MMd_fraction", MMd_fraction);
  }
  if (field->type != FieldType::real)
    throw Error(who + ": " + key + " is not a real-valued parameter");
  if (key.rfind("numerics.", 0) == 0)
    throw Error(who + ": " + key + " is a numerical setting, not a parameter of the model");
  if (!key_in_effect(c, key))
    throw Error(who + ": " + key + " has no effect in this case: " + key_not_in_effect(c, key));
  // Keys a case file may hold without effect (a warning there, so that a study can sweep
  // contact.pure_rolling over a base case with mu), but that a branch or a diagram cannot vary:
  // every orbit would be the same one (a branch of 23 equal orbits, exit 0).
  if (c.contact.pure_rolling && (key == "contact.mu" || key == "contact.mu_static"))
    throw Error(who + ": " + key +
                " has no effect in this case: contact.pure_rolling = true (rolling without a "
                "friction limit); vary it with contact.pure_rolling = false");
  if (key == "roller.m_f")
    throw Error(who + ": " + key +
                " has no effect on the drum's motion: it enters the Appendix A transmissibility "
                "only (oscidrum transmissibility)");
  // The ends as Python's arguments and the CLI's flags name them.
  for (const auto& [name, value] : {std::pair{"from (--from)", from}, std::pair{"to (--to)", to}}) {
    const std::string why = check_field(*field, value);
    if (!why.empty()) throw Error(who + ": " + name + ": " + why, key, value);
  }
  // roller.unbalance = 0 is not a moment of zero but "M0 as roller.M0 gives it": the model
  // jumps there (M0 = 4 m_u e_u e_w nu^2 just above), so no branch or row of values can start,
  // end or pass at it.
  if (key == "roller.unbalance" && (from == 0.0 || to == 0.0))
    throw Error(who + ": roller.unbalance = 0 means M0 as roller.M0 gives it (" +
                    shortest(c.roller.M0) +
                    " N m here), not a moment of 0: M0 jumps there; start the range above 0 (e.g. "
                    "0.01 kg m^2), or vary roller.M0 instead",
                key, 0.0);
  // The rules between fields too (a drum radius beyond the trough's, ...): a range whose end no
  // case can have is said now, not after a branch crawled towards it and failed there.
  for (const auto& [name, value] : {std::pair{"from (--from)", from}, std::pair{"to (--to)", to}}) {
    Case at = c;
    set_varied(at, *field, value, MMd_fraction);
    try {
      const Model model(at);
    } catch (const Error& e) {
      throw Error(who + ": " + name + " " + shortest(value) + " " + field->unit +
                      ": the case is not valid there: " + e.what(),
                  key, value);
    }
  }
  return *field;
}

std::string quoted_value(const Field& field, double value) {
  const std::string unit = display_unit(field);
  return shortest(value / field.display_scale) + (unit == "-" ? "" : " " + unit);
}

std::string invalid_at(const Case& c, const Field& field, double value, double MMd_fraction) {
  Case at = c;
  try {
    set_varied(at, field, value, MMd_fraction);
    std::string why = check_field(field, value);
    if (why.empty()) (void)Model(at);
    return why;
  } catch (const Error& e) {
    return e.what();
  }
}

void check_range_interior(const Case& c, const Field& field, double from, double to,
                          const std::string& who, double MMd_fraction) {
  std::vector<double> values = {from + 1e-6 * (to - from), to - 1e-6 * (to - from)};
  for (int k = 1; k < kRangeChecks; ++k) values.push_back(from + (to - from) * k / kRangeChecks);
  std::sort(values.begin(), values.end(), [&](double a, double b) {
    return (a - from) * (to - from) < (b - from) * (to - from);  // from --from towards --to
  });
  for (const double value : values) {
    const std::string why = invalid_at(c, field, value, MMd_fraction);
    if (!why.empty())
      throw Error(who + ": " + field.key + " = " + shortest(value) +
                      (std::string(field.unit) == "-" ? "" : " " + std::string(field.unit)) +
                      ", between from = " + shortest(from) + " and to = " + shortest(to) +
                      " (--from, --to): the case is not valid there (" + why +
                      "); a branch varies the parameter continuously from one to the other: "
                      "choose a range whose every value is valid",
                  field.key, value);
  }
}

}  // namespace oscidrum::detail
