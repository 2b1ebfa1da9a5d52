// Tests of the parameter table (oscidrum/fields.hpp) and of Model's validation (model.hpp):
// defaults are the paper's roller (docs/model.md section 1, paper Table 1) on the Table 2 soil at
// G = 25 MN/m^2; every field round-trips and touches only its own member; bad values are
// rejected with a message naming the key, the rule and the value.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/soil.hpp"

namespace oscidrum {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The test's own map from key to the Case member, written independently of fields.cpp, so that
// an accessor that reads or writes the wrong member is caught.
using Member = std::function<double&(Case&)>;
const std::map<std::string, Member>& members() {
  static const std::map<std::string, Member> m = {
      {"roller.r", [](Case& c) -> double& { return c.roller.r; }},
      {"roller.b", [](Case& c) -> double& { return c.roller.b; }},
      {"roller.m", [](Case& c) -> double& { return c.roller.m; }},
      {"roller.I", [](Case& c) -> double& { return c.roller.I; }},
      {"roller.P0", [](Case& c) -> double& { return c.roller.P0; }},
      {"roller.f", [](Case& c) -> double& { return c.roller.f; }},
      {"roller.M0", [](Case& c) -> double& { return c.roller.M0; }},
      {"roller.unbalance", [](Case& c) -> double& { return c.roller.unbalance; }},
      {"roller.kd", [](Case& c) -> double& { return c.roller.kd; }},
      {"roller.cd", [](Case& c) -> double& { return c.roller.cd; }},
      {"roller.g", [](Case& c) -> double& { return c.roller.g; }},
      {"roller.m_f", [](Case& c) -> double& { return c.roller.m_f; }},
      {"roller.static_moment", [](Case& c) -> double& { return c.roller.static_moment; }},
      {"soil.G", [](Case& c) -> double& { return c.soil.G; }},
      {"soil.nu", [](Case& c) -> double& { return c.soil.nu; }},
      {"soil.rho", [](Case& c) -> double& { return c.soil.rho; }},
      {"soil.ksh", [](Case& c) -> double& { return c.soil.ksh; }},
      {"soil.ksv", [](Case& c) -> double& { return c.soil.ksv; }},
      {"soil.csh", [](Case& c) -> double& { return c.soil.csh; }},
      {"soil.csv", [](Case& c) -> double& { return c.soil.csv; }},
      {"contact.mu", [](Case& c) -> double& { return c.contact.mu; }},
      {"contact.mu_static", [](Case& c) -> double& { return c.contact.mu_static; }},
      {"contact.v_eps", [](Case& c) -> double& { return c.contact.v_eps; }},
      {"MMd", [](Case& c) -> double& { return c.MMd; }},
      {"numerics.rtol", [](Case& c) -> double& { return c.numerics.rtol; }},
      {"numerics.atol", [](Case& c) -> double& { return c.numerics.atol; }},
      {"numerics.steady_tol", [](Case& c) -> double& { return c.numerics.steady_tol; }},
      {"numerics.slip_constraint_rate",
       [](Case& c) -> double& { return c.numerics.slip_constraint_rate; }},
  };
  return m;
}

// The trough keys, read and written on the shape itself: the circle of radius R is k = 0, a = R;
// the log spiral holds k and a.
bool is_trough_key(const std::string& key) { return key == "trough.k" || key == "trough.a"; }

double trough_direct(const Case& c, const std::string& key) {
  if (const auto* circle = std::get_if<CircleTrough>(&c.trough.shape))
    return key == "trough.k" ? 0.0 : circle->R;
  const auto& spiral = std::get<LogSpiralTrough>(c.trough.shape);
  return key == "trough.k" ? spiral.k() : spiral.a();
}

void set_trough_direct(Case& c, const std::string& key, double v) {
  double k = trough_direct(c, "trough.k"), a = trough_direct(c, "trough.a");
  (key == "trough.k" ? k : a) = v;
  if (k == 0.0)
    c.trough.shape = CircleTrough{a};
  else
    c.trough.shape = LogSpiralTrough(k, a);
}

// A real field set directly, bypassing the field table.
void set_direct(Case& c, const std::string& key, double v) {
  if (is_trough_key(key))
    set_trough_direct(c, key, v);
  else
    members().at(key)(c) = v;
}

// Non-double members (integers, booleans, the choice), read directly.
double direct_value(const Case& c0, const std::string& key) {
  Case c = c0;
  if (auto it = members().find(key); it != members().end()) return it->second(c);
  if (is_trough_key(key)) return trough_direct(c, key);
  if (key == "soil.input") return static_cast<double>(static_cast<int>(c.soil.input));
  if (key == "numerics.method") return static_cast<double>(static_cast<int>(c.numerics.method));
  if (key == "contact.pure_rolling") return c.contact.pure_rolling ? 1.0 : 0.0;
  if (key == "contact.law") return static_cast<double>(static_cast<int>(c.contact.law));
  if (key == "roller.type") return static_cast<double>(static_cast<int>(c.roller.type));
  if (key == "roller.exciter") return static_cast<double>(static_cast<int>(c.roller.exciter));
  if (key == "contact.unilateral") return c.contact.unilateral ? 1.0 : 0.0;
  if (key == "numerics.suspension_from_static") return c.numerics.suspension_from_static;
  if (key == "numerics.continuation") return c.numerics.continuation;
  if (key == "numerics.max_periods") return c.numerics.max_periods;
  if (key == "numerics.max_multiplicity") return c.numerics.max_multiplicity;
  if (key == "numerics.output_periods") return c.numerics.output_periods;
  if (key == "numerics.samples_per_period") return c.numerics.samples_per_period;
  if (key == "numerics.max_switches_per_period") return c.numerics.max_switches_per_period;
  if (key == "numerics.max_steps_per_period") return c.numerics.max_steps_per_period;
  if (key == "numerics.start_ramp_periods") return c.numerics.start_ramp_periods;
  ADD_FAILURE() << "the test does not know the field '" << key << "': add it to members()";
  return kNaN;
}

// A valid value of the field different from `current`.
double other_valid_value(const Field& f, double current) {
  switch (f.type) {
    case FieldType::boolean:
      return current == 0.0 ? 1.0 : 0.0;
    case FieldType::choice:
      return current == f.min ? f.max : f.min;
    case FieldType::integer:
      return current + 1.0 <= f.max ? current + 1.0 : current - 1.0;
    case FieldType::real:
      break;
  }
  for (double v : {current * 1.25, current * 0.75, current + 0.125, current - 0.125}) {
    if (v != current && check_field(f, v).empty()) return v;
  }
  ADD_FAILURE() << "no valid other value for " << f.key;
  return current;
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// ---- the table ------------------------------------------------------------------------------

TEST(Fields, EveryCaseMemberHasExactlyOneField) {
  // 15 roller + 8 soil + 2 trough + 6 contact + MMd + 13 numerics members in parameters.hpp.
  EXPECT_EQ(fields().size(), 46u);
  std::set<std::string> keys;
  for (const Field& f : fields()) {
    EXPECT_TRUE(keys.insert(f.key).second) << "duplicate key " << f.key;
    EXPECT_EQ(find_field(f.key), &f);
    EXPECT_NE(std::string(f.unit), "") << f.key;
    EXPECT_NE(std::string(f.description), "") << f.key;
    EXPECT_EQ(f.type == FieldType::choice, f.choices != nullptr) << f.key;
  }
  EXPECT_EQ(find_field("no.such.key"), nullptr);
}

TEST(Fields, GetReadsTheRightMember) {
  const Case c;
  for (const Field& f : fields()) EXPECT_EQ(get_field(c, f.key), direct_value(c, f.key)) << f.key;
}

TEST(Fields, EverySetRoundTripsAndTouchesOnlyItsOwnMember) {
  const Case defaults;
  for (const Field& f : fields()) {
    Case c;
    const double v = other_valid_value(f, f.get(c));
    ASSERT_NE(v, f.get(c)) << f.key;
    ASSERT_NO_THROW(set_field(c, f.key, v)) << f.key;
    EXPECT_EQ(get_field(c, f.key), v) << f.key;
    EXPECT_EQ(direct_value(c, f.key), v) << f.key << " writes another member";
    for (const Field& g : fields()) {
      if (&g == &f) continue;
      EXPECT_EQ(direct_value(c, g.key), direct_value(defaults, g.key))
          << "setting " << f.key << " changed " << g.key;
    }
    // Back to the default value: the round trip is exact.
    set_field(c, f.key, direct_value(defaults, f.key));
    EXPECT_EQ(direct_value(c, f.key), direct_value(defaults, f.key)) << f.key;
  }
}

// ---- defaults: the paper's roller (Table 1), Table 2 at G = 25, circle R = 0.606, mu = 0.5 ---

TEST(Fields, DefaultsAreThePapersRoller) {
  const Case c;
  EXPECT_EQ(c.roller.r, 0.6);
  EXPECT_EQ(c.roller.b, 1.68);
  EXPECT_EQ(c.roller.m, 1851.0);
  EXPECT_EQ(c.roller.I, 411.78);
  EXPECT_EQ(c.roller.P0, 45224.0);
  EXPECT_EQ(c.roller.f, 39.0);
  EXPECT_EQ(c.roller.M0, 54947.0);
  EXPECT_EQ(c.roller.kd, 4e6);
  EXPECT_EQ(c.roller.cd, 3e3);
  EXPECT_EQ(c.roller.g, 9.81);
  // Fz = P0 - m g = 27 066 N (7), as paper Table 1 gives it (to 1 N).
  EXPECT_NEAR(c.roller.P0 - c.roller.m * c.roller.g, 27066.0, 0.5);
  EXPECT_EQ(c.MMd, 0.0);
}

TEST(Fields, DefaultSoilIsTable2AtG25) {
  const Case c;
  const Table2Row* row = nullptr;
  for (const Table2Row& r : table2())
    if (r.G == 25e6) row = &r;
  ASSERT_NE(row, nullptr);
  EXPECT_EQ(c.soil.input, SoilInput::table2);
  // The model takes the row at G = 25 MN/m^2 (its one conversion of the soil input) ...
  const Model model(c);
  EXPECT_EQ(model.ksh(), row->ksh);
  EXPECT_EQ(model.ksv(), row->ksv);
  EXPECT_EQ(model.csh(), row->csh);
  EXPECT_EQ(model.csv(), row->csv);
  // ... which the default coefficients also hold (for soil.input = "coefficients").
  EXPECT_EQ(c.soil.ksh, row->ksh);
  EXPECT_EQ(c.soil.ksv, row->ksv);
  EXPECT_EQ(c.soil.csh, row->csh);
  EXPECT_EQ(c.soil.csv, row->csv);
  // The printed row itself (paper Table 2): 41.4, 66.3 MN/m; 141, 263 kN s/m.
  EXPECT_EQ(c.soil.ksh, 41.4e6);
  EXPECT_EQ(c.soil.ksv, 66.3e6);
  EXPECT_EQ(c.soil.csh, 141e3);
  EXPECT_EQ(c.soil.csv, 263e3);
  EXPECT_EQ(c.soil.G, 25e6);
  EXPECT_EQ(c.soil.nu, 0.3);
  EXPECT_EQ(c.soil.rho, 1900.0);
}

TEST(Fields, DefaultTroughContactAndNumerics) {
  const Case c;
  ASSERT_TRUE(std::holds_alternative<CircleTrough>(c.trough.shape));  // the paper's circle
  EXPECT_EQ(std::get<CircleTrough>(c.trough.shape).R, 0.606);
  EXPECT_EQ(get_field(c, "trough.a"), 0.606);
  EXPECT_EQ(get_field(c, "trough.k"), 0.0);
  EXPECT_EQ(c.contact.mu, 0.5);
  EXPECT_FALSE(c.contact.pure_rolling);
  EXPECT_FALSE(c.numerics.suspension_from_static);  // the paper's convention by default
  EXPECT_EQ(c.numerics.method, SteadyMethod::shooting);
  EXPECT_NO_THROW(Model{c});
}

// ---- set_field: rules and messages -------------------------------------------------------------

TEST(Fields, ExactMessageForNegativeShearModulus) {
  Case c;
  const std::string msg = error_of([&] { set_field(c, "soil.G", -5e6); });
  // The message documented in fields.hpp and error.hpp: key, rule, unit, value.
  EXPECT_EQ(msg, "soil.G must be in [10000, 1e+11] [Pa]; got -5e+06") << msg;
  EXPECT_EQ(c.soil.G, 25e6) << "a rejected value must leave the case unchanged";
  // The error carries the key and the value.
  try {
    set_field(c, "soil.G", -5e6);
  } catch (const Error& e) {
    EXPECT_EQ(e.key(), "soil.G");
    EXPECT_EQ(e.value(), -5e6);
  }
}

// Which keys take effect (key_in_effect): each soil input reads its own keys, roller.M0 is replaced
// by an unbalance, the trough keys are those of the shape; every other key always.
TEST(Fields, KeyInEffectFollowsTheSoilInputTheUnbalanceAndTheShape) {
  const std::vector<std::string> modulus_keys = {"soil.G", "soil.nu", "soil.rho"};
  const std::vector<std::string> coefficient_keys = {"soil.ksh", "soil.ksv", "soil.csh",
                                                     "soil.csv"};
  Case c;  // Table 2: G only
  EXPECT_TRUE(key_in_effect(c, "soil.G"));
  for (const char* k : {"soil.nu", "soil.rho", "soil.ksh", "soil.csv"})
    EXPECT_FALSE(key_in_effect(c, k)) << k;
  EXPECT_NE(key_not_in_effect(c, "soil.nu").find("Table 2 holds nu = 0.3"), std::string::npos);
  c.soil.input = SoilInput::modulus;
  for (const std::string& k : modulus_keys) EXPECT_TRUE(key_in_effect(c, k)) << k;
  for (const std::string& k : coefficient_keys) EXPECT_FALSE(key_in_effect(c, k)) << k;
  c.soil.input = SoilInput::coefficients;
  for (const std::string& k : modulus_keys) EXPECT_FALSE(key_in_effect(c, k)) << k;
  for (const std::string& k : coefficient_keys) EXPECT_TRUE(key_in_effect(c, k)) << k;
  EXPECT_EQ(key_not_in_effect(c, "soil.G")
                .rfind("soil.G has no effect while soil.input = \"coefficients\"", 0),
            0u);
  EXPECT_TRUE(key_in_effect(c, "roller.M0"));
  c.roller.unbalance = 0.22877;
  EXPECT_FALSE(key_in_effect(c, "roller.M0"));
  // The regularisation velocity only with the regularised law.
  EXPECT_FALSE(key_in_effect(c, "contact.v_eps"));
  c.contact.law = FrictionChoice::regularised;
  EXPECT_TRUE(key_in_effect(c, "contact.v_eps"));
  c.contact.pure_rolling = true;
  EXPECT_FALSE(key_in_effect(c, "contact.v_eps"));
  c.contact = Contact{};
  // Both shapes are given by trough.k and trough.a; every other key takes effect.
  c.trough.shape = LogSpiralTrough(0.002, 0.601);
  EXPECT_TRUE(key_in_effect(c, "trough.k"));
  EXPECT_TRUE(key_in_effect(Case{}, "trough.a"));
  // The drum width: Appendix B (soil.input = modulus) and the vibratory drum's Evib-type modulus
  // (on a soil with a Poisson's ratio) read it; nothing else does.
  EXPECT_FALSE(key_in_effect(c, "roller.b"));  // the soil by its coefficients here
  {
    Case table2_case;  // Table 2: roller.b in no formula the paper's drum reads
    EXPECT_FALSE(key_in_effect(table2_case, "roller.b"));
    EXPECT_NE(key_not_in_effect(table2_case, "roller.b").find("enters Appendix B"),
              std::string::npos);
    Case m = c;
    m.soil.input = SoilInput::modulus;
    EXPECT_TRUE(key_in_effect(m, "roller.b"));
    Case v = table2_case;
    v.roller.type = RollerType::vibratory;
    EXPECT_TRUE(key_in_effect(v, "roller.b"));
    v.soil.input = SoilInput::coefficients;
    EXPECT_FALSE(key_in_effect(v, "roller.b"));
  }
  for (const Field& f : fields()) {
    const std::string key = f.key;
    // The vibratory drum's keys take effect with roller.type = vibratory only
    // (tests/roller/test_vibratory_drum.cpp).
    if (!key.starts_with("soil.") && key != "roller.M0" && key != "contact.v_eps" &&
        key != "roller.static_moment" && key != "roller.exciter" && key != "roller.b") {
      EXPECT_TRUE(key_in_effect(c, key)) << key;
    }
    EXPECT_EQ(key_in_effect(c, key), key_not_in_effect(c, key).empty()) << key;
  }
}

// A value that is right in the unit people say it in (issue 25, point 8): soil.G = 30 is meant as
// 30 MN/m^2 = 30e6 Pa. Values are SI; the message says so and what was meant.
TEST(Fields, ValueInTheDisplayUnitGetsAHint) {
  Case c;
  const Field& G = *find_field("soil.G");
  EXPECT_EQ(std::string(G.display_unit), "MN/m^2");
  EXPECT_EQ(G.display_scale, 1e6);
  EXPECT_EQ(error_of([&] { set_field(c, "soil.G", 30.0); }),
            "soil.G must be in [10000, 1e+11] [Pa]; got 30 (values are in Pa: did you mean 3e+07, "
            "i.e. 30 MN/m^2?)");
  // No hint where the value would not fit either, nor for a field shown in its own unit.
  EXPECT_EQ(error_of([&] { set_field(c, "soil.G", 1e6 * 1e6); }).find("did you mean"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { set_field(c, "roller.r", -0.6); }).find("did you mean"),
            std::string::npos);
  EXPECT_EQ(std::string(display_unit(*find_field("roller.r"))), "m");
}

TEST(Fields, MessagesNameKeyRuleAndValue) {
  Case c;
  EXPECT_EQ(error_of([&] { set_field(c, "soil.nu", 0.5); }),
            "soil.nu must be in [0, 0.5); got 0.5");
  EXPECT_EQ(error_of([&] { set_field(c, "contact.mu", -0.1); }),
            "contact.mu must be >= 0; got -0.1");
  EXPECT_EQ(error_of([&] { set_field(c, "roller.m", 0.0); }), "roller.m must be > 0 [kg]; got 0");
  EXPECT_EQ(error_of([&] { set_field(c, "roller.kd", -1.0); }),
            "roller.kd must be >= 0 [N/m]; got -1");
  const std::string nan_msg = error_of([&] { set_field(c, "roller.I", kNaN); });
  EXPECT_NE(nan_msg.find("roller.I must be finite and > 0 [kg m^2]; got "), std::string::npos)
      << nan_msg;
  EXPECT_NE(nan_msg.find("nan"), std::string::npos) << nan_msg;
  // inf is > 0: the rule says that the value must be finite too.
  EXPECT_EQ(error_of([&] { set_field(c, "roller.m", kInf); }),
            "roller.m must be finite and > 0 [kg]; got inf");
  const std::string inf_msg = error_of([&] { set_field(c, "MMd", -kInf); });
  EXPECT_NE(inf_msg.find("MMd must be finite [N m]; got -inf"), std::string::npos) << inf_msg;
  const std::string int_msg = error_of([&] { set_field(c, "numerics.max_periods", 2.5); });
  EXPECT_NE(int_msg.find("numerics.max_periods must be an integer"), std::string::npos) << int_msg;
  EXPECT_NE(int_msg.find("got 2.5"), std::string::npos) << int_msg;
}

TEST(Fields, EveryFieldRejectsNonFiniteValuesAndLeavesTheCaseUnchanged) {
  for (const Field& f : fields()) {
    for (double bad : {kNaN, kInf, -kInf}) {
      Case c;
      const double before = f.get(c);
      const std::string msg = error_of([&] { set_field(c, f.key, bad); });
      EXPECT_EQ(msg.rfind(std::string(f.key) + " must be ", 0), 0u) << f.key << ": " << msg;
      EXPECT_EQ(f.get(c), before) << f.key;
    }
  }
}

TEST(Fields, EveryFieldRejectsValuesOutsideItsRange) {
  for (const Field& f : fields()) {
    if (f.type == FieldType::boolean) {
      Case c;
      EXPECT_THROW(set_field(c, f.key, 0.5), Error) << f.key;
      EXPECT_THROW(set_field(c, f.key, 2.0), Error) << f.key;
      continue;
    }
    std::vector<double> bad;
    if (std::isfinite(f.min)) {
      bad.push_back(f.min_open ? f.min : f.min - 1.0);
      const double inside = f.min_open ? std::nextafter(f.min, kInf) : f.min;
      if (f.type == FieldType::real) {
        EXPECT_EQ(check_field(f, inside), "") << f.key;
      }
    }
    if (std::isfinite(f.max)) {
      bad.push_back(f.max_open ? f.max : f.max + 1.0);
      const double inside = f.max_open ? std::nextafter(f.max, -kInf) : f.max;
      if (f.type == FieldType::real) {
        EXPECT_EQ(check_field(f, inside), "") << f.key;
      }
    }
    for (double v : bad) {
      Case c;
      const double before = f.get(c);
      const std::string msg = error_of([&] { set_field(c, f.key, v); });
      EXPECT_EQ(msg.rfind(std::string(f.key) + " must be " + field_rule(f), 0), 0u)
          << f.key << " = " << v << ": " << msg;
      EXPECT_NE(msg.find("; got "), std::string::npos) << msg;
      EXPECT_EQ(f.get(c), before) << f.key;
    }
  }
}

TEST(Fields, RulesReadAsDocumented) {
  EXPECT_EQ(field_rule(*find_field("soil.G")), "in [10000, 1e+11]");
  EXPECT_EQ(field_rule(*find_field("soil.nu")), "in [0, 0.5)");
  EXPECT_EQ(field_rule(*find_field("contact.mu")), ">= 0");
  EXPECT_EQ(field_rule(*find_field("MMd")), "finite");
  EXPECT_EQ(field_rule(*find_field("contact.pure_rolling")), "true or false");
  EXPECT_EQ(field_rule(*find_field("soil.input")), "one of coefficients, modulus, table2");
}

TEST(Fields, UnknownKeySuggestsTheNearestKey) {
  Case c;
  EXPECT_EQ(error_of([&] { set_field(c, "soil.g", 1.0); }),
            "unknown parameter 'soil.g'; did you mean 'soil.G'?");
  EXPECT_EQ(error_of([&] { (void)get_field(c, "roller.mas"); }),
            "unknown parameter 'roller.mas'; did you mean 'roller.m'?");
  EXPECT_EQ(error_of([&] { set_field_text(c, "contact.mue", "0.4"); }),
            "unknown parameter 'contact.mue'; did you mean 'contact.mu'?");
  // A key's name without its section: that key (by edit distance M0 and mu were 'MMd').
  EXPECT_EQ(error_of([&] { set_field(c, "M0", 1.0); }),
            "unknown parameter 'M0'; did you mean 'roller.M0'?");
  EXPECT_EQ(error_of([&] { set_field(c, "mu", 1.0); }),
            "unknown parameter 'mu'; did you mean 'contact.mu'?");
  // A typo of such a name: the name in its section is nearer than any whole key ('muu' was 3
  // edits from 'MMd' and got that).
  EXPECT_EQ(error_of([&] { set_field(c, "muu", 1.0); }),
            "unknown parameter 'muu'; did you mean 'contact.mu'?");
  EXPECT_EQ(error_of([&] { set_field(c, "rtoll", 1.0); }),
            "unknown parameter 'rtoll'; did you mean 'numerics.rtol'?");
  // Nothing close: no suggestion.
  EXPECT_EQ(error_of([&] { set_field(c, "completely.unrelated", 1.0); }),
            "unknown parameter 'completely.unrelated'");
}

// ---- set_field_text ---------------------------------------------------------------------------

TEST(Fields, TextParsesNumbersBooleansAndChoices) {
  Case c;
  set_field_text(c, "soil.G", "4.5e7");
  EXPECT_EQ(c.soil.G, 4.5e7);
  set_field_text(c, "MMd", "-2747.35");
  EXPECT_EQ(c.MMd, -2747.35);
  set_field_text(c, "numerics.max_periods", "300");
  EXPECT_EQ(c.numerics.max_periods, 300);
  set_field_text(c, "contact.pure_rolling", "true");
  EXPECT_TRUE(c.contact.pure_rolling);
  set_field_text(c, "contact.pure_rolling", "false");
  EXPECT_FALSE(c.contact.pure_rolling);
  set_field_text(c, "numerics.suspension_from_static", "true");
  EXPECT_TRUE(c.numerics.suspension_from_static);
  // Issue 14 (4): exactly true/false, integers as digits (the config file's rules).
  EXPECT_NE(error_of([&] {
              set_field_text(c, "numerics.suspension_from_static", "1");
            }).find("must be true or false"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              set_field_text(c, "numerics.max_periods", "1e3");
            }).find("must be an integer"),
            std::string::npos);
  set_field_text(c, "soil.input", "modulus");
  EXPECT_EQ(c.soil.input, SoilInput::modulus);
  EXPECT_EQ(format_field(c, *find_field("soil.input")), "modulus");
  set_field_text(c, "soil.input", "coefficients");
  EXPECT_EQ(c.soil.input, SoilInput::coefficients);
  EXPECT_EQ(format_field(c, *find_field("contact.pure_rolling")), "false");
}

TEST(Fields, TextRejectsGarbage) {
  const Case defaults;
  for (const char* text : {"", "abc", "12abc", "1e", "0.5.5", "--1"}) {
    Case c;
    const std::string msg = error_of([&] { set_field_text(c, "soil.G", text); });
    EXPECT_EQ(msg.rfind("soil.G must be a decimal number", 0), 0u) << "'" << text << "': " << msg;
    EXPECT_NE(msg.find(std::string("'") + text + "'"), std::string::npos) << msg;
    EXPECT_EQ(c.soil.G, defaults.soil.G);
  }
  Case c;
  // Parsed numbers still go through the field's rule.
  EXPECT_THROW(set_field_text(c, "soil.G", "-5e6"), Error);
  EXPECT_THROW(set_field_text(c, "soil.G", "nan"), Error);
  EXPECT_THROW(set_field_text(c, "soil.G", "inf"), Error);
  EXPECT_THROW(set_field_text(c, "numerics.max_periods", "2.5"), Error);
  EXPECT_THROW(set_field_text(c, "contact.pure_rolling", "maybe"), Error);
  EXPECT_THROW(set_field_text(c, "contact.pure_rolling", "2"), Error);
  const std::string msg = error_of([&] { set_field_text(c, "soil.input", "gravel"); });
  EXPECT_EQ(msg, "soil.input must be one of coefficients, modulus, table2; got 'gravel'");
  EXPECT_EQ(c.soil.G, defaults.soil.G);
  EXPECT_EQ(c.soil.input, defaults.soil.input);
  EXPECT_EQ(c.contact.pure_rolling, defaults.contact.pure_rolling);
}

// ---- Model construction: every rule, with the field named in the message ----------------------

// Model{c} must throw oscidrum::Error whose message contains every one of `parts`.
void expect_model_rejects(const Case& c, std::initializer_list<std::string> parts) {
  const std::string msg = error_of([&] { Model model(c); });
  ASSERT_NE(msg, "(no error)");
  for (const std::string& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << msg;
}

TEST(ModelValidation, RejectsNonPositiveMassRadiusInertia) {
  for (double bad : {0.0, -1.0}) {
    Case c;
    c.roller.m = bad * 1851.0;
    expect_model_rejects(c, {"roller.m", "> 0", "[kg]"});
    c = Case{};
    c.roller.r = bad * 0.6;
    expect_model_rejects(c, {"roller.r", "> 0", "[m]"});
    c = Case{};
    c.roller.I = bad * 411.78;
    expect_model_rejects(c, {"roller.I", "> 0"});
    c = Case{};
    c.roller.b = bad;
    expect_model_rejects(c, {"roller.b", "> 0"});
  }
}

TEST(ModelValidation, RejectsNonPositiveStiffness) {
  Case c;
  c.soil.ksh = 0.0;
  expect_model_rejects(c, {"soil.ksh", "> 0", "got 0"});
  c = Case{};
  c.soil.ksv = -66.3e6;
  expect_model_rejects(c, {"soil.ksv", "> 0"});
  c = Case{};
  c.soil.csh = 0.0;
  expect_model_rejects(c, {"soil.csh", "> 0"});
  c = Case{};
  c.roller.kd = -4e6;
  expect_model_rejects(c, {"roller.kd", ">= 0", "got -4"});
  c = Case{};
  c.soil.input = SoilInput::modulus;
  c.soil.G = 0.0;
  expect_model_rejects(c, {"soil.G", "in [10000, 1e+11]", "got 0"});
}

TEST(ModelValidation, RejectsCircularTroughNotLargerThanTheDrum) {
  Case c;
  c.trough.shape = CircleTrough{0.6};  // R = r
  expect_model_rejects(c, {"trough.a", "roller.r", "0.6"});
  c.trough.shape = CircleTrough{0.59};  // R < r
  expect_model_rejects(c, {"trough.a", "roller.r", "0.59"});
  c.trough.shape = CircleTrough{0.603};  // the paper's smallest R: fine
  EXPECT_NO_THROW(Model{c});
}

TEST(ModelValidation, RejectsNegativeFriction) {
  Case c;
  c.contact.mu = -0.5;
  expect_model_rejects(c, {"contact.mu", ">= 0", "-0.5"});
  c.contact.mu = 0.0;  // frictionless contact is a valid (degenerate) model
  EXPECT_NO_THROW(Model{c});
}

TEST(ModelValidation, RejectsPoissonRatioOutsideItsRangeForModulusInput) {
  for (double bad : {-0.1, 0.5, 0.7}) {
    Case c;
    c.soil.input = SoilInput::modulus;
    c.soil.nu = bad;
    expect_model_rejects(c, {"soil.nu", "[0, 0.5)"});
  }
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.nu = 0.0;
  EXPECT_NO_THROW(Model{c});
  c.soil.nu = 0.49;
  EXPECT_NO_THROW(Model{c});
}

TEST(ModelValidation, RejectsAxleLoadBelowDrumWeight) {
  Case c;
  c.roller.P0 = 18000.0;  // < m g = 18158.31 N, so Fz = P0 - m g < 0 (7)
  expect_model_rejects(c, {"roller.P0", "18000"});
  c.roller.P0 = c.roller.m * c.roller.g;  // Fz = 0: the drum alone, allowed
  EXPECT_NO_THROW(Model{c});
}

// A case far stiffer than any roller (its fastest rate on the supports over 2e4 times roller.f)
// would take minutes or fail (roller.cd = 2e9 N s/m ran 44 s into max_periods_reached): refused,
// naming the field that makes it stiff; just below the bound it is accepted (and runs).
TEST(ModelValidation, RejectsACaseTooStiffToIntegrate) {
  {
    // The paper's roller on G = 25 MN/m^2, which the message and docs/config.md quote: its
    // fastest rate is sqrt((kd + ksv) / m) = 5.0 f.
    const Case paper;
    const Model m(paper);
    const Roller& R = paper.roller;
    const double rates[] = {(R.cd + m.csh()) / R.m, (R.cd + m.csv()) / R.m,
                            std::sqrt((R.kd + m.ksh()) / R.m), std::sqrt((R.kd + m.ksv()) / R.m)};
    EXPECT_NEAR(*std::max_element(std::begin(rates), std::end(rates)) / R.f, 5.0, 0.05);
    EXPECT_EQ(std::max_element(std::begin(rates), std::end(rates)), std::end(rates) - 1);
  }
  Case c;
  c.roller.cd = 2e9;  // (cd + csh) / m = 1.08e6 1/s = 2.8e4 f
  expect_model_rejects(c, {"roller.cd", "too stiff", "2e+09", "(roller.cd + csh) / roller.m"});
  c.roller.cd = 1e9;  // 1.4e4 f
  EXPECT_NO_THROW(Model{c});
  c = Case{};
  c.roller.kd = 1e15;  // sqrt((kd + ksv) / m) = 7.4e5 1/s = 1.9e4 f: accepted
  EXPECT_NO_THROW(Model{c});
  c.roller.kd = 2e15;  // 2.7e4 f
  expect_model_rejects(c, {"roller.kd", "sqrt((roller.kd + ks"});
  c = Case{};
  c.soil.input = SoilInput::coefficients;
  c.soil.csv = 5e9;  // the soil's dashpot dominates
  expect_model_rejects(c, {"soil.csv", "(roller.cd + csv) / roller.m"});
  c = Case{};
  c.roller.m = 0.2;  // a drum of 200 g: every rate is fast (3.4e4 f), the mass is named
  expect_model_rejects(c, {"roller.m = 0.2"});
  // The stiffest soil the fields admit, through Appendix B, is far inside the bound.
  c = Case{};
  c.soil.input = SoilInput::modulus;
  c.soil.G = 1e11;
  EXPECT_NO_THROW(Model{c});
  // ... at 39 Hz; at 0.1 Hz it is not, and the soil is named, not the paper's roller.kd beside
  // it (the message said "roller.kd = 4e+06 makes it so").
  c.roller.f = 0.1;
  expect_model_rejects(c, {"the soil's ksh", "from Appendix B (42)-(45) at soil.G = 1e+11 Pa",
                           "at roller.f = 0.1 Hz"});
  // ... where soil.nu near 1/2 is not the cause (a spring, not the vertical dashpot): not named.
  c.soil.nu = 0.495;
  try {
    const Model m(c);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("soil.nu near 1/2"), std::string::npos) << e.what();
  }
  // An incompressible soil: Appendix B's dashpot csv, from soil.nu (not roller.cd = 3000).
  c = Case{};
  c.soil.input = SoilInput::modulus;
  c.soil.G = 27e6;
  c.soil.nu = 0.49999999999;
  expect_model_rejects(c, {"the soil's csv", "soil.nu near 1/2"});
}

TEST(ModelValidation, RejectsNaNInEveryRealField) {
  for (const Field& f : fields()) {
    if (f.type != FieldType::real) continue;
    Case c;
    ASSERT_TRUE(members().count(f.key) || is_trough_key(f.key)) << f.key;
    set_direct(c, f.key, kNaN);
    expect_model_rejects(c, {std::string(f.key) + " must be ", "nan"});
  }
}

TEST(ModelValidation, RejectsInfinityInEveryRealField) {
  for (const Field& f : fields()) {
    if (f.type != FieldType::real) continue;
    Case c;
    set_direct(c, f.key, kInf);
    expect_model_rejects(c, {std::string(f.key) + " must be ", "inf"});
  }
}

TEST(ModelValidation, ModulusInputGoesThroughAppendixB) {
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = 40e6;
  const Model model(c);
  const SoilCoefficients s = soil_coefficients(40e6, 0.3, 1900.0, c.roller);
  EXPECT_EQ(model.ksh(), s.ksh);
  EXPECT_EQ(model.ksv(), s.ksv);
  EXPECT_EQ(model.csh(), s.csh);
  EXPECT_EQ(model.csv(), s.csv);
}

TEST(ModelValidation, DerivedConstants) {
  const Case c;
  const Model model(c);
  EXPECT_NEAR(model.W(), c.roller.P0, 1e-12 * c.roller.P0);  // W = m g + Fz = P0
  EXPECT_NEAR(model.Fz(), 27066.0, 0.5);                     // (7)
  EXPECT_DOUBLE_EQ(model.nu(), 2.0 * M_PI * 39.0);
  EXPECT_DOUBLE_EQ(model.period(), 1.0 / 39.0);
  EXPECT_EQ(model.z_ref(), 0.0);  // the paper: kd acts on z_M measured from t = 0
  // (5), (6): MM(t) = M0 sin(nu t) + MMd.
  Case d = c;
  d.MMd = 0.05 * d.roller.M0;
  const Model driven(d);
  const double t = 0.3 / 39.0;
  EXPECT_NEAR(driven.torque(t), 54947.0 * std::sin(2.0 * M_PI * 39.0 * t) + 0.05 * 54947.0,
              1e-12 * 54947.0);
}

// The excitation's angle nu t wrapped to [0, 2 pi) (the output column alpha): within rounding of
// the exact remainder of nu t by 2 pi, over a thousand periods and at the wrap itself; the torque
// is M0 sin(alpha) + MMd there.
TEST(ModelValidation, ExcitationAngleIsNuTWrappedToOneTurn) {
  const Model model{Case{}};
  const double f = 39.0, T = 1.0 / f;
  for (double t : {0.0, 0.3 * T, 0.999 * T, T, 1.0000001 * T, 17.25 * T, 999.9 * T, 1000.0 * T,
                   std::nextafter(T, 0.0), std::nextafter(5.0 * T, 10.0)}) {
    const double alpha = model.excitation_angle(t);
    EXPECT_GE(alpha, 0.0) << t;
    EXPECT_LT(alpha, 2.0 * M_PI) << t;
    // The remainder in long double: nu t to about 1e-19 relative.
    const long double turns = static_cast<long double>(f) * t;
    long double wrapped = (turns - std::floor(turns)) * 2.0L * 3.14159265358979323846264338L;
    // Rounded to either end of the turn: the same angle.
    if (wrapped > 2.0L * 3.14159265358979323846264338L - 1e-11L) wrapped = 0.0L;
    if (alpha > 2.0 * M_PI - 1e-11) continue;
    EXPECT_NEAR(alpha, static_cast<double>(wrapped), 4e-16 * (1.0 + f * t) * 2.0 * M_PI) << t;
    EXPECT_NEAR(model.torque(t), 54947.0 * std::sin(alpha), 1e-11 * 54947.0 * (1.0 + f * t)) << t;
  }
}

// (5): M0 = 4 m_u e_u e_w nu^2. The paper's roller (54 947 N m at 39 Hz) has m_u e_u e_w =
// 0.22877 kg m^2; given by its unbalance, M0 follows f^2 and replaces roller.M0.
TEST(ModelValidation, UnbalanceGivesM0ThatGrowsWithFSquared) {
  Case c;
  EXPECT_EQ(oscillation_moment(c.roller), 54947.0);  // unset: M0 as given
  c.roller.unbalance = 0.22877;
  EXPECT_NEAR(oscillation_moment(c.roller), 54947.0, 1.0);
  c.roller.M0 = 1.0;  // ignored while the unbalance is set
  c.roller.f = 19.5;  // half the frequency: a quarter of the moment
  EXPECT_NEAR(oscillation_moment(c.roller), 54947.0 / 4.0, 0.25);
  const Model model(c);
  const double t = 0.3 / 19.5;
  EXPECT_NEAR(model.torque(t), oscillation_moment(c.roller) * std::sin(2.0 * M_PI * 19.5 * t),
              1e-9 * 54947.0);
  EXPECT_NE(find_field("roller.unbalance"), nullptr);
  EXPECT_THROW(set_field(c, "roller.unbalance", -1.0), Error);
}

}  // namespace
}  // namespace oscidrum
