// oscidrum_io/sweep.hpp: a study = a base case and the parameters to vary, expanded into cases.
// The TOML syntax is in docs/config.md ("Sweeps"); config.hpp reads it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "oscidrum/parameters.hpp"
#include "oscidrum_io/case_spec.hpp"

namespace oscidrum::io {

/// One swept key and its values.
struct SweepAxis {
  std::string key;            ///< a field key or an extra key (soil.table2_G, MMd_fraction)
  std::vector<Value> values;  ///< at least one
  std::string origin;         ///< "study.toml:7:1"
};

/// Axes varied together (zipped: equal lengths). In product mode each factor is one dimension of
/// the cartesian product.
struct SweepFactor {
  std::vector<SweepAxis> axes;
  std::size_t size() const { return axes.empty() ? 0 : axes.front().values.size(); }
};

enum class SweepMode { product, zip };

struct StudySpec {
  CaseSpec base;  ///< the base case (file keys, then flags)
  SweepMode mode = SweepMode::product;
  std::vector<SweepFactor> factors;  ///< in file order; the first varies slowest
  std::string source;                ///< the study file, for messages
};

/// The expanded study: one Case per combination, with the swept values that made it.
struct Study {
  std::vector<std::string> keys;           ///< swept keys, in column order
  std::vector<Case> cases;                 ///< finalised and validated
  std::vector<std::vector<Value>> varied;  ///< per case, one value per key
};

/// Largest study expand() accepts.
inline constexpr std::size_t kMaxStudyCases = 1000000;

/// Expand the product (or the zip) into finalised, validated cases, in order: product mode
/// counts like nested loops with the first factor outermost. Throws oscidrum::Error naming the
/// case and its swept values when one is invalid, or when zipped lists differ in length.
Study expand(const StudySpec& spec);

/// A 64-bit fingerprint of the cases (every field of every case) and of `extra` (e.g. the
/// output header): a journal of a different study is never resumed.
std::uint64_t fingerprint(const Study& study, const std::string& extra);

}  // namespace oscidrum::io
