// Where could the drum's steady state double its period? A scan of the Floquet multipliers of the
// period-1 steady state (docs/periodic.md, "Subharmonic orbits"). A period doubling happens where
// a real multiplier crosses -1; this prints, for every case of a grid, the most negative real
// multiplier and the largest modulus, and at the end the case closest to -1.
//
//   build/examples/floquet_scan > scan.csv                    # the grid of docs/periodic.md
//   build/examples/floquet_scan roller.f=20,25,30 MMd=0,4000  # any grid: key=v1,v2,... (product)
//
// Keys are the parameter names of `oscidrum fields`. Without arguments the grid is the one
// documented in docs/periodic.md. The soil is given by its shear modulus (soil.input = modulus),
// the roller by its unbalance unless roller.unbalance=0 is given (then roller.M0 stays fixed).
// Columns: the swept values, status, method (shooting, or transient when shooting fell back),
// multiplicity, stability, max_modulus and min_real (the most negative real multiplier; empty
// when the steady state has no multipliers). A stable period-1 orbit has min_real > -1; a
// period-2 steady state found by shooting reports multiplicity 2.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "oscidrum/oscidrum.hpp"

namespace {

struct Factor {
  std::string key;
  std::vector<std::string> values;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    out.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Factor> grid;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "floquet_scan: expected key=v1,v2,...; got '%s'\n", argv[i]);
      return 2;
    }
    grid.push_back({arg.substr(0, eq), split(arg.substr(eq + 1))});
  }
  if (grid.empty()) {
    // The plausible space of a real roller: f 20-80 Hz with M0 following f^2 (the paper's
    // unbalance), soft to stiff soil, driving torques up to about the friction limit mu W r,
    // friction coefficients, circular troughs from tight to wide and a log-spiral.
    grid = {{"roller.f", split("20,22.5,25,27.5,30,35,40,45,50,55,60,65,70,75,80")},
            {"soil.G", split("5e6,15e6,25e6,50e6,100e6")},
            {"MMd", split("0,2000,4000,6000,8000")},
            {"contact.mu", split("0.3,0.5,0.7")},
            {"trough.a", split("0.603,0.606,0.65")}};
  }
  for (const Factor& f : grid) std::printf("%s,", f.key.c_str());
  std::printf("status,method,multiplicity,stability,max_modulus,min_real\n");

  std::vector<std::size_t> index(grid.size(), 0);
  double closest = 0.0;
  std::string closest_case;
  long cases = 0, doubled = 0;
  while (true) {
    oscidrum::Case c;
    c.soil.input = oscidrum::SoilInput::modulus;
    c.roller.unbalance = 0.22877;  // M0 = 4 m_u e_u e_w nu^2 (5), the paper's roller
    std::string label;
    try {
      for (std::size_t k = 0; k < grid.size(); ++k) {
        oscidrum::set_field_text(c, grid[k].key, grid[k].values[index[k]]);
        label += grid[k].values[index[k]] + ",";
      }
      const oscidrum::Result r = oscidrum::simulate(c);
      double min_real = std::nan("");
      for (const auto& z : r.floquet.multipliers)
        if (std::abs(z.imag()) <= 1e-8 * std::abs(z) && !(z.real() >= min_real))
          min_real = z.real();
      std::printf(
          "%s%s,%s,%d,%s,", label.c_str(), oscidrum::to_string(r.status),
          r.diagnostics.method == oscidrum::SteadyMethod::shooting ? "shooting" : "transient",
          r.diagnostics.multiplicity, oscidrum::to_string(r.floquet.stability));
      if (r.floquet.stability == oscidrum::Stability::unknown)
        std::printf(",\n");
      else
        std::printf("%.6f,%.6f\n", r.floquet.max_modulus, min_real);
      ++cases;
      if (r.diagnostics.multiplicity > 1) ++doubled;
      if (r.diagnostics.multiplicity == 1 && min_real < closest) {
        closest = min_real;
        closest_case = label;
      }
    } catch (const oscidrum::Error& e) {
      std::printf("%s# invalid: %s\n", label.c_str(), e.what());
    }
    std::size_t k = 0;
    for (; k < grid.size(); ++k) {
      if (++index[k] < grid[k].values.size()) break;
      index[k] = 0;
    }
    if (k == grid.size()) break;
  }
  std::fprintf(stderr,
               "%ld cases, %ld with a steady state repeating every p > 1 periods; most negative "
               "real multiplier of a period-1 orbit: %.6f at (",
               cases, doubled, closest);
  for (std::size_t k = 0; k < grid.size(); ++k)
    std::fprintf(stderr, "%s%s", k ? ", " : "", grid[k].key.c_str());
  if (!closest_case.empty()) closest_case.pop_back();
  std::fprintf(stderr, ") = (%s)\n", closest_case.c_str());
  return 0;
}
