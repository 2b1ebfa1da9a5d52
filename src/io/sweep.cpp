// Expansion of a StudySpec into cases: cartesian product of factors or one zipped factor.
#include "oscidrum_io/sweep.hpp"

#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"

namespace oscidrum::io {
namespace {

std::string describe_case(std::size_t index, const std::vector<std::string>& keys,
                          const std::vector<Value>& values) {
  std::string s = "case " + std::to_string(index) + " (";
  for (std::size_t i = 0; i < keys.size(); ++i)
    s += (i ? ", " : "") + keys[i] + " = " + format_value(values[i]);
  return s + ")";
}

// FNV-1a, 64 bit.
void mix(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
}

}  // namespace

class Expansion {
 public:
  CaseSpec base;
  std::vector<SweepFactor> factors;  // zip mode: one factor holding every axis
  std::size_t total = 0;
  std::function<void(Case&)> adjust;

  // The factor indices of case n: an odometer, the last factor fastest.
  std::vector<std::size_t> digits(std::size_t n) const {
    std::vector<std::size_t> idx(factors.size(), 0);
    for (std::size_t fi = factors.size(); fi-- > 0;) {
      idx[fi] = n % factors[fi].size();
      n /= factors[fi].size();
    }
    return idx;
  }
  std::vector<Value> values(std::size_t n) const {
    const std::vector<std::size_t> idx = digits(n);
    std::vector<Value> v;
    for (std::size_t fi = 0; fi < factors.size(); ++fi)
      for (const SweepAxis& a : factors[fi].axes) v.push_back(a.values[idx[fi]]);
    return v;
  }
  // The finalised case n (validated with `check`).
  Case build(std::size_t n, bool check) const {
    CaseSpec s = base;
    const std::vector<std::size_t> idx = digits(n);
    for (std::size_t fi = 0; fi < factors.size(); ++fi)
      for (const SweepAxis& a : factors[fi].axes) assign(s, a.key, a.values[idx[fi]], a.origin);
    Case c = finalize(s);
    if (check) validate(c, s);
    if (adjust) adjust(c);
    return c;
  }
};

std::size_t StudyCases::size() const { return e_ ? e_->total : 0; }
Case StudyCases::operator[](std::size_t i) const { return e_->build(i, false); }
Case StudyCases::at(std::size_t i) const {
  if (i >= size())
    throw std::out_of_range("study case " + std::to_string(i) + " of " + std::to_string(size()));
  return (*this)[i];
}
std::size_t StudyValues::size() const { return e_ ? e_->total : 0; }
std::vector<Value> StudyValues::operator[](std::size_t i) const { return e_->values(i); }

void Study::adjust(std::function<void(Case&)> f) {
  auto e = std::make_shared<Expansion>(*expansion);
  if (e->adjust) {
    e->adjust = [g = e->adjust, f = std::move(f)](Case& c) { g(c), f(c); };
  } else {
    e->adjust = std::move(f);
  }
  expansion = e;
  cases = StudyCases(e);
  varied = StudyValues(e);
}

Study expand(const StudySpec& spec, const StudyProgress& progress) {
  std::vector<SweepFactor> factors = spec.factors;
  if (factors.empty())
    throw Error(spec.source +
                ": [sweep] names no parameter to vary; add e.g. "
                "\"soil.table2_G\" = \"all\" (see docs/config.md)");
  if (spec.mode == SweepMode::zip && factors.size() > 1) {
    SweepFactor all;
    for (const SweepFactor& f : factors)
      all.axes.insert(all.axes.end(), f.axes.begin(), f.axes.end());
    factors = {all};
  }
  Study study;
  for (const SweepFactor& f : factors) {
    for (const SweepAxis& a : f.axes) {
      if (a.values.empty())
        throw Error(a.origin + ": sweep list " + a.key + " is empty; give at least one value");
      if (a.values.size() != f.size())
        throw Error(a.origin + ": zipped sweep lists must have equal lengths; " + a.key + " has " +
                    std::to_string(a.values.size()) + " values, " + f.axes.front().key + " has " +
                    std::to_string(f.size()));
      for (const std::string& k : study.keys)
        if (k == a.key) throw Error(a.origin + ": " + a.key + " is swept twice");
      study.keys.push_back(a.key);
    }
  }
  for (const std::string& k : study.keys)
    if (k == "soil.G")
      for (const std::string& other : study.keys)
        if (other == "soil.table2_G")
          throw Error(spec.source + ": sweep either soil.G or soil.table2_G, not both");

  std::size_t total = 1;
  for (const SweepFactor& f : factors) {
    if (total > kMaxStudyCases / f.size())
      throw Error(spec.source + ": the sweep has more than " + std::to_string(kMaxStudyCases) +
                  " cases; split it");
    total *= f.size();
  }
  auto e = std::make_shared<Expansion>();
  e->base = spec.base;
  e->factors = std::move(factors);
  e->total = total;
  // Every case is built and validated now, before anything runs; then only its recipe is kept.
  for (std::size_t n = 0; n < total; ++n) {
    if (progress && n % kStudyProgressCases == 0 && n > 0) progress(n, total);
    try {
      (void)e->build(n, true);
    } catch (const Error& err) {
      throw Error(describe_case(n, study.keys, e->values(n)) + ": " + err.what());
    }
  }
  study.expansion = e;
  study.cases = StudyCases(e);
  study.varied = StudyValues(e);
  return study;
}

std::uint64_t fingerprint(const Study& study, const std::string& extra,
                          const StudyProgress& progress) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  mix(h, extra.data(), extra.size());
  const std::size_t total = study.cases.size();
  for (std::size_t n = 0; n < total; ++n) {
    if (progress && n % kStudyProgressCases == 0 && n > 0) progress(n, total);
    const Case c = study.cases[n];
    for (const Field& f : fields()) {
      const double v = f.get(c);
      mix(h, &v, sizeof v);
    }
  }
  return h;
}

}  // namespace oscidrum::io
