// commands.hpp: the commands of the oscidrum tool. Each command lives in its own file and has one
// entry point that adds its subcommand to the app; main.cpp lists them in kCommands. To add a
// command (e.g. `oscidrum paper`, `oscidrum validate`): write cmd_<name>.cpp with an
// add_<name>_command function, declare it here, add it to kCommands in main.cpp and the source
// to CMakeLists.txt.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace oscidrum {
struct ValidationRow;
}

namespace oscidrum::cli {

/// Exit codes (docs/cli.md).
inline constexpr int kExitOk = 0;          ///< success
inline constexpr int kExitCaseFailed = 1;  ///< a case ended with a status other than steady_state
inline constexpr int kExitUsage = 2;       ///< bad usage or input (message on stderr)
inline constexpr int kExitInternal = 3;    ///< a bug: an unexpected exception
inline constexpr int kExitInterrupted = 130;  ///< SIGINT; 143 for SIGTERM (interrupted_exit_code)

/// What a parsed command does; main runs it after parsing, and returns its exit code.
using Action = std::function<int()>;

/// Adds a subcommand to `app`. When it is selected, its callback stores its work in `action`.
using AddCommand = void (*)(CLI::App& app, Action& action);

void add_run_command(CLI::App& app, Action& action);
void add_sweep_command(CLI::App& app, Action& action);
void add_merge_command(CLI::App& app, Action& action);
void add_soil_command(CLI::App& app, Action& action);
void add_transmissibility_command(CLI::App& app, Action& action);
void add_fields_command(CLI::App& app, Action& action);
void add_validate_command(CLI::App& app, Action& action);
void add_paper_command(CLI::App& app, Action& action);
void add_analyze_command(CLI::App& app, Action& action);
void add_outputs_command(CLI::App& app, Action& action);
void add_identify_command(CLI::App& app, Action& action);
void add_continue_command(CLI::App& app, Action& action);
void add_diagram_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action);

/// The validation table as CSV (one row per claim): `validate --csv`, and `paper` without its
/// Python package.
std::string validation_csv(const std::vector<ValidationRow>& rows);

}  // namespace oscidrum::cli
