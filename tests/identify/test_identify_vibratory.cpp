// The identification of the soil from a vibratory drum's record (roller.type = vibratory,
// docs/model.md section 14): the same harmonics of x_M'' and z_M'' are fitted as for the
// oscillation drum, so a record of either roller gives its soil. Synthetic records made by
// oscidrum itself at 1 % from the case's frequency, with 5 % noise and a slow drift; the model's
// force amplitude F0 = m_u e_u nu^2 follows the record's f by itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "identify/synthetic_records.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

constexpr double kNominal = 30.0;       // the case's frequency [Hz]
constexpr double kF = kNominal * 1.01;  // the record's [Hz]
constexpr double kStaticMoment = 0.9;   // m_u e_u [kg m], as examples/vibratory.toml

// The paper's drum with a rotating unbalance (a circular exciter) on Appendix B soil, contact
// that can open, Coulomb friction mu = 0.5, at frequency f.
Case vibratory(double G, double f) {
  Case c;
  set_field_text(c, "roller.type", "vibratory");
  set_field(c, "roller.static_moment", kStaticMoment);
  set_field(c, "roller.f", f);
  set_field_text(c, "contact.unilateral", "true");
  c.soil.input = SoilInput::modulus;
  c.soil.G = G;
  return c;
}

// In contact throughout and with lift-off in every period: G is recovered within 3 % from the
// noisy record, its 95 % interval holds the truth, and the fit is good.
TEST(IdentifyVibratory, TheSoilOfAVibratoryRecordIsRecovered) {
  for (const double G : {12.0e6, 60.0e6}) {
    SCOPED_TRACE("G = " + std::to_string(G));
    const Case truth = vibratory(G, kF);
    const Result steady = simulate(Model(truth));
    ASSERT_EQ(steady.status, Status::steady_state) << steady.message;
    const RecordSamples r = noisy_record(truth, 1.5, 1500, 5);
    const Identification id = identify_whole(vibratory(25e6, kNominal), r, {});
    ASSERT_EQ(id.estimates.size(), 1u);
    const Estimate& e = id.estimates[0];
    EXPECT_NEAR(e.value / G, 1.0, 0.03);
    EXPECT_LE(e.lower, G);
    EXPECT_GE(e.upper, G);
    EXPECT_LT(id.relative_residual, 0.02);
    EXPECT_NEAR(id.f / kF, 1.0, 1e-4);
    // The model at the estimate is the vibratory drum at the record's f.
    EXPECT_NEAR(id.fitted.roller.f / kF, 1.0, 1e-4);
    EXPECT_EQ(get_field(id.fitted, "roller.static_moment"), kStaticMoment);
  }
}

// kb of a record (docs/outputs.md, `analyze --case --unbalance-col`): a noise-free record that
// oscidrum writes of a vibratory steady state (record time = model time modulo the period, so
// the unbalance's angle is alpha = 2 pi f t, the documented convention), sampled at 2000 points
// per period over 6 periods, gives the kb of the simulated steady state (the dense integral of
// the contact force): in continuous contact to the interpolation of the record (1e-6), with
// lift-off to the aliasing of the jump of z_M'' at the landing in 2000 samples per period
// (O(1/2000): 2e-3). Without the angle, the case or a vibratory roller: NaN and the reason.
TEST(IdentifyVibratory, KbOfARecordIsTheSimulatedKb) {
  struct Expected {
    double G, tolerance;
    bool lift_off;
  };
  for (const Expected e : {Expected{12e6, 1e-6, false}, Expected{60e6, 2e-3, true}}) {
    SCOPED_TRACE("G = " + std::to_string(e.G));
    const Case truth = vibratory(e.G, kNominal);
    const Model model(truth);
    const Result steady = simulate(model);
    ASSERT_EQ(steady.status, Status::steady_state) << steady.message;
    const Metrics sim = compute_metrics(model, steady);
    EXPECT_EQ(sim.flight_fraction > 0.0, e.lift_off);
    SyntheticRecord o;
    o.duration = 6.0 / kNominal;
    o.sample_rate = 2000.0 * kNominal;
    const RecordSamples r = synthetic_record({truth}, o);
    std::vector<double> alpha(r.t.size());
    for (std::size_t j = 0; j < r.t.size(); ++j) alpha[j] = 2.0 * M_PI * kNominal * r.t[j];
    WindowOptions wo;
    wo.f = kNominal;
    std::vector<RecordWindow> ws = analyze_windows(r.t, r.ddx_M, r.ddz_M, {}, wo);
    ASSERT_EQ(ws.size(), 1u);
    ASSERT_TRUE(ws[0].valid) << ws[0].reason;
    EXPECT_TRUE(std::isnan(ws[0].metrics.kb));  // before record_kb
    EXPECT_EQ(record_kb(ws, r.t, alpha, &truth), "");
    EXPECT_NEAR(ws[0].metrics.kb, sim.kb, e.tolerance * sim.kb);
    // The phase matters: the angle a quarter turn off gives another number.
    std::vector<double> off = alpha;
    for (double& a : off) a += M_PI / 2.0;
    std::vector<RecordWindow> shifted = ws;
    EXPECT_EQ(record_kb(shifted, r.t, off, &truth), "");
    EXPECT_GT(std::abs(shifted[0].metrics.kb - sim.kb), 0.1 * sim.kb);
    // Without the angle, the case, or with the oscillation drum: NaN and one line why.
    EXPECT_NE(record_kb(ws, r.t, {}, &truth).find("no unbalance angle"), std::string::npos);
    EXPECT_TRUE(std::isnan(ws[0].metrics.kb));
    EXPECT_NE(record_kb(ws, r.t, alpha, nullptr).find("--case"), std::string::npos);
    EXPECT_TRUE(std::isnan(ws[0].metrics.kb));
    const Case paper;
    EXPECT_NE(record_kb(ws, r.t, alpha, &paper).find("oscillation drum"), std::string::npos);
    EXPECT_TRUE(std::isnan(ws[0].metrics.kb));
  }
}

}  // namespace
}  // namespace oscidrum
