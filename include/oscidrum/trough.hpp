// oscidrum/trough.hpp: the settlement trough's shape as a component (docs/model.md section 1.4,
// docs/architecture.md "Components"). A shape is a type that owns its parameters, its roll curve
// (15)-(16) with the derivatives (46)-(50) and their rates, the rolling relation (11), its
// curvature at the bottom, its check against the drum and its summary. Every shape provides the
// functions listed under TroughShapeType below, in its own file src/physics/trough_<name>.cpp;
// the shapes are gathered in the variant TroughShape, and every function on a TroughShape
// dispatches with std::visit, so that a shape that misses a function does not compile.
#pragma once

#include <concepts>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace oscidrum {

struct Kinematics;       // oscidrum/kinematics.hpp
struct KinematicsRates;  // oscidrum/kinematics.hpp

/// One number that describes a shape, for summaries, JSON and Python.
struct TroughParameter {
  const char* symbol;  ///< "R", "k", "a", "alpha", "R0"
  double value;        ///< in `unit`
  const char* unit;    ///< "m", "rad", "-"
  const char* key;     ///< the case key that sets it ("trough.a"), or nullptr if derived
};

/// Where a drum stands against the trough when it is not in contact (contact.unilateral, docs/
/// model.md section 13): the position angle delta of the trough's point nearest to the drum (its
/// normal passes through the drum centre M), and the gap between drum and trough along that
/// normal, > 0 apart, < 0 overlapping. In contact the gap is 0 and delta is the contact's.
struct TroughGap {
  double delta = 0.0;  ///< [rad]
  double gap = 0.0;    ///< [m]
};

/// Why a drum cannot roll in a trough: the message, naming the rule and the values, and the case
/// key it is about. An empty message: the drum fits.
struct FitProblem {
  std::string message;
  const char* key = nullptr;
};

// ---- the circle -------------------------------------------------------------------------------

/// Circular trough of radius R (the paper's circle, k = 0 in (8)).
struct CircleTrough {
  static constexpr const char* name = "circle";
  double R = 0.606;  ///< trough radius [m]

  bool operator==(const CircleTrough&) const = default;
};

/// "circle, R = 0.606 m".
std::string summary(const CircleTrough& s);
/// R (set by trough.a).
std::vector<TroughParameter> parameters(const CircleTrough& s);
/// The value of a case key for this shape (trough.k = 0, trough.a = R), NaN for another key.
double key_value(const CircleTrough& s, std::string_view key);
/// Radius of curvature at the bottom (delta = 0) [m]: R.
double curvature_radius_at_bottom(const CircleTrough& s);
/// The curvature radius at the bottom as a formula of the case's keys, for messages: "trough.a".
const char* curvature_radius_formula(const CircleTrough& s);
/// Whether a drum of radius r [m] can roll in the circle: R must exceed r (key trough.a).
FitProblem fit_problem(const CircleTrough& s, double r);
/// (15), (16), (46)-(50), (33), (37) at delta [rad] for a drum of radius r [m].
Kinematics kinematics(const CircleTrough& s, double r, double delta);
/// d f2, d f4, d f6 / d delta at delta [rad].
KinematicsRates kinematics_rates(const CircleTrough& s, double r, double delta);
/// (11) at k = 0: phi = (R - r) delta / r [rad].
double phi_rolling(const CircleTrough& s, double r, double delta);
/// The gap of a drum of radius r [m] whose centre is at (x, z) [m] from the trough's point A
/// (the centre's position in contact at delta is (x_roll, z_roll) (15), (16)): the drum centre's
/// distance from the trough's centre, (0, -(R - r)), falls short of R - r by the gap.
TroughGap gap(const CircleTrough& s, double r, double x, double z);

// ---- the logarithmic spiral ---------------------------------------------------------------------

/// Log-spiral trough R(theta) = a exp(k theta), k > 0 (8), with alpha = atan(1/k),
/// theta0 = pi - alpha and R0 = a exp(k theta0), the radius at the bottom. The derived values are
/// computed once, by the constructor.
class LogSpiralTrough {
 public:
  static constexpr const char* name = "log_spiral";
  /// k [-] > 0 and a [m] > 0 (the case's rules check them; see fields.hpp).
  LogSpiralTrough(double k = 0.002, double a = 0.606);

  double k() const { return k_; }                  ///< [-]
  double a() const { return a_; }                  ///< [m]
  double alpha() const { return alpha_; }          ///< atan(1/k) (8) [rad]
  double R0() const { return R0_; }                ///< a exp(k (pi - alpha)) (8) [m]
  double sin_alpha() const { return sin_alpha_; }  ///< [-]
  double cos_alpha() const { return cos_alpha_; }  ///< [-]
  double root() const { return root_; }            ///< sqrt(1 + k^2) [-]

  bool operator==(const LogSpiralTrough& other) const { return k_ == other.k_ && a_ == other.a_; }

 private:
  double k_, a_, alpha_, R0_, sin_alpha_, cos_alpha_, root_;
};

/// "log spiral, k = 0.002, a = 0.601 m".
std::string summary(const LogSpiralTrough& s);
/// k (trough.k), a (trough.a), and the derived alpha, R0.
std::vector<TroughParameter> parameters(const LogSpiralTrough& s);
/// trough.k = k, trough.a = a; NaN for another key.
double key_value(const LogSpiralTrough& s, std::string_view key);
/// sqrt(1 + k^2) R0 [m].
double curvature_radius_at_bottom(const LogSpiralTrough& s);
/// "sqrt(1+k^2) R0".
const char* curvature_radius_formula(const LogSpiralTrough& s);
/// Whether a drum of radius r [m] can roll in the spiral: sqrt(1 + k^2) R0 must exceed r.
FitProblem fit_problem(const LogSpiralTrough& s, double r);
Kinematics kinematics(const LogSpiralTrough& s, double r, double delta);
KinematicsRates kinematics_rates(const LogSpiralTrough& s, double r, double delta);
/// (11): phi = sqrt(1 + k^2) R0 [1 - exp(-k delta)] / (k r) - delta [rad].
double phi_rolling(const LogSpiralTrough& s, double r, double delta);
/// The gap of a drum centred at (x, z) [m] from A: delta by Newton's method on the condition that
/// the normal (sin delta, cos delta) at the roll curve's point passes through the centre.
TroughGap gap(const LogSpiralTrough& s, double r, double x, double z);

// ---- every shape --------------------------------------------------------------------------------

/// What a trough shape provides. A type in the variant below that misses one of these fails the
/// static_assert in src/physics/trough.cpp with this concept's name.
template <class S>
concept TroughShapeType = requires(const S& s, double r, double delta, std::string_view key) {
  { S::name } -> std::convertible_to<const char*>;
  { summary(s) } -> std::same_as<std::string>;
  { parameters(s) } -> std::same_as<std::vector<TroughParameter>>;
  { key_value(s, key) } -> std::same_as<double>;
  { curvature_radius_at_bottom(s) } -> std::same_as<double>;
  { curvature_radius_formula(s) } -> std::same_as<const char*>;
  { fit_problem(s, r) } -> std::same_as<FitProblem>;
  kinematics(s, r, delta);
  kinematics_rates(s, r, delta);
  { phi_rolling(s, r, delta) } -> std::same_as<double>;
  { gap(s, r, delta, delta) } -> std::same_as<TroughGap>;
};

/// The trough shapes. Registering a new shape is adding it here.
using TroughShape = std::variant<CircleTrough, LogSpiralTrough>;

/// The shape the case keys trough.k and trough.a describe: the circle of radius a for k = 0,
/// else the log spiral (k, a). The one place where k = 0 means a circle.
TroughShape trough_shape(double k, double a);

/// The names of every shape, in variant order ("circle", "log_spiral").
std::vector<std::string> trough_shape_names();

/// The functions above on whichever shape is held (std::visit).
const char* trough_name(const TroughShape& shape);
std::string summary(const TroughShape& shape);
std::vector<TroughParameter> parameters(const TroughShape& shape);
double key_value(const TroughShape& shape, std::string_view key);
double curvature_radius_at_bottom(const TroughShape& shape);
const char* curvature_radius_formula(const TroughShape& shape);
FitProblem fit_problem(const TroughShape& shape, double r);
/// The gap of a drum of radius r [m] centred at (x, z) [m] from the trough's point A.
TroughGap gap(const TroughShape& shape, double r, double x, double z);
/// Throws oscidrum::Error (with the key of the problem and its value) if the drum of radius r [m]
/// cannot roll in the trough.
void check_fit(const TroughShape& shape, double r);

}  // namespace oscidrum
