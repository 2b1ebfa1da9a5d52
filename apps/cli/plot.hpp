// plot.hpp: the --plot option of `oscidrum run`, which hands the files to the Python package.
#pragma once

#include <string>
#include <vector>

namespace oscidrum::cli {

/// Run `python_interpreter() -m oscidrum.plot case --csv CSV --json JSON --out DIR` (its stdout
/// goes to our stderr, so that our stdout stays a clean result). The package's source directory is
/// put first on PYTHONPATH when the tool runs from a build tree. Returns true on success; on
/// failure prints why on stderr and returns false. `quiet`: as run_python's.
bool run_plot(const std::string& csv, const std::string& json, const std::string& dir,
              bool quiet = false);

/// The Python interpreter --plot and `paper` run: $OSCIDRUM_PYTHON if set, else the one the build
/// made the package for (CMake's Python3_EXECUTABLE), else /usr/bin/python3. Never the
/// `python3` on PATH, which may be an interpreter without the package's dependencies.
std::string python_interpreter();

/// Run `python_interpreter() -m <module_args...>` with the package found first in the build tree,
/// its output on our stdout. Returns its exit status, or -1 if it could not start or was killed
/// (then one error line ending with `data_note` is printed; for other non-zero statuses too unless
/// `quiet_status` lists them or it is 3, a module's error it explained itself). SIGINT or SIGTERM
/// is passed on to the module; it returns -1 then, without a message (the caller sees
/// interrupted()). `quiet` (the command's --quiet): the module's own lines (the files it wrote)
/// are not shown; its errors are. `plotting`: a --plot's module, so that the watcher, should it
/// have to end a module slow to stop, says "interrupted while plotting; " and `data_note` as
/// plot_interrupted does.
int run_python(const std::vector<std::string>& module_args, const std::string& data_note,
               const std::vector<int>& quiet_status = {}, bool quiet = false, bool plotting = true);

/// After a --plot's run_python was interrupted: "oscidrum: interrupted while plotting; " and
/// `data_note` on stderr; returns the signal's exit code (130 or 143).
int plot_interrupted(const std::string& data_note);

}  // namespace oscidrum::cli
