// Tests of the equations of motion (docs/model.md sections 3-5): the accelerations returned by
// stick_accelerations (30)-(32) and slip_accelerations (34), (36), (38), (53) are checked against
// the balance equations (19), (20), (23) and the soil equations (24)-(26) they were derived from,
// against an independent Eigen solve of those balance equations, and for equilibrium, mirror
// symmetry and the frictionless limit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "equations/equations.hpp"
#include "equations/slip_general.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/state.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

using test::kBalanceResidual;
using test::kIdentity;
using test::kIndependentSolve;
using test::kSymmetry;

constexpr int kSamples = 200;  // random states per configuration and phase

struct Config {
  const char* name;
  double k, a;
  bool from_static;
};
// The paper's base circle and its spiral (trough-shape study), each with the suspension
// measured as in the paper (from t = 0) and from static equilibrium.
const std::vector<Config> kConfigs = {
    {"circle R = 0.606", 0.0, 0.606, false},
    {"circle R = 0.606, from static", 0.0, 0.606, true},
    {"spiral k = 0.002 a = 0.601", 0.002, 0.601, false},
    {"spiral k = 0.002 a = 0.601, from static", 0.002, 0.601, true}};

Model make_model(const Config& cfg, double MMd_over_M0 = 0.05, double mu = 0.5) {
  Case c;
  c.trough.shape = trough_shape(cfg.k, cfg.a);
  c.numerics.suspension_from_static = cfg.from_static;
  c.MMd = MMd_over_M0 * c.roller.M0;
  c.contact.mu = mu;
  return Model(c);
}

// ---- independent pieces, written here from the paper --------------------------------------------

// Slip friction factors (35).
struct FrictionFactors {
  double fmu1, fmu2;
};
FrictionFactors friction_factors(const Model& model, double delta, int s) {
  const double smu = s * model.cone();
  return {std::cos(delta) - smu * std::sin(delta), std::sin(delta) + smu * std::cos(delta)};
}

// Soil forces Fh = ksh x_A + csh x_A', Fv = ksv s_A + csv s_A' (right-hand sides of (24), (25)).
struct SoilForces {
  double Fh, Fv;
};
SoilForces soil_forces(const Model& model, const State& q) {
  return {model.ksh() * q.x_A + model.csh() * q.dx_A, model.ksv() * q.s_A + model.csv() * q.ds_A};
}

// N and T from the soil: (24) N sin - T cos = Fh, (25) N cos + T sin = Fv, solved numerically.
struct ForcePair {
  double N, T;
};
ForcePair soil_contact(const Model& model, const State& q) {
  const SoilForces F = soil_forces(model, q);
  Eigen::Matrix2d A;
  A << std::sin(q.delta), -std::cos(q.delta), std::cos(q.delta), std::sin(q.delta);
  const Eigen::Vector2d x = A.fullPivLu().solve(Eigen::Vector2d(F.Fh, F.Fv));
  return {x(0), x(1)};
}

// Slip coupling (39): fmu1 Fh - fmu2 Fv.
double coupling(const Model& model, const State& q, int s) {
  const FrictionFactors f = friction_factors(model, q.delta, s);
  const SoilForces F = soil_forces(model, q);
  return f.fmu1 * F.Fh - f.fmu2 * F.Fv;
}

// d/dt of (39), with fmu1' = -fmu2 delta', fmu2' = fmu1 delta' (35) and the given accelerations.
double coupling_rate(const Model& model, const State& q, const Accelerations& a, int s) {
  const FrictionFactors f = friction_factors(model, q.delta, s);
  const SoilForces F = soil_forces(model, q);
  const double dFh = model.csh() * a.x_A + model.ksh() * q.dx_A;
  const double dFv = model.csv() * a.s_A + model.ksv() * q.ds_A;
  return -f.fmu2 * q.ddelta * F.Fh + f.fmu1 * dFh - f.fmu1 * q.ddelta * F.Fv - f.fmu2 * dFv;
}

// Drum centre (14), (17), (18).
struct Centre {
  double x, z, dx, dz, ddx, ddz;
};
Centre centre(const Model& model, const State& q, const Accelerations& a) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const double d2 = q.ddelta * q.ddelta;
  return {k.x_roll + q.x_A,
          k.z_roll + q.s_A,
          k.f1 * q.ddelta + q.dx_A,
          k.f3 * q.ddelta + q.ds_A,
          k.f1 * a.delta + k.f2 * d2 + a.x_A,
          k.f3 * a.delta + k.f4 * d2 + a.s_A};
}

// Residuals of the drum's balance equations with the contact forces N, T:
// (19) T cos - N sin - cd xM' - kd xM - m xM'' = 0,
// (20) W - T sin - N cos - cd zM' - kd (zM - z_ref) - m zM'' = 0,
// (23) I phi'' - MM(t) + T r = 0.
struct Residuals {
  double horizontal, vertical, angular;
};
Residuals balance(const Model& model, double t, const State& q, const Accelerations& a,
                  ForcePair F) {
  const Centre M = centre(model, q, a);
  const double sn = std::sin(q.delta), cs = std::cos(q.delta);
  return {F.T * cs - F.N * sn - model.cd() * M.dx - model.kd() * M.x - model.m() * M.ddx,
          model.W() - F.T * sn - F.N * cs - model.cd() * M.dz - model.kd() * (M.z - model.z_ref()) -
              model.m() * M.ddz,
          model.I() * a.phi - model.torque(t) + F.T * model.r()};
}

// N and T from the drum side, (21) and (22).
ForcePair drum_contact(const Model& model, const State& q, const Accelerations& a) {
  const Centre M = centre(model, q, a);
  const double sn = std::sin(q.delta), cs = std::cos(q.delta);
  const double V =
      model.W() - (model.m() * M.ddz + model.cd() * M.dz + model.kd() * (M.z - model.z_ref()));
  const double H = model.m() * M.ddx + model.cd() * M.dx + model.kd() * M.x;
  return {V * cs - H * sn, V * sn + H * cs};
}

void expect_balanced(const Model& model, double t, const State& q, const Accelerations& a,
                     ForcePair F, const std::string& where) {
  const Residuals r = balance(model, t, q, a, F);
  const double W = model.W();
  EXPECT_LE(std::abs(r.horizontal), kBalanceResidual * W) << "(19) " << where;
  EXPECT_LE(std::abs(r.vertical), kBalanceResidual * W) << "(20) " << where;
  EXPECT_LE(std::abs(r.angular), kBalanceResidual * W * model.r()) << "(23) " << where;
}

// Natural acceleration scales, used as floors when comparing accelerations that may be small:
// the load W accelerates the drum mass at W/m; the drum's position angle moves by 1 / (r f5(0))
// per metre of the centre; the torque W r turns the drum at W r / I.
Accelerations scales(const Model& model) {
  const double f5 = kinematics(model.geometry(), 0.0).f5;
  const double lin = model.W() / model.m();
  return {lin / (model.r() * f5), lin, lin, model.W() * model.r() / model.I()};
}

void expect_same_accelerations(const Accelerations& got, const Accelerations& want,
                               const Accelerations& scale, double tol, const std::string& where) {
  auto bound = [&](double w, double s) { return tol * std::max(std::abs(w), s); };
  EXPECT_NEAR(got.delta, want.delta, bound(want.delta, scale.delta)) << "delta'' " << where;
  EXPECT_NEAR(got.x_A, want.x_A, bound(want.x_A, scale.x_A)) << "x_A'' " << where;
  EXPECT_NEAR(got.s_A, want.s_A, bound(want.s_A, scale.s_A)) << "s_A'' " << where;
  EXPECT_NEAR(got.phi, want.phi, bound(want.phi, scale.phi)) << "phi'' " << where;
}

// ---- random states ------------------------------------------------------------------------------

struct Sample {
  double t;
  State q;
};

// A state of realistic size (docs/model.md section 4 and 5 magnitudes at f = 39 Hz): delta in
// [-0.3, 0.3], x_A and s_A ~ 1e-3 m, delta' ~ 50 rad/s, x_A' ~ 0.2 m/s, s_A' ~ 0.05 m/s. In stick
// phi' = f5 delta' (12); in slip phi' = f5 delta' - s u with u in (0, 0.5] rad/s so that
// sign(v_rel) = s (13). With `on_cone`, x_A' is chosen so that the slip coupling (39) holds,
// i.e. |T| = mu N with T = -s mu N (the state of a slip phase, or a stick state at the cone).
Sample random_sample(std::mt19937& rng, const Model& model, int s, bool on_cone) {
  auto U = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  Sample p;
  p.t = U(0.0, 1.0);
  State& q = p.q;
  q.delta = U(-0.3, 0.3);
  q.x_A = U(-1e-3, 1e-3);
  q.s_A = U(0.2e-3, 1.5e-3);
  q.phi = U(-2.0, 2.0);
  q.ddelta = U(-50.0, 50.0);
  q.dx_A = U(-0.2, 0.2);
  q.ds_A = U(-0.05, 0.05);
  const double f5 = kinematics(model.geometry(), q.delta).f5;
  q.dphi = f5 * q.ddelta - s * U(0.01, 0.5);
  if (on_cone) {
    const FrictionFactors f = friction_factors(model, q.delta, s == 0 ? 1 : s);
    const double Fv = model.ksv() * q.s_A + model.csv() * q.ds_A;
    q.dx_A = (f.fmu2 * Fv / f.fmu1 - model.ksh() * q.x_A) / model.csh();  // (39)
  }
  return p;
}

std::string describe(const Config& cfg, int s, const Sample& p) {
  return std::string(cfg.name) +
         (s == 0  ? ", stick"
          : s > 0 ? ", slip+"
                  : ", slip-") +
         ", t = " + std::to_string(p.t) + ", delta = " + std::to_string(p.q.delta);
}

// ---- the stick phase ----------------------------------------------------------------------------

// The accelerations of (30)-(32) satisfy the drum's balances (19), (20), (23) with N and T from
// the soil (24)-(25), and the rolling condition (12).
TEST(StickPhase, SatisfiesTheBalanceEquations) {
  std::mt19937 rng(20190901);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int i = 0; i < kSamples; ++i) {
      const Sample p = random_sample(rng, model, 0, false);
      const std::string where = describe(cfg, 0, p);
      const Accelerations a = stick_accelerations(model, p.t, p.q);
      const ContactForces lib = contact_forces(model, p.q);
      const ForcePair soil = soil_contact(model, p.q);
      EXPECT_NEAR(lib.N, soil.N, kIdentity * model.W()) << where;
      EXPECT_NEAR(lib.T, soil.T, kIdentity * model.W()) << where;
      expect_balanced(model, p.t, p.q, a, soil, where);
      const Kinematics k = kinematics(model.geometry(), p.q.delta);
      const double phi = k.f5 * a.delta + k.f6 * p.q.ddelta * p.q.ddelta;  // (12)
      EXPECT_NEAR(a.phi, phi, kIdentity * std::max(std::abs(phi), scales(model).phi)) << where;
    }
  }
}

// The soil is massless, so in stick N and T from the drum's accelerations (21)-(22) equal N and
// T from the soil (26) and its companion.
TEST(StickPhase, DrumAndSoilGiveTheSameContactForces) {
  std::mt19937 rng(7);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int i = 0; i < kSamples; ++i) {
      const Sample p = random_sample(rng, model, 0, false);
      const Accelerations a = stick_accelerations(model, p.t, p.q);
      const ForcePair drum = drum_contact(model, p.q, a);
      const ContactForces soil = contact_forces(model, p.q);
      EXPECT_NEAR(drum.N, soil.N, kBalanceResidual * model.W()) << describe(cfg, 0, p);
      EXPECT_NEAR(drum.T, soil.T, kBalanceResidual * model.W()) << describe(cfg, 0, p);
    }
  }
}

// drum_motion is (14), (17), (18).
TEST(StickPhase, DrumMotionIsTheCentreKinematics) {
  std::mt19937 rng(11);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int i = 0; i < 20; ++i) {
      const Sample p = random_sample(rng, model, 0, false);
      const Accelerations a = stick_accelerations(model, p.t, p.q);
      const DrumMotion d = drum_motion(model, p.q, a);
      const Centre c = centre(model, p.q, a);
      EXPECT_NEAR(d.x_M, c.x, kIdentity * model.r());
      EXPECT_NEAR(d.z_M, c.z, kIdentity * model.r());
      EXPECT_NEAR(d.dx_M, c.dx, kIdentity * std::max(1.0, std::abs(c.dx)));
      EXPECT_NEAR(d.dz_M, c.dz, kIdentity * std::max(1.0, std::abs(c.dz)));
      EXPECT_NEAR(d.ddx_M, c.ddx, kIdentity * std::max(1.0, std::abs(c.ddx)));
      EXPECT_NEAR(d.ddz_M, c.ddz, kIdentity * std::max(1.0, std::abs(c.ddz)));
    }
  }
}

// Rows 0-2 of the independent solves: the drum's balance equations (19), (20), (23) in the
// unknowns (delta'', x_A'', s_A'', phi'', N, T), the same in stick and slip.
void drum_rows(const Model& model, double t, const State& q, const Kinematics& k,
               Eigen::Matrix<double, 6, 6>& A, Eigen::Matrix<double, 6, 1>& b) {
  const double sn = std::sin(q.delta), cs = std::cos(q.delta), d2 = q.ddelta * q.ddelta;
  const double m = model.m(), cd = model.cd(), kd = model.kd();
  const double xM = k.x_roll + q.x_A, zM = k.z_roll + q.s_A - model.z_ref();
  const double dxM = k.f1 * q.ddelta + q.dx_A, dzM = k.f3 * q.ddelta + q.ds_A;
  // (19): T cos - N sin - m (f1 delta'' + x_A'') = cd xM' + kd xM + m f2 delta'^2
  A(0, 0) = -m * k.f1;
  A(0, 1) = -m;
  A(0, 4) = -sn;
  A(0, 5) = cs;
  b(0) = cd * dxM + kd * xM + m * k.f2 * d2;
  // (20): -T sin - N cos - m (f3 delta'' + s_A'') = -W + cd zM' + kd (zM - z_ref) + m f4 delta'^2
  A(1, 0) = -m * k.f3;
  A(1, 2) = -m;
  A(1, 4) = -cs;
  A(1, 5) = -sn;
  b(1) = -model.W() + cd * dzM + kd * zM + m * k.f4 * d2;
  // (23): I phi'' + r T = MM(t)
  A(2, 3) = model.I();
  A(2, 5) = model.r();
  b(2) = model.torque(t);
}

// Independent solve of the stick phase: unknowns (delta'', x_A'', s_A'', phi'', N, T) from
// (19), (20), (23), (24), (25) and the rolling condition (12), by full-pivot LU.
Accelerations solve_stick(const Model& model, double t, const State& q, ForcePair* forces) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const double sn = std::sin(q.delta), cs = std::cos(q.delta), d2 = q.ddelta * q.ddelta;
  const SoilForces F = soil_forces(model, q);
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b;
  drum_rows(model, t, q, k, A, b);
  // (24), (25): the massless soil
  A(3, 4) = sn;
  A(3, 5) = -cs;
  b(3) = F.Fh;
  A(4, 4) = cs;
  A(4, 5) = sn;
  b(4) = F.Fv;
  // (12): phi'' - f5 delta'' = f6 delta'^2
  A(5, 3) = 1.0;
  A(5, 0) = -k.f5;
  b(5) = k.f6 * d2;
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(A);
  EXPECT_TRUE(lu.isInvertible());
  const Eigen::Matrix<double, 6, 1> x = lu.solve(b);
  if (forces) *forces = {x(4), x(5)};
  return {x(0), x(1), x(2), x(3)};
}

TEST(StickPhase, AgreesWithAnIndependentSolve) {
  std::mt19937 rng(42);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int i = 0; i < kSamples; ++i) {
      const Sample p = random_sample(rng, model, 0, false);
      const std::string where = describe(cfg, 0, p);
      ForcePair F{};
      const Accelerations want = solve_stick(model, p.t, p.q, &F);
      const Accelerations got = stick_accelerations(model, p.t, p.q);
      expect_same_accelerations(got, want, scales(model), kIndependentSolve, where);
      const ContactForces lib = contact_forces(model, p.q);
      EXPECT_NEAR(lib.N, F.N, kIndependentSolve * model.W()) << where;
      EXPECT_NEAR(lib.T, F.T, kIndependentSolve * model.W()) << where;
      EXPECT_EQ(got.delta, accelerations(model, p.t, p.q, Phase::stick).delta);
    }
  }
}

// ---- the slip phase -----------------------------------------------------------------------------

// On a slip state ((39) holds) the soil's N and T obey Coulomb's law T = -s mu N (27), and the
// accelerations of (34), (36), (38), (53) satisfy (19), (20), (23) with them.
TEST(SlipPhase, SatisfiesTheBalanceEquations) {
  std::mt19937 rng(1234);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int s : {1, -1}) {
      for (int i = 0; i < kSamples; ++i) {
        const Sample p = random_sample(rng, model, s, true);
        const std::string where = describe(cfg, s, p);
        EXPECT_NEAR(coupling(model, p.q, s), 0.0, kIdentity * model.W()) << where;
        EXPECT_GT(s * slip_velocity(model, p.q), 0.0) << where;
        const ForcePair soil = soil_contact(model, p.q);
        EXPECT_NEAR(soil.T, -s * model.cone() * soil.N, kBalanceResidual * model.W()) << where;
        const Accelerations a = slip_accelerations(model, p.t, p.q, s);
        expect_balanced(model, p.t, p.q, a, soil, where);
      }
    }
  }
}

// For any state (also off (39)) the slip equations take N from the soil (26) and T = -s mu N:
// the drum side (21)-(22) gives exactly these, and (19), (20), (23) hold with them.
TEST(SlipPhase, UsesNormalForceOfTheSoilAndCoulombFriction) {
  std::mt19937 rng(99);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int s : {1, -1}) {
      for (int i = 0; i < kSamples; ++i) {
        const Sample p = random_sample(rng, model, s, false);
        const std::string where = describe(cfg, s, p);
        const Accelerations a = slip_accelerations(model, p.t, p.q, s);
        const double N = contact_forces(model, p.q).N;  // (26)
        const ForcePair drum = drum_contact(model, p.q, a);
        EXPECT_NEAR(drum.N, N, kBalanceResidual * model.W()) << where;
        EXPECT_NEAR(drum.T, -s * model.cone() * N, kBalanceResidual * model.W()) << where;
        expect_balanced(model, p.t, p.q, a, {N, -s * model.cone() * N}, where);
      }
    }
  }
}

// (39) <=> Coulomb's law: T + s mu N = -residual(39) for the soil's N and T, at any state; and
// slip_constraint_residual is (39).
TEST(SlipPhase, CouplingIsTheFrictionLaw) {
  std::mt19937 rng(5);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int s : {1, -1}) {
      for (int i = 0; i < 50; ++i) {
        const Sample p = random_sample(rng, model, s, false);
        const double R = coupling(model, p.q, s);
        EXPECT_NEAR(slip_constraint_residual(model, p.q, s), R, kIdentity * model.W());
        const ContactForces F = contact_forces(model, p.q);
        EXPECT_NEAR(F.T + s * model.cone() * F.N, -R, kIdentity * model.W()) << describe(cfg, s, p);
      }
    }
  }
}

// The time derivative of (39), computed here with the returned accelerations, vanishes without
// Baumgarte stabilisation and equals -beta * residual with it (for states off (39)).
TEST(SlipPhase, CouplingRateVanishesOrDecaysAtTheBaumgarteRate) {
  std::mt19937 rng(31415);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    const double rate_scale = model.nu() * model.W();  // a force changing over 1/nu [N/s]
    for (int s : {1, -1}) {
      for (int i = 0; i < kSamples; ++i) {
        const bool on_cone = (i % 2 == 0);
        const Sample p = random_sample(rng, model, s, on_cone);
        const std::string where = describe(cfg, s, p);
        const double R = coupling(model, p.q, s);
        const Accelerations a0 = slip_accelerations(model, p.t, p.q, s, 0.0);
        EXPECT_NEAR(coupling_rate(model, p.q, a0, s), 0.0, kBalanceResidual * rate_scale) << where;
        for (double beta : {2.0 * model.nu(), 1e4}) {
          const Accelerations a = slip_accelerations(model, p.t, p.q, s, beta);
          EXPECT_NEAR(coupling_rate(model, p.q, a, s), -beta * R,
                      kBalanceResidual * (rate_scale + beta * std::abs(R)))
              << where << ", beta = " << beta << ", residual = " << R;
        }
      }
    }
  }
}

// Independent solve of the slip phase: unknowns (delta'', x_A'', s_A'', phi'', N, T) from (19),
// (20), (23), the normal soil force (26), Coulomb's law T = -s mu N (27) and the differentiated
// coupling d(39)/dt = -beta (39), by full-pivot LU.
Accelerations solve_slip(const Model& model, double t, const State& q, int s, double beta) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const double sn = std::sin(q.delta), cs = std::cos(q.delta);
  const SoilForces F = soil_forces(model, q);
  const FrictionFactors f = friction_factors(model, q.delta, s);
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b;
  drum_rows(model, t, q, k, A, b);  // (19), (20), (23) as in the stick phase
  // (26): N = Fh sin + Fv cos, the soil's normal force
  A(3, 4) = 1.0;
  b(3) = F.Fh * sn + F.Fv * cs;
  // (27): T + s mu N = 0
  A(4, 5) = 1.0;
  A(4, 4) = s * model.cone();
  b(4) = 0.0;
  // d/dt (39) = fmu1 (csh x_A'' + ksh x_A') - fmu2 (csv s_A'' + ksv s_A')
  //             - (fmu2 Fh + fmu1 Fv) delta' = -beta (39); scaled by 1/csh.
  const double csh = model.csh();
  A(5, 1) = f.fmu1;
  A(5, 2) = -f.fmu2 * model.csv() / csh;
  b(5) = (-beta * (f.fmu1 * F.Fh - f.fmu2 * F.Fv) - f.fmu1 * model.ksh() * q.dx_A +
          f.fmu2 * model.ksv() * q.ds_A + (f.fmu2 * F.Fh + f.fmu1 * F.Fv) * q.ddelta) /
         csh;
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(A);
  EXPECT_TRUE(lu.isInvertible());
  const Eigen::Matrix<double, 6, 1> x = lu.solve(b);
  return {x(0), x(1), x(2), x(3)};
}

TEST(SlipPhase, AgreesWithAnIndependentSolve) {
  std::mt19937 rng(2718);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int s : {1, -1}) {
      for (int i = 0; i < kSamples; ++i) {
        const Sample p = random_sample(rng, model, s, i % 2 == 0);
        for (double beta : {0.0, 2.0 * model.nu()}) {
          const std::string where = describe(cfg, s, p) + ", beta = " + std::to_string(beta);
          const Accelerations want = solve_slip(model, p.t, p.q, s, beta);
          const Accelerations got = slip_accelerations(model, p.t, p.q, s, beta);
          expect_same_accelerations(got, want, scales(model), kIndependentSolve, where);
          const Accelerations via = accelerations(
              model, p.t, p.q, s > 0 ? Phase::slip_positive : Phase::slip_negative, beta);
          EXPECT_EQ(via.delta, got.delta) << where;
          EXPECT_EQ(via.phi, got.phi) << where;
        }
      }
    }
  }
}

// At the friction cone (|T| = mu N, T = -s mu N) stick and slip give the same phi'': both are
// (23) with the same T.
TEST(SlipPhase, AngularAccelerationIsContinuousAtTheFrictionCone) {
  std::mt19937 rng(8);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int s : {1, -1}) {
      for (int i = 0; i < 50; ++i) {
        Sample p = random_sample(rng, model, s, true);
        const Accelerations slip = slip_accelerations(model, p.t, p.q, s);
        p.q.dphi = kinematics(model.geometry(), p.q.delta).f5 * p.q.ddelta;  // rolling
        const Accelerations stick = stick_accelerations(model, p.t, p.q);
        EXPECT_NEAR(slip.phi, stick.phi, kBalanceResidual * scales(model).phi)
            << describe(cfg, s, p);
      }
    }
  }
}

// The slip equations (34), (38), (53) are singular where the determinant of their x_A'', s_A''
// rows vanishes: cos fmu1 + (csv/csh) sin fmu2 = 0 with (35), written here from the matrix of
// (38) and (53). With a large friction coefficient that happens on the trough's flank; the
// accelerations grow as 1 / D there, and slip_determinant must be the D that does it.
TEST(SlipPhase, AccelerationsDivergeWhereTheSlipDeterminantVanishes) {
  std::mt19937 rng(41);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg, 0.05, 10.0);
    for (int s : {1, -1}) {
      const auto D = [&](double delta) {
        const FrictionFactors f = friction_factors(model, delta, s);
        return std::cos(delta) * f.fmu1 + model.csv() / model.csh() * std::sin(delta) * f.fmu2;
      };
      // D(0) = 1; the root on the side where s mu sin(delta) (csv/csh - 1) < 0.
      const double side = (model.csv() > model.csh() ? -1.0 : 1.0) * s;
      const auto delta_at = [&](double value) {  // bisection of D(delta) = value on [0, 1] side
        double lo = 0.0, hi = side * 1.0;
        EXPECT_LT(D(hi), 0.0) << cfg.name;
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (lo + hi);
          (D(mid) > value ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
      };
      Sample p = random_sample(rng, model, s, false);
      for (double delta : {0.0, 0.2 * side, delta_at(0.0)}) {
        EXPECT_NEAR(detail::slip_determinant(model, kinematics(model.geometry(), delta), s * 10.0),
                    D(delta), 1e-14)
            << cfg.name << ", delta = " << delta;
      }
      double previous = 0.0;
      for (double value : {1e-2, 1e-3, 1e-4}) {
        p.q.delta = delta_at(value);
        const Accelerations a = slip_accelerations(model, p.t, p.q, s);
        const double scaled = std::abs(a.x_A) * value;  // tends to a constant as D -> 0
        if (previous != 0.0) {
          EXPECT_NEAR(scaled / previous, 1.0, 0.05) << describe(cfg, s, p);
        }
        previous = scaled;
      }
      EXPECT_GT(previous, 0.0);
    }
  }
}

// Frictionless slip (mu = 0): no friction torque, phi'' = MM(t) / I (23).
TEST(SlipPhase, FrictionlessDrumSpinsFreely) {
  std::mt19937 rng(3);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg, 0.05, 0.0);
    for (int s : {1, -1}) {
      for (int i = 0; i < 50; ++i) {
        const Sample p = random_sample(rng, model, s, false);
        const Accelerations a = slip_accelerations(model, p.t, p.q, s, 2.0 * model.nu());
        EXPECT_DOUBLE_EQ(a.phi, model.torque(p.t) / model.I()) << describe(cfg, s, p);
      }
    }
  }
}

TEST(SlipPhase, SlipVelocity) {
  const Model model = make_model(kConfigs[2]);
  State q;
  q.delta = 0.2;
  q.ddelta = 30.0;
  q.dphi = 0.1;
  const double f5 = kinematics(model.geometry(), q.delta).f5;
  EXPECT_NEAR(slip_velocity(model, q), model.r() * (f5 * q.ddelta - q.dphi), kIdentity);  // (13)
  q.dphi = f5 * q.ddelta;  // rolling: no slip
  EXPECT_NEAR(slip_velocity(model, q), 0.0, kIdentity);
}

// ---- the slip phase with a velocity-dependent coefficient (a regularised law) -------------------

Model make_regularised_model(const Config& cfg, double v_eps) {
  Case c;
  c.trough.shape = trough_shape(cfg.k, cfg.a);
  c.numerics.suspension_from_static = cfg.from_static;
  c.MMd = 0.05 * c.roller.M0;
  c.contact.law = FrictionChoice::regularised;
  c.contact.v_eps = v_eps;
  return Model(c);
}

// A random state whose slip velocity is within a few v_eps, where tanh(v_rel / v_eps) and its
// derivatives are far from their limits.
Sample random_creep_sample(std::mt19937& rng, const Model& model, double v_eps) {
  Sample p = random_sample(rng, model, 1, false);
  const double f5 = kinematics(model.geometry(), p.q.delta).f5;
  const double v = std::uniform_real_distribution<double>(-3.0, 3.0)(rng) * v_eps;
  p.q.dphi = f5 * p.q.ddelta - v / model.r();  // (13)
  return p;
}

// The smooth phase takes N from the soil (26) and T = -mu tanh(v_rel / v_eps) N at any state, and
// its accelerations satisfy the drum's balances (19), (20), (23) with them.
TEST(SmoothSlipPhase, SatisfiesTheBalanceEquationsWithTheRegularisedLaw) {
  std::mt19937 rng(4242);
  for (const Config& cfg : kConfigs) {
    for (double v_eps : {1e-3, 0.1}) {
      const Model model = make_regularised_model(cfg, v_eps);
      for (int i = 0; i < kSamples; ++i) {
        const Sample p = random_creep_sample(rng, model, v_eps);
        const std::string where = describe(cfg, 0, p) + ", v_eps = " + std::to_string(v_eps);
        const Accelerations a = accelerations(model, p.t, p.q, Phase::smooth, 2.0 * model.nu());
        const double N = contact_forces(model, p.q).N;  // (26)
        const double T = -0.5 * std::tanh(slip_velocity(model, p.q) / v_eps) * N;
        const ForcePair drum = drum_contact(model, p.q, a);
        EXPECT_NEAR(drum.N, N, kBalanceResidual * model.W()) << where;
        EXPECT_NEAR(drum.T, T, kBalanceResidual * model.W()) << where;
        expect_balanced(model, p.t, p.q, a, {N, T}, where);
      }
    }
  }
}

// d(39)/dt along the smooth phase, with m = mu tanh(v_rel / v_eps) changing in time: written here
// from (35) and (13), fmu1' = -fmu2 delta' - m' sin, fmu2' = fmu1 delta' + m' cos,
// m' = dm/dv (r f6 delta'^2 + r f5 delta'' - r phi''). It equals -beta (39).
TEST(SmoothSlipPhase, CouplingRateIncludesTheChangingCoefficient) {
  std::mt19937 rng(777);
  for (const Config& cfg : kConfigs) {
    const double v_eps = 0.01;
    const Model model = make_regularised_model(cfg, v_eps);
    const double rate_scale = model.nu() * model.W();
    for (int i = 0; i < kSamples; ++i) {
      const Sample p = random_creep_sample(rng, model, v_eps);
      const State& q = p.q;
      const Kinematics k = kinematics(model.geometry(), q.delta);
      const double v = slip_velocity(model, q), th = std::tanh(v / v_eps);
      const double m = 0.5 * th, m_v = 0.5 * (1.0 - th * th) / v_eps;
      const double sn = std::sin(q.delta), cs = std::cos(q.delta);
      const double fmu1 = cs - m * sn, fmu2 = sn + m * cs;
      const SoilForces F = soil_forces(model, q);
      for (double beta : {0.0, 2.0 * model.nu()}) {
        const Accelerations a = accelerations(model, p.t, q, Phase::smooth, beta);
        const double dv = model.r() * (k.f6 * q.ddelta * q.ddelta + k.f5 * a.delta - a.phi);
        const double dm = m_v * dv;
        const double dFh = model.csh() * a.x_A + model.ksh() * q.dx_A;
        const double dFv = model.csv() * a.s_A + model.ksv() * q.ds_A;
        const double rate = (-fmu2 * q.ddelta - dm * sn) * F.Fh + fmu1 * dFh -
                            (fmu1 * q.ddelta + dm * cs) * F.Fv - fmu2 * dFv;
        const double g = fmu1 * F.Fh - fmu2 * F.Fv;
        EXPECT_NEAR(rate, -beta * g, kBalanceResidual * (rate_scale + beta * std::abs(g)))
            << describe(cfg, 0, p) << ", beta = " << beta;
        EXPECT_NEAR(slip_constraint_residual(model, q, 0), g, kIdentity * model.W());
      }
    }
  }
}

// With a constant coefficient (dm/dv = 0) the general system is the paper's (55): the general
// solve and the paper's elimination agree.
TEST(SmoothSlipPhase, GeneralSystemWithAConstantCoefficientIsThePapers) {
  std::mt19937 rng(99);
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg);
    for (int s : {1, -1}) {
      for (int i = 0; i < 50; ++i) {
        const Sample p = random_sample(rng, model, s, i % 2 == 0);
        const double beta = 2.0 * model.nu();
        const auto a = detail::general_slip_accelerations(
            model, p.t, p.q.to_array(),
            detail::kinematics_t(kinematics(model.geometry(), p.q.delta)), s * 0.5, 0.0, beta);
        const Accelerations want = slip_accelerations(model, p.t, p.q, s, beta);
        expect_same_accelerations({a[0], a[1], a[2], a[3]}, want, scales(model), kIndependentSolve,
                                  describe(cfg, s, p));
      }
    }
  }
}

// ---- equilibrium
// ---------------------------------------------------------------------------------

// Model::initial_state (at rest at the bottom, t = 0, MMd = 0) is an equilibrium of the stick
// phase, with the suspension measured either way; the soil carries N = W ksv / (ksv + kd) in the
// paper's convention (the suspension carries the rest) and N = W from static equilibrium.
TEST(Equilibrium, InitialStateIsAtRest) {
  for (const Config& cfg : kConfigs) {
    const Model model = make_model(cfg, 0.0);
    const State q = model.initial_state();
    EXPECT_EQ(q.delta, 0.0);
    EXPECT_EQ(q.x_A, 0.0);
    EXPECT_EQ(q.phi, 0.0);
    EXPECT_EQ(q.ddelta, 0.0);
    EXPECT_EQ(q.dx_A, 0.0);
    EXPECT_EQ(q.ds_A, 0.0);
    EXPECT_EQ(q.dphi, 0.0);
    const Accelerations a = stick_accelerations(model, 0.0, q);
    const Accelerations zero{};
    expect_same_accelerations(a, zero, scales(model), kIdentity, cfg.name);
    const ContactForces F = contact_forces(model, q);
    const double W = model.W(), ksv = model.ksv(), kd = model.kd();
    EXPECT_NEAR(F.N + kd * (q.s_A - model.z_ref()), W, kIdentity * W) << cfg.name;
    EXPECT_NEAR(F.N, cfg.from_static ? W : W * ksv / (ksv + kd), kIdentity * W) << cfg.name;
    EXPECT_NEAR(F.T, 0.0, kIdentity * W) << cfg.name;
    EXPECT_NEAR(q.s_A, cfg.from_static ? W / ksv : W / (ksv + kd), kIdentity * q.s_A);
    EXPECT_NEAR(model.z_ref(), cfg.from_static ? W / ksv : 0.0, kIdentity * W / ksv);
    expect_balanced(model, 0.0, q, a, {F.N, F.T}, cfg.name);
  }
}

// ---- symmetry
// ------------------------------------------------------------------------------------

State mirror(const State& q) {
  return {-q.delta, -q.x_A, q.s_A, -q.phi, -q.ddelta, -q.dx_A, q.ds_A, -q.dphi};
}

// Circular trough, MMd = 0: (delta, x_A, phi, their rates, t) -> (-..., t + half period) with
// s_A, s_A' kept (and s -> -s in slip) maps the accelerations to (-delta'', -x_A'', s_A'',
// -phi''), since MM(t + T/2) = -MM(t).
TEST(Symmetry, CircularTroughIsMirrorSymmetric) {
  std::mt19937 rng(2019);
  for (bool from_static : {false, true}) {
    const Config cfg{"circle R = 0.606", 0.0, 0.606, from_static};
    const Model model = make_model(cfg, 0.0);
    const double half = 0.5 * model.period();
    for (int s : {0, 1, -1}) {
      for (int i = 0; i < kSamples; ++i) {
        Sample p = random_sample(rng, model, s, s != 0 && i % 2 == 0);
        p.t = std::uniform_real_distribution<double>(0.0, 2.0 * model.period())(rng);
        const std::string where = describe(cfg, s, p);
        const State q2 = mirror(p.q);
        const double t2 = p.t + half;
        Accelerations a, b;
        if (s == 0) {
          a = stick_accelerations(model, p.t, p.q);
          b = stick_accelerations(model, t2, q2);
        } else {
          a = slip_accelerations(model, p.t, p.q, s, 2.0 * model.nu());
          b = slip_accelerations(model, t2, q2, -s, 2.0 * model.nu());
          EXPECT_NEAR(slip_constraint_residual(model, q2, -s),
                      -slip_constraint_residual(model, p.q, s), kIdentity * model.W());
        }
        const Accelerations want{-a.delta, -a.x_A, a.s_A, -a.phi};
        expect_same_accelerations(b, want, scales(model), kSymmetry, where);
        const ContactForces F = contact_forces(model, p.q), G = contact_forces(model, q2);
        EXPECT_NEAR(G.N, F.N, kIdentity * model.W()) << where;
        EXPECT_NEAR(G.T, -F.T, kIdentity * model.W()) << where;
      }
    }
  }
}

}  // namespace
}  // namespace oscidrum
