// plot.hpp: the --plot option of `oscidrum run`, which hands the files to the Python package.
#pragma once

#include <string>

namespace oscidrum::cli {

/// Run `/usr/bin/python3 -m oscidrum.plot case --csv CSV --json JSON --out DIR` (its stdout goes
/// to our stderr, so that our stdout stays a clean result). The package's source directory is
/// put first on PYTHONPATH when the tool runs from a build tree. Returns true on success; on
/// failure prints why on stderr and returns false.
bool run_plot(const std::string& csv, const std::string& json, const std::string& dir);

}  // namespace oscidrum::cli
