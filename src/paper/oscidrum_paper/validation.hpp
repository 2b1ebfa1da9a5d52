// oscidrum/validation.hpp: the paper's studies (docs/validation.md) and the check of every
// result the paper states that a simulation can check. Used by the tests, by `oscidrum validate`
// and `oscidrum paper`, and to generate docs/validation.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// One curve of the paper: a contact model, driving torque and trough, over a list of G.
struct PaperSeries {
  std::string id;           ///< e.g. "rolling_MMd0_R0.606"
  std::string description;  ///< e.g. "pure rolling, MMd = 0, circle R = 0.606 m"
  bool pure_rolling = true;
  double MMd_fraction = 0.0;  ///< MMd / M0 [-]
  double k = 0.0;             ///< trough spiral parameter [-]
  double a = 0.606;           ///< trough spiral parameter (circle radius when k = 0) [m]
  std::vector<double> G;      ///< shear moduli [Pa]: Table 2 values use Table 2, others Appendix B
  double mu = 0.5;            ///< friction coefficient when !pure_rolling [-]
};

/// The case the paper simulates for one series at one G (Table 1 roller, Table 2 soil, mu = 0.5
/// for stick-slip).
Case paper_case(const PaperSeries& series, double G);

/// Every series the paper plots (Figs. 7-22): pure rolling MMd = 0 for R = 0.603, 0.606, 0.62,
/// 0.65 m (the paper prints only the extremes of its four radii; 0.62 is our choice), pure
/// rolling MMd = 0.05 M0, stick-slip (mu = 0.5) MMd = 0 and 0.05 M0, all over G = 5 ... 70
/// MN/m^2 on R = 0.606 m unless said; and the trough-shape pair at G = 5 (circle R = 0.603 m and
/// spiral k = 0.002, a = 0.601 m).
std::vector<PaperSeries> paper_series();

/// The outcome of one series: per G, the status and metrics.
struct SeriesResult {
  PaperSeries series;
  std::vector<Status> status;
  std::vector<Metrics> metrics;
  std::vector<Diagnostics> diagnostics;
  std::vector<Result> results;  ///< kept only when asked (samples for figures)
};

struct PaperRunOptions {
  int threads = 0;            ///< 0: all cores
  bool keep_samples = false;  ///< keep each case's steady state (for figures)
  int n_harmonics = 10;
  SteadyMethod method = Numerics{}.method;  ///< how each case's steady state is found
  double steady_tol = 0.0;  ///< numerics.steady_tol of every case (0: the default) [-]
  std::function<void(std::size_t done, std::size_t total)> progress;
  /// Polled as StudyOptions::cancelled; when it returns true the run stops and
  /// run_paper_studies throws oscidrum::Error("cancelled").
  std::function<bool()> cancelled;
};

/// Run every series of paper_series() (about 100 cases).
std::vector<SeriesResult> run_paper_studies(const PaperRunOptions& options = {});

/// One line of the validation table.
struct ValidationRow {
  std::string id;        ///< short stable identifier, e.g. "fig9a.xmax_G5"
  std::string figure;    ///< where the paper says it, e.g. "Fig. 9a"
  std::string claim;     ///< what the paper states
  std::string paper;     ///< the paper's number or statement
  std::string oscidrum;  ///< what oscidrum computes
  std::string rule;      ///< the acceptance rule applied
  bool agrees = false;
  bool checkable = true;  ///< false: the paper gives nothing a simulation can be compared with
  std::string note;       ///< explanation, required where it does not agree
};

/// Check every claim listed in docs/validation.md against the results of run_paper_studies().
std::vector<ValidationRow> validate(const std::vector<SeriesResult>& results);

/// The table as Markdown (with a summary line), for docs/validation.md.
std::string validation_markdown(const std::vector<ValidationRow>& rows);

}  // namespace oscidrum
