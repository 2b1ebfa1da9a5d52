// Checks of the drum with unilateral contact shared by its tests and the vibratory drum's (tests
// only): the finite-difference check of a 10 x 10 Jacobian, and the energy of one steady period.
//
// The energy of one steady period, for the energy-balance checks of the oscillation drum with
// flight (test_unilateral_drum.cpp) and of the vibratory drum (test_vibratory_drum.cpp): the work
// of the excitation against what the buffers' and the soil's dashpots dissipate and what friction
// does in slip, integrated on the flow's dense output by 8-point Gauss-Legendre quadrature on every
// piece. The drum centre's velocity is the chart's, M' = A' + (r f5 - g) delta' t - g' n
// (docs/model.md section 13; in contact g = g' = 0: (17)); landing on massless soil costs no
// energy.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "oscidrum/oscidrum.hpp"
#include "roller/unilateral_drum.hpp"

namespace oscidrum::detail {

/// Central differences of a map R^10 -> R^10 (the unilateral drum's state), compared with J row
/// by row in scaled units: each entry to 1e-6 of its row's largest scaled derivative.
template <class F>
void expect_jacobian(const Dynamics<UnilateralDrum>::Matrix& J,
                     const Dynamics<UnilateralDrum>::Vector& y, F&& map, const std::string& what) {
  using U = Dynamics<UnilateralDrum>;
  const std::array<double, 10> scale = {0.3, 1e-3, 1e-3, 1.0, 1e-4, 40.0, 0.1, 0.05, 40.0, 0.1};
  U::Matrix fd;
  for (int j = 0; j < 10; ++j) {
    const double h = 1e-6 * scale[j];
    U::Vector a = y, b = y;
    a[j] += h;
    b[j] -= h;
    const U::Vector fa = map(a), fb = map(b);
    for (int i = 0; i < 10; ++i) fd(i, j) = (fa[i] - fb[i]) / (2 * h);
  }
  for (int i = 0; i < 10; ++i) {
    double row = 0.0;
    for (int j = 0; j < 10; ++j) row = std::max(row, std::abs(fd(i, j)) * scale[j]);
    for (int j = 0; j < 10; ++j)
      EXPECT_LE(std::abs(J(i, j) - fd(i, j)) * scale[j], 1e-6 * std::max(row, 1e-300))
          << what << " (" << i << ", " << j << "): " << J(i, j) << " against " << fd(i, j);
  }
}

struct PeriodEnergy {
  bool reached = false;     ///< the period was integrated to its end
  double in = 0.0;          ///< the excitation's work [J]
  double out = 0.0;         ///< dissipated by the dashpots and by friction [J]
  double friction = 0.0;    ///< of `out`: friction's work in slip, |T v_rel| (13), (27) [J]
  double flight_out = 0.0;  ///< of `out`: dissipated in flight (the soil relaxing) [J]
};

/// The energy of the steady period that starts at r's first sample. The excitation's power is
/// F . M' + MM(t) phi' with F the centre load less the static W (zero for the oscillation drum,
/// whose W does no net work over a period; the vibratory drum's unbalance force) and MM(t) the
/// torque (5), (6) (in stick phi' = f5 delta' (12): the flow integrates phi' there without
/// reading it).
inline PeriodEnergy energy_over_period(const Model& model, const Result& r) {
  using U = Dynamics<UnilateralDrum>;
  struct Energy : BasicFlowObserver<UnilateralDrum> {
    const Model& model;
    PeriodEnergy e;
    explicit Energy(const Model& m) : model(m) {}
    bool on_step(const BasicStepView<UnilateralDrum>& s) override {
      static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                      0.9602898564975363};
      static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                      0.1012285362903763};
      const double h = 0.5 * (s.t1() - s.t0()), mid = 0.5 * (s.t1() + s.t0());
      for (int i = 0; i < 4; ++i) {
        for (double sign : {-1.0, 1.0}) {
          const double t = mid + sign * h * x[i];
          const UnilateralState q = s.state(t);
          const Kinematics k = kinematics(model.geometry(), q.delta);
          const double rho = model.r() * k.f5 - q.gap;
          const double dx_M = q.dx_A + rho * q.ddelta * k.cos_delta - q.dgap * k.sin_delta;
          const double dz_M = q.ds_A - rho * q.ddelta * k.sin_delta - q.dgap * k.cos_delta;
          const CentreLoad L = model.centre_load(t);
          const double dphi = s.phase() == Phase::stick ? k.f5 * q.ddelta : q.dphi;
          const double p_in = L.x * dx_M + (L.z - model.W()) * dz_M + model.torque(t) * dphi;
          double p_friction = 0.0;
          if (s.phase() == Phase::slip_positive || s.phase() == Phase::slip_negative) {
            const ContactForces f = contact_forces(model, q.contact());
            p_friction = std::abs(f.T * slip_velocity(model, q.contact()));
          }
          const double p_out = model.cd() * (dx_M * dx_M + dz_M * dz_M) +
                               model.csh() * q.dx_A * q.dx_A + model.csv() * q.ds_A * q.ds_A +
                               p_friction;
          e.in += w[i] * h * p_in;
          e.out += w[i] * h * p_out;
          e.friction += w[i] * h * p_friction;
          if (s.phase() == Phase::flight) e.flight_out += w[i] * h * p_out;
        }
      }
      return true;
    }
  } energy(model);
  const FlowOptions options = FlowOptions::from(model);
  const U u(model, options.baumgarte);
  const double t0 = r.samples.t.front(), t1 = t0 + model.period();
  const Phase phase = u.flow_phase(r.samples.phase.front());
  UnilateralFlow flow(model, options);
  flow.reset(t0, UnilateralState::from_array(u.consistent(U::sampled_state(r.samples, 0), phase)),
             phase);
  energy.e.reached = flow.advance(t1, &energy) == FlowStop::reached;
  return energy.e;
}

}  // namespace oscidrum::detail
