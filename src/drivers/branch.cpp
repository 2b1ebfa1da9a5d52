// Branches of periodic orbits (docs/bifurcations.md): the checks of the options and the run on
// the roller the case describes. The continuation itself is src/drivers/branch_continuation.hpp.
#include "oscidrum/branch.hpp"

#include <functional>
#include <string>
#include <utility>

#include "drivers/branch_continuation.hpp"
#include "drivers/varied_parameter.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "roller/rollers.hpp"
#include "util/format.hpp"

namespace oscidrum {

Branch continue_branch(const Case& c, const BranchOptions& o) {
  const Field* field = &detail::varied_field(c, o.key, o.from, o.to, "continue", o.MMd_fraction);
  if (!(o.from != o.to))
    throw Error("continue: the range's start and end (from and to, --from and --to) must differ",
                o.key, o.to);
  // The branch moves G continuously; Table 2 holds 14 values of it.
  if (o.key == "soil.G" && c.soil.input == SoilInput::table2)
    throw Error(
        "continue: soil.G varies continuously along a branch, but soil.input = \"table2\" holds "
        "only the G of paper Table 2 (5e6, 10e6, ..., 70e6 Pa); set soil.input = \"modulus\" "
        "(Appendix B, --set soil.input=modulus)",
        "soil.G");
  if (!(o.initial_step > 0 && o.max_step >= o.initial_step && o.min_step > 0 &&
        o.min_step <= o.initial_step && o.max_step <= 1))
    throw Error(
        "continue: the arclength steps must satisfy 0 < min_step <= initial_step (--step) "
        "<= max_step (--max-step) <= 1; got min_step " +
        detail::shortest(o.min_step) + ", initial_step " + detail::shortest(o.initial_step) +
        ", max_step " + detail::shortest(o.max_step) +
        (o.initial_step > o.max_step && o.max_step <= 1
             ? " (a --step above --max-step needs a --max-step at least as large)"
             : ""));
  if (!(o.tolerance > 0 && o.tolerance < 1))
    throw Error("continue: tolerance (--tolerance) must be in (0, 1); got " +
                detail::shortest(o.tolerance));
  if (o.max_points < 2)
    throw Error(
        "continue: max_points (--max-points) must be >= 2; got " + std::to_string(o.max_points),
        "max_points");
  // As the CLI's --switch-depth: a cascade of period doublings followed to period 2^5 at most
  // (each level a branch of its own; an unbounded depth could follow it to period 2^99).
  if (o.switch_depth < 0 || o.switch_depth > 5)
    throw Error("continue: switch_depth must be in [0, 5]; got " + std::to_string(o.switch_depth),
                "switch_depth", o.switch_depth);
  // The metrics' harmonics within what the samples resolve (else every point's metrics were
  // unavailable without a word: compute_metrics refuses them).
  if (o.metrics && (o.harmonics < 0 || o.harmonics >= c.numerics.samples_per_period / 2))
    throw Error("continue: harmonics must be in [0, numerics.samples_per_period / 2 = " +
                    std::to_string(c.numerics.samples_per_period / 2) +
                    "), the samples' Nyquist limit; got " + std::to_string(o.harmonics),
                "harmonics", o.harmonics);
  const Model model(c);  // validates the case
  detail::check_range_interior(c, *field, o.from, o.to, "continue", o.MMd_fraction);
  return detail::with_roller(model, [&]<class R>() {
    detail::branching::Continuation<R> primary(c, o, *field);
    Branch branch = primary.run();
    // Branch switching at each period doubling onto the period-2p branch, and onward from
    // those (o.switch_depth levels); a branch's own children are grown before it is stored.
    std::function<void(Branch&, const detail::branching::Continuation<R>&, int)> grow =
        [&](Branch& parent, const detail::branching::Continuation<R>& from, int depth) {
          if (depth > o.switch_depth) return;
          for (const auto& d : from.doublings()) {
            if (o.cancelled && o.cancelled()) return;
            detail::branching::Continuation<R> child(c, o, *field);
            child.set_multiplicity(parent.multiplicity);
            Branch b = child.switch_at(d, from.scale());
            grow(b, child, depth + 1);
            parent.bifurcations[static_cast<std::size_t>(d.index)].child =
                static_cast<int>(parent.children.size());
            parent.children.push_back(std::move(b));
          }
          // A period-p branch that shrank onto its period-p/2 orbit: that orbit's branch on
          // towards `to` (the range the user asked for).
          if (const auto& h = from.halving()) {
            if (o.cancelled && o.cancelled()) return;
            detail::branching::Continuation<R> child(c, o, *field);
            child.set_multiplicity(parent.multiplicity);
            Branch b = child.halve_at(*h, from.scale());
            grow(b, child, depth + 1);
            parent.bifurcations[static_cast<std::size_t>(h->index)].child =
                static_cast<int>(parent.children.size());
            parent.children.push_back(std::move(b));
          }
        };
    grow(branch, primary, 1);
    return branch;
  });
}

}  // namespace oscidrum
