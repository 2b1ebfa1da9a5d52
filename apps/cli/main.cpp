// oscidrum: the command-line tool. Parses the command line with CLI11, runs the selected
// command, and turns every error into a one-line message and an exit code (commands.hpp).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/text.hpp"
#include "oscidrum/version.hpp"
#include "terminal.hpp"

namespace {

using namespace oscidrum::cli;

// Every command, in the order of `oscidrum --help`.
constexpr AddCommand kCommands[] = {
    add_run_command,      add_sweep_command,
    add_merge_command,    add_analyze_command,
    add_identify_command, add_calibrate_command,
    add_validate_command, add_paper_command,
    add_soil_command,     add_transmissibility_command,
    add_fields_command,   add_outputs_command,
    add_continue_command, add_diagram_command,
};

// Lists each command with the first sentence of its description only; `oscidrum CMD --help`
// shows the whole of it.
class Formatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override {
    std::string text = sub->get_description();
    const std::size_t end = text.find(". ");
    if (end != std::string::npos) text = text.substr(0, end + 1);
    std::ostringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true), text, column_width_);
    return out.str();
  }
};

// One line of printable UTF-8: line breaks become spaces, other control characters and bytes
// that are not UTF-8 (a file name or a cell from a binary file) are escaped as \xNN.
std::string one_line(std::string s) {
  if (s.size() > 2000) s = s.substr(0, 2000) + "... (cut)";  // never a megabyte of echo
  for (char& ch : s)
    if (ch == '\n' || ch == '\r') ch = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return oscidrum::printable(s);
}

int error(const std::string& message, int code) {
  std::cerr << "oscidrum: error: " << one_line(message) << "\n";
  return code;
}

// CLI11's parse errors in words that say what to do: a flag given twice ("At Most 1 required but
// received 2"), and a near miss of a flag or command named ("--Mu", "sweeep").
std::string explain_parse_error(const CLI::ParseError& e, const CLI::App& app,
                                const CLI::App& active) {
  const std::string message = e.what();
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) &&
      message.find("At Most 1 required but received") != std::string::npos) {
    const std::string name = message.substr(0, message.find(':'));
    return name + " is given more than once (or with its short form too); give it once";
  }
  if (!dynamic_cast<const CLI::ExtrasError*>(&e)) return message;
  const std::size_t colon = message.find(": ");
  if (colon == std::string::npos) return message;
  std::vector<std::string> flags, commands;
  for (const CLI::Option* opt : active.get_options()) {
    for (const std::string& l : opt->get_lnames()) flags.push_back("--" + l);
    for (const std::string& s : opt->get_snames()) flags.push_back("-" + s);
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    commands.push_back(sub->get_name());
  const auto has = [&](const std::string& flag) {
    return std::find(flags.begin(), flags.end(), flag) != flags.end();
  };
  // "did you mean --mu?" for one near miss; "--mu for --Mu, --nu for --Nu" for several.
  std::vector<std::pair<std::string, std::string>> near_misses;  // (word, guess)
  std::string output_hint;
  std::istringstream words(message.substr(colon + 2));
  for (std::string word; words >> word;) {
    std::string near;
    if (word.rfind("-", 0) == 0) {
      const std::string flag = word.substr(0, word.find('='));
      near = oscidrum::nearest(flag, flags);
      // An output file asked for as sweep's --out (or -o): name the command's own outputs.
      if (near.empty() && (flag == "--out" || flag == "--output" || flag == "-o") && has("--csv") &&
          has("--json"))
        output_hint = "this command writes its outputs with --csv FILE and --json FILE";
    } else if (&active == &app) {
      near = oscidrum::nearest(word, commands);
    }
    if (!near.empty() && near != word) near_misses.emplace_back(word, near);
  }
  std::string hints;
  if (near_misses.size() == 1) hints = near_misses[0].second;
  for (std::size_t i = 0; near_misses.size() > 1 && i < near_misses.size(); ++i)
    hints += (i == 0 ? "" : ", ") + near_misses[i].second + " for " + near_misses[i].first;
  std::string explained = message;
  if (!hints.empty()) explained += " (did you mean " + hints + "?)";
  if (!output_hint.empty()) explained += " (" + output_hint + ")";
  return explained;
}

int run(int argc, char** argv) {
  CLI::App app(
      "oscidrum simulates an oscillation roller drum on soil: the stick-slip model of Paulmichl, "
      "Adam & Adam (2019), integrated from rest to its steady state.\nAll inputs and outputs "
      "are in SI units unless a flag says otherwise.",
      "oscidrum");
  app.set_version_flag("--version", oscidrum::version);
  app.formatter(std::make_shared<Formatter>());
  app.footer(
      "Examples:\n"
      "  oscidrum run                          the paper's roller on Table 2 soil, G = 25 MN/m^2\n"
      "  oscidrum run --G 40 --pure-rolling --csv steady.csv\n"
      "  oscidrum sweep examples/table2_sweep.toml --out results.csv\n"
      "  oscidrum sweep study.toml --shard 2/4 --out s2.csv   one slice; oscidrum merge joins "
      "them\n"
      "  oscidrum analyze field.csv            metrics of a measured acceleration record\n"
      "  oscidrum identify pass.csv            the soil's G along a pass, with its band\n"
      "  oscidrum validate                     check every result the paper states\n"
      "  oscidrum paper --out out/paper        the paper's figures, data and report\n"
      "  oscidrum soil --table2                Appendix B against paper Table 2\n"
      "  oscidrum fields                       every config key with unit, default and rule\n"
      "Exit codes: 0 ok, 1 a case did not reach its steady state, 2 bad usage or input, "
      "3 internal error, 130 interrupted.\nDocs: docs/cli.md, docs/config.md, docs/outputs.md");
  Action action;
  std::string names;
  for (AddCommand add : kCommands) add(app, action);
  strict_numbers(app);  // every numeric flag: decimal text only, before its own rule
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string where = "oscidrum";
    const CLI::App* active = &app;
    for (const CLI::App* sub : app.get_subcommands()) {
      where += " " + sub->get_name();
      active = sub;
    }
    return error(explain_parse_error(e, app, *active) + " (see '" + where + " --help')",
                 kExitUsage);
  }
  if (!action)
    return error("a command is required: " + names + " (see 'oscidrum --help')", kExitUsage);
  const int code = action();
  // Results written to a standard output that cannot take them (a full disk, /dev/full, a closed
  // pipe) are lost: that is an error, not success.
  std::cout.flush();
  const bool c_failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (!std::cout || c_failed)
    return error(std::string("writing to standard output failed (") + std::strerror(errno) +
                     "): the results are lost",
                 kExitUsage);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  install_interrupt_handlers();  // first: before any thread starts (terminal.hpp)
  try {
    return run(argc, argv);
  } catch (const oscidrum::Error& e) {
    // A wait or a write cut short by the signal (a FIFO without a reader) ends as interrupted.
    if (interrupted())
      return error(std::string("interrupted (") + interrupt_name() + ")", interrupted_exit_code());
    return error(e.what(), kExitUsage);
  } catch (const std::exception& e) {
    return error(std::string("internal error: ") + e.what(), kExitInternal);
  } catch (...) {
    return error("internal error: unknown exception", kExitInternal);
  }
}
