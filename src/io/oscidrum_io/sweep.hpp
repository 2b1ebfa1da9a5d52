// oscidrum_io/sweep.hpp: a study = a base case and the parameters to vary, expanded into cases.
// The TOML syntax is in docs/config.md ("Sweeps"); config.hpp reads it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
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

class Expansion;  // the base case and the factors (sweep.cpp)

/// The cases of a study, built on demand from the base case and the swept values: a study of
/// a million cases holds its factors, not a million Case objects. Indexing builds (and
/// finalises) case i; expand() has validated every one.
class StudyCases {
 public:
  StudyCases() = default;
  explicit StudyCases(std::shared_ptr<const Expansion> e) : e_(std::move(e)) {}
  std::size_t size() const;
  bool empty() const { return size() == 0; }
  Case operator[](std::size_t i) const;
  Case at(std::size_t i) const;  ///< throws std::out_of_range past the end
  Case front() const { return at(0); }

  class iterator {
   public:
    using value_type = Case;
    using difference_type = std::ptrdiff_t;
    iterator(const StudyCases* c, std::size_t i) : c_(c), i_(i) {}
    Case operator*() const { return (*c_)[i_]; }
    iterator& operator++() { return ++i_, *this; }
    bool operator==(const iterator& o) const { return i_ == o.i_; }

   private:
    const StudyCases* c_;
    std::size_t i_;
  };
  iterator begin() const { return {this, 0}; }
  iterator end() const { return {this, size()}; }

 private:
  std::shared_ptr<const Expansion> e_;
};

/// The swept values of each case, one per key, also on demand.
class StudyValues {
 public:
  StudyValues() = default;
  explicit StudyValues(std::shared_ptr<const Expansion> e) : e_(std::move(e)) {}
  std::size_t size() const;
  std::vector<Value> operator[](std::size_t i) const;

 private:
  std::shared_ptr<const Expansion> e_;
};

/// The expanded study: one Case per combination, with the swept values that made it.
struct Study {
  std::vector<std::string> keys;               ///< swept keys, in column order
  StudyCases cases;                            ///< finalised and validated (built on demand)
  StudyValues varied;                          ///< per case, one value per key
  std::shared_ptr<const Expansion> expansion;  ///< what cases and varied build from
  /// Apply `f` to every case as it is built (e.g. --no-continuation), after any earlier one.
  void adjust(std::function<void(Case&)> f);
};

/// Largest study expand() accepts.
inline constexpr std::size_t kMaxStudyCases = 1000000;

/// Called by expand() and fingerprint(), which build every case (seconds for the largest studies),
/// every kStudyProgressCases cases with (cases done, cases in all): a progress line; it may
/// throw to stop.
using StudyProgress = std::function<void(std::size_t done, std::size_t total)>;
inline constexpr std::size_t kStudyProgressCases = 4096;

/// Expand the product (or the zip) into finalised, validated cases, in order: product mode
/// counts like nested loops with the first factor outermost. Throws oscidrum::Error naming the
/// case and its swept values when one is invalid, or when zipped lists differ in length.
Study expand(const StudySpec& spec, const StudyProgress& progress = {});

/// A 64-bit fingerprint of the cases (every field of every case) and of `extra` (e.g. the
/// output header): a journal of a different study is never resumed.
std::uint64_t fingerprint(const Study& study, const std::string& extra,
                          const StudyProgress& progress = {});

}  // namespace oscidrum::io
