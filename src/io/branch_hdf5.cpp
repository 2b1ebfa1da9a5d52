// A branch of periodic orbits in one HDF5 file (oscidrum_io/branch_hdf5.hpp).
#include "oscidrum_io/branch_hdf5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "hdf5_objects.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/version.hpp"

namespace oscidrum::io {
namespace {

using namespace h5;  // NOLINT: the helpers of hdf5_objects.hpp

constexpr const char* kFormat = "oscidrum-branch";
constexpr std::int64_t kFormatVersion = 1;

// The branch and its descendants, depth first: (branch, index of its parent or -1), the order
// of `continue --csv`'s branch column.
std::vector<std::pair<const Branch*, int>> all_branches(const Branch& b) {
  std::vector<std::pair<const Branch*, int>> out = {{&b, -1}};
  for (std::size_t i = 0; i < out.size(); ++i)
    for (const Branch& c : out[i].first->children) out.push_back({&c, static_cast<int>(i)});
  return out;
}

// A (rows x cols) dataset of doubles, row-major.
void write_matrix(hid_t group, const std::string& name, const std::vector<double>& v,
                  std::size_t rows, std::size_t cols, const std::string& unit,
                  const std::string& file) {
  const hsize_t dims[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(cols)};
  const Id space(H5Screate_simple(2, dims, nullptr), H5Sclose);
  const Id d = checked(
      H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose, "cannot write " + file + ": dataset " + name);
  if (!v.empty())
    check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "cannot write " + file + ": dataset " + name);
  attr_string(d, "unit", unit, file);
}

Id group(hid_t parent, const std::string& name, const std::string& file) {
  return checked(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "cannot write " + file + ": group " + name);
}

// The datasets of one column per point; `unit` "" for none.
template <class F>
std::vector<double> column(const Branch& b, F get) {
  std::vector<double> v;
  for (const BranchPoint& p : b.points) v.push_back(static_cast<double>(get(p)));
  return v;
}

void write_branch(hid_t parent, std::size_t index, const Branch& b, int parent_index,
                  int first_child, const std::string& file) {
  const Id g = group(parent, std::to_string(index), file);
  attr_int(g, "multiplicity", b.multiplicity, file);
  attr_int(g, "parent", parent_index, file);
  attr_string(g, "end", to_string(b.end), file);
  attr_string(g, "message", b.message, file);
  attr_int(g, "period_maps", b.period_maps, file);
  attr_double(g, "seconds", b.seconds, file);
  const std::string& unit = b.unit;
  std::vector<std::int64_t> point;
  for (std::size_t k = 0; k < b.points.size(); ++k) point.push_back(static_cast<std::int64_t>(k));
  write_ints(g, "point", point, H5T_STD_I64LE, false, file);
  write_doubles(g, "parameter", column(b, [](const BranchPoint& p) { return p.parameter; }), unit,
                false, file);
  write_doubles(g, "arclength", column(b, [](const BranchPoint& p) { return p.arclength; }), "-",
                false, file);
  write_doubles(g, "multiplicity", column(b, [](const BranchPoint& p) { return p.multiplicity; }),
                "-", false, file);
  write_doubles(g, "stable", column(b, [](const BranchPoint& p) { return p.stable() ? 1 : 0; }),
                "-", false, file);
  write_doubles(g, "unstable", column(b, [](const BranchPoint& p) { return p.unstable; }), "-",
                false, file);
  write_doubles(g, "max_modulus",
                column(b, [](const BranchPoint& p) { return p.floquet.max_modulus; }), "-", false,
                file);
  write_doubles(g, "dq_ds", column(b, [](const BranchPoint& p) { return p.dq_ds; }), "-", false,
                file);
  write_doubles(g, "min_N", column(b, [](const BranchPoint& p) { return p.min_N; }), "N", false,
                file);
  write_doubles(g, "corrector_iterations",
                column(b, [](const BranchPoint& p) { return p.corrector_iterations; }), "-", false,
                file);
  std::vector<std::string> sequence;
  for (const BranchPoint& p : b.points) sequence.push_back(p.sequence);
  write_strings(g, "sequence", sequence, file);
  // The multipliers by decreasing modulus, one row per point (NaN where a point has fewer).
  std::size_t n_mu = 0;
  for (const BranchPoint& p : b.points) n_mu = std::max(n_mu, p.floquet.multipliers.size());
  std::vector<double> re, im;
  for (const BranchPoint& p : b.points)
    for (std::size_t i = 0; i < n_mu; ++i) {
      const std::complex<double> m =
          i < p.floquet.multipliers.size() ? p.floquet.multipliers[i] : NAN;
      re.push_back(m.real());
      im.push_back(m.imag());
    }
  write_matrix(g, "multipliers_re", re, b.points.size(), n_mu, "-", file);
  write_matrix(g, "multipliers_im", im, b.points.size(), n_mu, "-", file);
  {
    const Id metrics = group(g, "metrics", file);
    for (const MetricOutput& o : metric_outputs())
      if (std::holds_alternative<double Metrics::*>(o.member)) {
        std::vector<double> v;
        for (const BranchPoint& p : b.points) v.push_back(scalar_value(p.metrics, o));
        write_doubles(metrics, o.name, v, o.unit, false, file);
      }
    // A spectrum (ddx_harmonics, ddz_harmonics): its amplitudes A_1 ... A_H, points x H.
    const std::size_t n_h =
        harmonics_held(b.points, [](const BranchPoint& p) -> const Metrics& { return p.metrics; });
    for (const MetricOutput& o : metric_outputs())
      if (!std::holds_alternative<double Metrics::*>(o.member) && n_h > 0) {
        std::vector<double> v;
        for (const BranchPoint& p : b.points)
          for (std::size_t n = 1; n <= n_h; ++n) v.push_back(harmonic_amplitude(p.metrics, o, n));
        write_matrix(metrics, o.name, v, b.points.size(), n_h, o.unit, file);
      }
  }
  // The point index as the dimension scale of every 1-D column (netCDF-4 readers see it).
  {
    const Id scale(H5Dopen2(g, "point", H5P_DEFAULT), H5Dclose);
    std::vector<Id> open;
    for (const char* name : {"parameter", "arclength", "multiplicity", "stable", "unstable",
                             "max_modulus", "dq_ds", "min_N", "corrector_iterations", "sequence"})
      open.emplace_back(H5Dopen2(g, name, H5P_DEFAULT), H5Dclose);
    std::vector<hid_t> ids;
    for (const Id& d : open) ids.push_back(d);
    attach_scale(scale, "point", ids, file);
  }
  const Id bif = group(g, "bifurcations", file);
  std::vector<std::string> kind, description;
  std::vector<double> parameter, tolerance, mu_re, mu_im;
  std::vector<std::int64_t> after, child;
  for (const Bifurcation& f : b.bifurcations) {
    kind.emplace_back(to_string(f.kind));
    description.push_back(f.description);
    parameter.push_back(f.parameter);
    tolerance.push_back(f.tolerance);
    mu_re.push_back(f.multiplier.real());
    mu_im.push_back(f.multiplier.imag());
    after.push_back(f.after_point);
    child.push_back(f.child >= 0 ? first_child + f.child : -1);
  }
  write_strings(bif, "kind", kind, file);
  write_doubles(bif, "parameter", parameter, unit, false, file);
  write_doubles(bif, "tolerance", tolerance, unit, false, file);
  write_ints(bif, "after_point", after, H5T_STD_I64LE, false, file);
  write_doubles(bif, "multiplier_re", mu_re, "-", false, file);
  write_doubles(bif, "multiplier_im", mu_im, "-", false, file);
  write_ints(bif, "child_branch", child, H5T_STD_I64LE, false, file);
  write_strings(bif, "description", description, file);
}

}  // namespace

void write_branch_hdf5(const std::string& path, const Branch& root) {
  const QuietErrors quiet;
  const std::string partial = path + ".partial";
  const auto branches = all_branches(root);
  try {
    const Id file = checked(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                            H5Fclose, "cannot write " + path + ": cannot create " + partial);
    attr_string(file, "format", kFormat, path);
    attr_int(file, "format_version", kFormatVersion, path);
    attr_string(file, "oscidrum_version", oscidrum::version, path);
    attr_string(file, "key", root.key, path);
    attr_string(file, "unit", root.unit, path);
    attr_int(file, "n_branches", static_cast<std::int64_t>(branches.size()), path);
    const Id g = group(file, "branches", path);
    for (std::size_t index = 0; index < branches.size(); ++index) {
      // The children of branch `index` are numbered after it in all_branches' order.
      int first_child = -1;
      for (std::size_t j = 0; j < branches.size(); ++j)
        if (branches[j].second == static_cast<int>(index)) {
          first_child = static_cast<int>(j);
          break;
        }
      write_branch(g, index, *branches[index].first, branches[index].second, first_child, path);
    }
  } catch (...) {
    std::remove(partial.c_str());
    throw;
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0) {
    std::remove(partial.c_str());
    throw Error("cannot write " + path + ": cannot rename " + partial);
  }
}

}  // namespace oscidrum::io
