// Finite-difference checks of every derivative coded in src/equations/jacobian.cpp: the third
// derivatives of the roll curves, the Jacobians of the stick (52) and slip (55) right-hand sides,
// the event gradients, the jump maps at slip ends, and the saltation matrices.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "equations/jacobian.hpp"
#include "oscidrum/oscidrum.hpp"
#include "tolerances.hpp"

namespace oscidrum::detail {
namespace {

// Typical magnitude of each state component (delta, x_A, s_A, phi, delta', x_A', s_A', phi'):
// finite-difference steps and comparisons are made relative to these.
const Vec8 kScale = (Vec8() << 0.3, 1e-3, 1e-3, 1.0, 50.0, 0.2, 0.05, 50.0).finished();
constexpr double kStep = 1e-5;  // relative step of the central differences

Case trough_case(bool spiral) {
  Case c;
  if (spiral) {
    c.trough.shape = trough_shape(0.002, 0.601);  // the paper's spiral (Figs. 7, 8)
  } else {
    c.trough.shape = CircleTrough{0.606};
  }
  c.MMd = 0.05 * c.roller.M0;
  return c;
}

State random_state(std::mt19937& rng, const Model& model) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State q;
  q.delta = 0.3 * u(rng);
  q.x_A = 1e-3 * u(rng);
  q.s_A = model.initial_state().s_A * (1.0 + 0.3 * u(rng));
  q.phi = u(rng);
  q.ddelta = 50.0 * u(rng);
  q.dx_A = 0.2 * u(rng);
  q.ds_A = 0.05 * u(rng);
  q.dphi = 50.0 * u(rng);
  return q;
}

// Central-difference Jacobian of a map R^8 -> R^8 at y, column j with step kStep * kScale[j];
// `fourth_order` uses the five-point stencil (truncation O(h^4)) for strongly curved maps.
Mat8 fd_jacobian(const std::function<Vec8(const Vec8&)>& map, const Vec8& y,
                 bool fourth_order = false, const Vec8& scale = kScale) {
  Mat8 J;
  for (int j = 0; j < 8; ++j) {
    const double h = kStep * scale[j];
    auto at = [&](double dy) {
      Vec8 z = y;
      z[j] += dy;
      return map(z);
    };
    if (fourth_order) {
      J.col(j) = (8.0 * (at(h) - at(-h)) - (at(2 * h) - at(-2 * h))) / (12.0 * h);
    } else {
      J.col(j) = (at(h) - at(-h)) / (2.0 * h);
    }
  }
  return J;
}

// Compare row by row in scaled units: the error of each entry, times the scale of its column,
// relative to the row's largest scaled entry (the row's size of a unit perturbation).
void expect_jacobian_near(const Mat8& analytic, const Mat8& fd, const std::string& what,
                          const Vec8& scale = kScale) {
  for (int i = 0; i < 8; ++i) {
    double row = 0.0;
    for (int j = 0; j < 8; ++j) row = std::max(row, std::abs(fd(i, j)) * scale[j]);
    for (int j = 0; j < 8; ++j) {
      EXPECT_LE(std::abs(analytic(i, j) - fd(i, j)) * scale[j],
                test::kFiniteDifference * std::max(row, 1e-300))
          << what << ": entry (" << i << ", " << j << ") analytic " << analytic(i, j) << " fd "
          << fd(i, j);
    }
  }
}

TEST(Jacobian, ThirdDerivativesOfTheRollCurves) {
  for (bool spiral : {false, true}) {
    const Model model(trough_case(spiral));
    for (double delta : {-0.4, -0.1, 0.0, 0.05, 0.3}) {
      const double h = 1e-5;
      const Kinematics kp = kinematics(model.geometry(), delta + h);
      const Kinematics km = kinematics(model.geometry(), delta - h);
      const KinematicsRates d = kinematics_rates(model.geometry(), delta);
      const double scale = model.r();
      EXPECT_NEAR(d.df2, (kp.f2 - km.f2) / (2 * h), test::kFiniteDifference * scale);
      EXPECT_NEAR(d.df4, (kp.f4 - km.f4) / (2 * h), test::kFiniteDifference * scale);
      EXPECT_NEAR(d.df6, (kp.f6 - km.f6) / (2 * h), test::kFiniteDifference);
    }
  }
}

// The vibratory drum (docs/model.md section 14): the same equations with the unbalance force on
// M, F0 = m_u e_u nu^2 = 53 kN at 30 Hz, turning (circular) or directed (vertical).
Case vibratory_case(bool spiral, Exciter exciter) {
  Case c = trough_case(spiral);
  c.roller.type = RollerType::vibratory;
  c.roller.static_moment = 1.5;
  c.roller.f = 30.0;
  c.roller.exciter = exciter;
  return c;
}

TEST(Jacobian, StickAndSlipRightHandSidesAgainstFiniteDifferences) {
  std::mt19937 rng(20190701);
  std::vector<std::pair<std::string, Case>> cases;
  for (bool spiral : {false, true}) {
    const std::string shape = spiral ? "spiral " : "circle ";
    cases.emplace_back(shape, trough_case(spiral));
    cases.emplace_back(shape + "vibratory circular ", vibratory_case(spiral, Exciter::circular));
    cases.emplace_back(shape + "vibratory reversed ",
                       vibratory_case(spiral, Exciter::circular_reversed));
  }
  for (const auto& [name, c] : cases) {
    const Model model(c);
    const double beta = 2.0 * model.nu();
    for (int i = 0; i < 20; ++i) {
      const State q = random_state(rng, model);
      const double t = 0.0013 * i;
      for (Phase phase : {Phase::stick, Phase::slip_positive, Phase::slip_negative}) {
        for (double b : {0.0, beta}) {
          if (phase == Phase::stick && b != 0.0) continue;
          const Mat8 J = phase_jacobian(model, t, q, phase, b);
          const Mat8 fd =
              fd_jacobian([&](const Vec8& y) { return phase_rhs(model, t, to_state(y), phase, b); },
                          to_vec8(q));
          expect_jacobian_near(
              J, fd,
              name + to_string(phase) + (b != 0.0 ? " Baumgarte" : "") + " #" + std::to_string(i));
        }
      }
    }
  }
}

// The smooth phase of the regularised law (T = -mu tanh(v_rel / v_eps) N), whose Jacobian comes
// from dual numbers: at states whose v_rel is within a few v_eps (where the coefficient changes).
TEST(Jacobian, SmoothPhaseOfTheRegularisedLawAgainstFiniteDifferences) {
  std::mt19937 rng(8128);
  for (bool spiral : {false, true}) {
    for (double v_eps : {1e-3, 0.05}) {
      Case c = trough_case(spiral);
      c.contact.law = FrictionChoice::regularised;
      c.contact.v_eps = v_eps;
      const Model model(c);
      for (int i = 0; i < 20; ++i) {
        State q = random_state(rng, model);
        const double f5 = kinematics(model.geometry(), q.delta).f5;
        q.dphi = f5 * q.ddelta - std::uniform_real_distribution<double>(-3.0, 3.0)(rng) * v_eps /
                                     model.r();  // v_rel (13) within 3 v_eps
        const double t = 0.0017 * i;
        for (double b : {0.0, 2.0 * model.nu()}) {
          const Mat8 J = phase_jacobian(model, t, q, Phase::smooth, b);
          // The differences in delta' and phi' on the scale of the regularisation: with the
          // default scale (50 rad/s) a step moves v_rel by ~1e-4 m/s, a tenth of v_eps = 1e-3,
          // where tanh is far from linear; steps of 1e-3 v_eps in v_rel are smooth enough for
          // the fourth-order stencil and large enough against the round-off of delta' ~ 50.
          Vec8 scale = kScale;
          scale[4] = scale[7] = 100.0 * v_eps / model.r();
          const Mat8 fd = fd_jacobian(
              [&](const Vec8& y) { return phase_rhs(model, t, to_state(y), Phase::smooth, b); },
              to_vec8(q), true, scale);
          expect_jacobian_near(J, fd,
                               std::string(spiral ? "spiral" : "circle") + " smooth v_eps " +
                                   std::to_string(v_eps) + (b != 0.0 ? " Baumgarte" : "") + " #" +
                                   std::to_string(i),
                               scale);
        }
      }
    }
  }
}

// Every phase Jacobian of both troughs under Coulomb's law and the regularised one (its smooth
// phase, from the general slip equations by dual numbers), at `states` random states, with and
// without the Baumgarte term: check(J, phase, model).
template <class Check>
void for_each_phase_jacobian(unsigned seed, int states, double dt, const Check& check) {
  std::mt19937 rng(seed);
  for (bool spiral : {false, true}) {
    for (bool regularised : {false, true}) {
      Case c = trough_case(spiral);
      if (regularised) {
        c.contact.law = FrictionChoice::regularised;
        c.contact.v_eps = 0.05;
      }
      const Model model(c);
      for (int i = 0; i < states; ++i) {
        const State q = random_state(rng, model);
        for (Phase phase :
             {Phase::stick, Phase::slip_positive, Phase::slip_negative, Phase::smooth}) {
          if ((phase == Phase::smooth) != regularised) continue;
          for (double b : {0.0, 2.0 * model.nu()})
            check(phase_jacobian(model, dt * i, q, phase, b), phase, model);
        }
      }
    }
  }
}

TEST(Jacobian, PhiIsCyclicAndStickSlavesPhiDot) {
  // No right-hand side depends on phi (the drum's angle is cyclic); in stick none depends on phi'
  // either (phi' = f5 delta').
  for_each_phase_jacobian(3, 3, 0.01, [](const Mat8& J, Phase phase, const Model&) {
    EXPECT_EQ(J.col(3).norm(), 0.0) << to_string(phase);
    if (phase == Phase::stick) {
      EXPECT_EQ(J.col(7).norm(), 0.0);
    }
  });
}

// The rows of delta, x_A and s_A are the unit rows of their velocities in every phase (with and
// without the Baumgarte term, the regularised law's smooth phase among them).
TEST(Jacobian, KinematicRowsAreUnitRows) {
  for_each_phase_jacobian(17, 5, 0.002, [](const Mat8& J, Phase phase, const Model&) {
    for (int row = 0; row < 3; ++row) {
      Eigen::Matrix<double, 1, 8> unit = Eigen::Matrix<double, 1, 8>::Zero();
      unit[row + 4] = 1.0;
      EXPECT_EQ(J.row(row), unit) << to_string(phase) << " row " << row;
    }
  });
}

TEST(Jacobian, EventGradientsAgainstFiniteDifferences) {
  std::mt19937 rng(11);
  for (bool spiral : {false, true}) {
    const Model model(trough_case(spiral));
    for (int i = 0; i < 20; ++i) {
      const State q = random_state(rng, model);
      for (EventFunction h :
           {EventFunction::stick_limit_negative, EventFunction::stick_limit_positive,
            EventFunction::slip_velocity, EventFunction::normal_force}) {
        const Vec8 g = event_gradient(model, q, h);
        double row = 0.0;
        Vec8 fd;
        for (int j = 0; j < 8; ++j) {
          const double step = kStep * kScale[j];
          Vec8 yp = to_vec8(q), ym = yp;
          yp[j] += step;
          ym[j] -= step;
          fd[j] = (event_value(model, to_state(yp), h) - event_value(model, to_state(ym), h)) /
                  (2 * step);
          row = std::max(row, std::abs(fd[j]) * kScale[j]);
        }
        for (int j = 0; j < 8; ++j)
          EXPECT_LE(std::abs(g[j] - fd[j]) * kScale[j], test::kFiniteDifference * row)
              << "event " << static_cast<int>(h) << " component " << j;
      }
    }
  }
}

TEST(Jacobian, JumpMapsAgainstFiniteDifferences) {
  std::mt19937 rng(5);
  for (bool spiral : {false, true}) {
    const Model model(trough_case(spiral));
    for (int i = 0; i < 20; ++i) {
      const State q = random_state(rng, model);
      for (bool reset_phi : {false, true}) {
        for (int coupling : {-1, 0, 1}) {
          const Mat8 G = jump_jacobian(model, q, reset_phi, coupling);
          const Mat8 fd = fd_jacobian(
              [&](const Vec8& y) {
                return to_vec8(jump_map(model, to_state(y), reset_phi, coupling));
              },
              to_vec8(q));
          expect_jacobian_near(G, fd,
                               "jump reset_phi " + std::to_string(reset_phi) + " coupling " +
                                   std::to_string(coupling));
        }
      }
      // The coupling jump makes (39) hold with its sign.
      for (int s_new : {-1, 1}) {
        const State qr = jump_map(model, q, true, s_new);
        EXPECT_NEAR(slip_constraint_residual(model, qr, s_new) / model.W(), 0.0,
                    test::kIdentity * 1e2);
      }
    }
  }
}

// Put q on the switching surface of `h` by moving the component `j` (h is affine in it).
State onto_surface(const Model& model, State q, EventFunction h, int j) {
  Vec8 y = to_vec8(q);
  for (int it = 0; it < 3; ++it) {
    const double value = event_value(model, to_state(y), h);
    y[j] -= value / event_gradient(model, to_state(y), h)[j];
  }
  return to_state(y);
}

// The saltation matrix is the derivative of the switch map with the flows frozen to their
// vector fields at the switching point q: from y, move along f-(q) for the time tau(y) at which
// h vanishes, apply the jump map g, move back along f+(g(q)) for tau(y). The result, to first
// order in y - q, is the state at the switching instant of q continued by S (y - q). The map is
// strongly curved where the crossing is slow (tau ~ 1/(dh . f-)), hence the five-point stencil.
Vec8 frozen_switch_map(const Model& model, double t, const State& q, Phase from, Phase to,
                       EventFunction h, bool jumped, const Vec8& y) {
  const double beta = 2.0 * model.nu();
  const Vec8 fm = phase_rhs(model, t, q, from, beta);
  const bool reset_phi = from != Phase::stick;
  const int coupling = (jumped && to != Phase::stick) ? static_cast<int>(to) : 0;
  const State gq = jump_map(model, q, reset_phi, coupling);
  const Vec8 fp = phase_rhs(model, t, gq, to, beta);
  double tau = 0.0;  // Newton on h(y + tau f-) = 0
  for (int it = 0; it < 30; ++it) {
    const State z = to_state(y + tau * fm);
    tau -= event_value(model, z, h) / event_gradient(model, z, h).dot(fm);
  }
  const State z = to_state(y + tau * fm);
  const Vec8 after = to_vec8(jump_map(model, z, reset_phi, coupling));
  return after - tau * fp;
}

TEST(Jacobian, SaltationMatricesAreTheDerivativeOfTheSwitch) {
  std::mt19937 rng(17);
  struct Switch {
    Phase from, to;
    EventFunction h;
    int moved;    // the component moved to put the state on the surface
    bool jumped;  // the soil's velocities jump (reversal; slip start with mu_static > mu)
  };
  const Switch switches[] = {
      {Phase::stick, Phase::slip_negative, EventFunction::stick_limit_negative, 5, false},
      {Phase::stick, Phase::slip_positive, EventFunction::stick_limit_positive, 5, false},
      {Phase::stick, Phase::slip_negative, EventFunction::stick_limit_negative, 5, true},
      {Phase::stick, Phase::slip_positive, EventFunction::stick_limit_positive, 5, true},
      {Phase::slip_positive, Phase::stick, EventFunction::slip_velocity, 7, false},
      {Phase::slip_negative, Phase::stick, EventFunction::slip_velocity, 7, false},
      {Phase::slip_positive, Phase::slip_negative, EventFunction::slip_velocity, 7, true},
      {Phase::slip_negative, Phase::slip_positive, EventFunction::slip_velocity, 7, true},
  };
  for (bool spiral : {false, true}) {
    for (double mu_static : {-1.0, 0.6}) {
      Case c = trough_case(spiral);
      c.contact.mu_static = mu_static;  // 0.6: static above the kinetic 0.5
      const Model model(c);
      const double beta = 2.0 * model.nu();
      for (int i = 0; i < 10; ++i) {
        const double t = 0.002 * i;
        for (const Switch& sw : switches) {
          if (sw.from == Phase::stick && sw.jumped && mu_static < 0.0) continue;
          // Near grazing (the flow almost tangent to the surface) the switch map curves on the
          // scale of any finite-difference step; keep crossings that are transversal in scaled
          // units (grazing itself is reported, see GrazingIsDetected).
          State q;
          for (;;) {
            q = onto_surface(model, random_state(rng, model), sw.h, sw.moved);
            const Vec8 dh = event_gradient(model, q, sw.h);
            const Vec8 fm = phase_rhs(model, t, q, sw.from, beta);
            const double cosine = std::abs(dh.dot(fm)) / (dh.cwiseProduct(kScale).norm() *
                                                          fm.cwiseQuotient(kScale).norm());
            if (cosine > 2e-3) break;
          }
          const Saltation S = switch_saltation(model, t, q, sw.from, sw.to, beta, sw.jumped);
          ASSERT_FALSE(S.grazing);
          const Mat8 fd = fd_jacobian(
              [&](const Vec8& y) {
                return frozen_switch_map(model, t, q, sw.from, sw.to, sw.h, sw.jumped, y);
              },
              to_vec8(q), true);
          const std::string what = std::string(to_string(sw.from)) + " -> " + to_string(sw.to) +
                                   (sw.jumped ? " with jump" : "");
          expect_jacobian_near(S.S, fd, what);
          // S maps the flow direction before the switch to the one after it (G f- + ... = f+).
          const Vec8 fm = phase_rhs(model, t, q, sw.from, beta);
          const int coupling = sw.jumped ? static_cast<int>(sw.to) : 0;
          const State gq = jump_map(model, q, sw.from != Phase::stick, coupling);
          const Vec8 fp = phase_rhs(model, t, gq, sw.to, beta);
          EXPECT_LE((S.S * fm - fp).norm(), 1e-9 * fp.norm()) << what;
        }
      }
    }
  }
}

TEST(Jacobian, GrazingIsDetected) {
  // A flow tangent to the surface (dh . f- = 0) has no saltation matrix.
  Vec8 dh = Vec8::Zero(), fm = Vec8::Zero();
  dh[0] = 1.0;
  fm[1] = 1.0;
  EXPECT_TRUE(saltation(Mat8::Identity(), fm, fm, dh).grazing);
  fm[0] = 1.0;
  EXPECT_FALSE(saltation(Mat8::Identity(), fm, fm, dh).grazing);
}

}  // namespace
}  // namespace oscidrum::detail
