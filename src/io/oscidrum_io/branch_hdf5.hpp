// oscidrum_io/branch_hdf5.hpp: a branch of periodic orbits and the period-2p branches switched
// onto at its period doublings in one HDF5 file (`oscidrum continue --hdf5 FILE`). The layout is
// documented in docs/bifurcations.md ("Outputs"); h5py reads it directly. HDF5 (the C library)
// stays out of this header.
#pragma once

#include <string>

#include "oscidrum/branch.hpp"

namespace oscidrum::io {

/// Write `root` and its children (depth first, as `continue --csv` numbers them) to `path`: a
/// group /branches/<index> per branch with its points as datasets (a unit attribute on each, the
/// dimension scale "point"), its multipliers as 2-D datasets, its metrics in metrics/ and its
/// bifurcations in bifurcations/. Written to PATH.partial, then renamed. Throws oscidrum::Error
/// "cannot write PATH: ...".
void write_branch_hdf5(const std::string& path, const Branch& root);

}  // namespace oscidrum::io
