// Paper Fig. 16 in C++ (the twin of examples/fig16_area_pure_rolling.py): the area inside the
// z_M''-x_M'' figure against the soil's shear modulus G, pure rolling, MMd = 0 and 0.05 M0.
//
//   build/examples/fig16_area_pure_rolling > fig16.csv
//
// Prints a CSV (G [MN/m^2], area for MMd = 0 and 0.05 M0 [m^2/s^4]) on stdout and the G of each
// maximum on stderr. The paper: largest at G = 20-25 MN/m^2 without, at G = 40 with the torque.
#include <cstdio>
#include <vector>

#include "oscidrum/oscidrum.hpp"
#include "oscidrum_paper/validation.hpp"

int main() {
  // The paper's two pure-rolling series on the circle R = 0.606 m, as the library defines them
  // (the cases of `oscidrum validate`).
  std::vector<oscidrum::PaperSeries> series;
  for (const oscidrum::PaperSeries& s : oscidrum::paper_series())
    if (s.id == "rolling_MMd0_R0.606" || s.id == "rolling_MMd0.05_R0.606") series.push_back(s);
  std::vector<oscidrum::Case> cases;
  for (const oscidrum::PaperSeries& s : series)
    for (double G : s.G) cases.push_back(oscidrum::paper_case(s, G));

  // Every case on all cores; outcomes in input order.
  const std::vector<oscidrum::CaseOutcome> out = oscidrum::run_study(cases);
  const std::size_t n = series[0].G.size();
  std::printf("G[MN/m^2],area_MMd0[m^2/s^4],area_MMd0.05[m^2/s^4]\n");
  for (std::size_t i = 0; i < n; ++i)
    std::printf("%g,%.6g,%.6g\n", series[0].G[i] / 1e6, out[i].metrics.area,
                out[n + i].metrics.area);
  for (std::size_t k = 0; k < series.size(); ++k) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!oscidrum::ok(out[k * n + i].result.status)) {
        std::fprintf(stderr, "case failed: %s\n", out[k * n + i].result.message.c_str());
        return 1;
      }
      if (out[k * n + i].metrics.area > out[k * n + best].metrics.area) best = i;
    }
    std::fprintf(stderr, "%s: largest area %.1f m^2/s^4 at G = %g MN/m^2\n",
                 series[k].description.c_str(), out[k * n + best].metrics.area,
                 series[k].G[best] / 1e6);
  }
  return 0;
}
