// The trough shape as a component (oscidrum/trough.hpp): the functions on a TroughShape, each a
// std::visit over the shapes, and the case keys' meaning. Each shape's own functions are in its
// file, src/physics/trough_<name>.cpp.
#include "oscidrum/trough.hpp"

#include <variant>

#include "oscidrum/error.hpp"
#include "oscidrum/kinematics.hpp"

namespace oscidrum {
namespace {

// Every shape of the variant provides every function of a shape.
template <class Variant>
struct AllShapes;
template <class... S>
struct AllShapes<std::variant<S...>> {
  static constexpr bool value = (TroughShapeType<S> && ...);
};
static_assert(
    AllShapes<TroughShape>::value,
    "every alternative of TroughShape must satisfy TroughShapeType (oscidrum/trough.hpp)");

template <class... S>
std::vector<std::string> names_of(std::variant<S...>*) {
  return {S::name...};
}

}  // namespace

TroughShape trough_shape(double k, double a) {
  if (k == 0.0) return CircleTrough{a};
  return LogSpiralTrough(k, a);
}

std::vector<std::string> trough_shape_names() {
  return names_of(static_cast<TroughShape*>(nullptr));
}

const char* trough_name(const TroughShape& shape) {
  return std::visit([](const auto& s) -> const char* { return s.name; }, shape);
}

std::string summary(const TroughShape& shape) {
  return std::visit([](const auto& s) { return summary(s); }, shape);
}

std::vector<TroughParameter> parameters(const TroughShape& shape) {
  return std::visit([](const auto& s) { return parameters(s); }, shape);
}

double key_value(const TroughShape& shape, std::string_view key) {
  return std::visit([key](const auto& s) { return key_value(s, key); }, shape);
}

double curvature_radius_at_bottom(const TroughShape& shape) {
  return std::visit([](const auto& s) { return curvature_radius_at_bottom(s); }, shape);
}

const char* curvature_radius_formula(const TroughShape& shape) {
  return std::visit([](const auto& s) { return curvature_radius_formula(s); }, shape);
}

FitProblem fit_problem(const TroughShape& shape, double r) {
  return std::visit([r](const auto& s) { return fit_problem(s, r); }, shape);
}

TroughGap gap(const TroughShape& shape, double r, double x, double z) {
  return std::visit([=](const auto& s) { return gap(s, r, x, z); }, shape);
}

void check_fit(const TroughShape& shape, double r) {
  const FitProblem p = fit_problem(shape, r);
  if (!p.message.empty()) throw Error(p.message, p.key, key_value(shape, p.key));
}

}  // namespace oscidrum
