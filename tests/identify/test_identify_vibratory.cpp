// The identification of the soil from a vibratory drum's record (roller.type = vibratory,
// docs/model.md section 14): the same harmonics of x_M'' and z_M'' are fitted as for the
// oscillation drum, so a record of either roller gives its soil. Synthetic records made by
// oscidrum itself at 1 % from the case's frequency, with 5 % noise and a slow drift; the model's
// force amplitude F0 = m_u e_u nu^2 follows the record's f by itself.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace oscidrum
