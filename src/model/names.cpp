// Names of the enumerations, used in CSV, JSON and messages.
#include "oscidrum/branch.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum {

const char* to_string(Phase phase) {
  switch (phase) {
    case Phase::stick:
      return "stick";
    case Phase::slip_positive:
      return "slip+";
    case Phase::slip_negative:
      return "slip-";
    case Phase::flight:
      return "flight";
    case Phase::smooth:
      return "smooth";
  }
  return "?";
}

const char* to_string(Status status) {
  switch (status) {
#define OSCIDRUM_CASE(name, description) \
  case Status::name:                     \
    return #name;
    OSCIDRUM_STATUSES(OSCIDRUM_CASE)
#undef OSCIDRUM_CASE
  }
  return "?";
}

const char* to_string(SteadyMethod method) {
  return method == SteadyMethod::shooting ? "shooting" : "transient";
}

const char* to_string(EventKind kind) {
  switch (kind) {
    case EventKind::stick_to_slip:
      return "stick_to_slip";
    case EventKind::slip_to_stick:
      return "slip_to_stick";
    case EventKind::slip_reversal:
      return "slip_reversal";
    case EventKind::contact_lost:
      return "contact_lost";
    case EventKind::lift_off:
      return "lift_off";
    case EventKind::landing:
      return "landing";
  }
  return "?";
}

const char* to_string(FlowStop stop) {
  switch (stop) {
    case FlowStop::reached:
      return "reached";
    case FlowStop::observer:
      return "observer";
    case FlowStop::contact_lost:
      return "contact_lost";
    case FlowStop::chattering:
      return "chattering";
    case FlowStop::non_finite:
      return "non_finite";
    case FlowStop::invalid_geometry:
      return "invalid_geometry";
    case FlowStop::budget_exceeded:
      return "budget_exceeded";
    case FlowStop::cancelled:
      return "cancelled";
    case FlowStop::inconsistent_state:
      return "inconsistent_state";
  }
  return "?";
}

const char* to_string(BifurcationKind kind) {
  switch (kind) {
    case BifurcationKind::fold:
      return "fold";
    case BifurcationKind::branch_point:
      return "branch_point";
    case BifurcationKind::period_doubling:
      return "period_doubling";
    case BifurcationKind::neimark_sacker:
      return "neimark_sacker";
    case BifurcationKind::grazing:
      return "grazing";
    case BifurcationKind::lift_off:
      return "lift_off";
  }
  return "?";
}

const char* to_string(BranchEnd end) {
  switch (end) {
    case BranchEnd::reached_end:
      return "reached_end";
    case BranchEnd::left_range:
      return "left_range";
    case BranchEnd::max_points:
      return "max_points";
    case BranchEnd::step_too_small:
      return "step_too_small";
    case BranchEnd::gross_slip:
      return "gross_slip";
    case BranchEnd::start_failed:
      return "start_failed";
    case BranchEnd::cancelled:
      return "cancelled";
    case BranchEnd::lift_off:
      return "lift_off";
    case BranchEnd::period_halved:
      return "period_halved";
  }
  return "?";
}

}  // namespace oscidrum
