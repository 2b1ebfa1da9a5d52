// oscidrum paper: reproduce the paper. The studies, the data behind Figs. 7-22, the figures and
// the report come from the Python package (oscidrum.paper run by python_interpreter(), one plotting
// implementation), which includes the validation table of src/validation.cpp. Without Python,
// the validation table alone is written.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum_io/files.hpp"
#include "oscidrum_paper/validation.hpp"
#include "plot.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct PaperOptions {
  std::string out = "out/paper";
  std::string format = "png";
  int threads = 0;
  bool quiet = false;
};

int run(const PaperOptions& o) {
  if (o.out.empty()) throw Error("--out needs a directory name; got an empty one");
  std::error_code ec;
  const bool existed = std::filesystem::exists(o.out, ec);
  std::filesystem::create_directories(o.out, ec);
  if (ec || !std::filesystem::is_directory(o.out))
    throw Error("--out " + o.out + ": cannot create the directory" +
                (ec ? ": " + ec.message() : std::string(" (a file of that name exists)")));
  std::vector<std::string> args = {
      "oscidrum.paper",         "--out", o.out, "--format", o.format, "--threads",
      std::to_string(o.threads)};
  if (o.quiet) args.emplace_back("--quiet");
  // paper.py exits 0 when every claim agrees and 1 (with the report written) when one does not.
  const int status =
      run_python(args, "writing the validation table alone", {1}, false, /*plotting=*/false);
  if (interrupted()) {  // paper.py removed what it had started: nothing partial is left
    // Nor the folder, when this run made it and it stayed empty.
    if (!existed && std::filesystem::is_empty(o.out, ec)) std::filesystem::remove(o.out, ec);
    std::cerr << "oscidrum: interrupted; nothing written\n";
    return interrupted_exit_code();
  }
  const bool reported = std::filesystem::exists(o.out + "/report.md");
  if (status == 0 || (status == 1 && reported)) {
    if (!o.quiet) std::cerr << "oscidrum paper: figures, data and report.md in " << o.out << "\n";
    return status == 0 ? kExitOk : kExitCaseFailed;
  }
  PaperRunOptions po;
  po.threads = o.threads;
  po.cancelled = [] { return interrupted(); };
  std::vector<SeriesResult> results;
  try {
    results = run_paper_studies(po);
  } catch (const Error&) {
    if (!interrupted()) throw;
    std::cerr << "oscidrum: interrupted\n";
    return interrupted_exit_code();
  }
  const std::vector<ValidationRow> rows = validate(results);
  io::write_file_atomic(o.out + "/validation.md",
                        "# Validation against the paper\n\n" + validation_markdown(rows));
  io::write_file_atomic(o.out + "/validation.csv", validation_csv(rows));
  std::cerr << "oscidrum paper: wrote " << o.out << "/validation.md and " << o.out
            << "/validation.csv only (the figures need the Python package)\n";
  return kExitCaseFailed;
}

}  // namespace

void add_paper_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<PaperOptions>();
  CLI::App* sub = app.add_subcommand(
      "paper",
      "Reproduce the paper: every study with its data, figures and a report. "
      "Runs the paper's ~100 cases on all cores and writes into --out: for each of Figs. 7-22 a "
      "CSV and a "
      "figure, report.md (each figure beside the paper's stated result) and the validation "
      "table validation.md. Needs the oscidrum Python package (matplotlib) for the figures.");
  sub->footer("Examples:\n  oscidrum paper --out out/paper --format svg");
  sub->add_option("--out", o->out, "output folder (default out/paper)");
  sub->add_option("--format", o->format, "figure format: png or svg")
      ->check(CLI::IsMember({"png", "svg"}));
  sub->add_option("--threads", o->threads, "worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024));
  sub->add_flag("-q,--quiet", o->quiet, "no progress on stderr");
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
