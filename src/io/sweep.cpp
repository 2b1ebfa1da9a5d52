// Expansion of a StudySpec into cases: cartesian product of factors or one zipped factor.
#include "oscidrum_io/sweep.hpp"

#include <cstdio>
#include <cstring>

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

Study expand(const StudySpec& spec) {
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
  std::vector<std::size_t> idx(factors.size(), 0);  // odometer, the last factor fastest
  study.cases.reserve(total);
  study.varied.reserve(total);
  for (std::size_t n = 0; n < total; ++n) {
    CaseSpec s = spec.base;
    std::vector<Value> values;
    for (std::size_t fi = 0; fi < factors.size(); ++fi)
      for (const SweepAxis& a : factors[fi].axes) values.push_back(a.values[idx[fi]]);
    try {
      std::size_t v = 0;
      for (std::size_t fi = 0; fi < factors.size(); ++fi)
        for (const SweepAxis& a : factors[fi].axes) assign(s, a.key, values[v++], a.origin);
      const Case c = finalize(s);
      validate(c, s);
      study.cases.push_back(c);
    } catch (const Error& e) {
      throw Error(describe_case(n, study.keys, values) + ": " + e.what());
    }
    study.varied.push_back(std::move(values));
    for (std::size_t fi = factors.size(); fi-- > 0;) {
      if (++idx[fi] < factors[fi].size()) break;
      idx[fi] = 0;
    }
  }
  return study;
}

std::uint64_t fingerprint(const Study& study, const std::string& extra) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  mix(h, extra.data(), extra.size());
  for (const Case& c : study.cases)
    for (const Field& f : fields()) {
      const double v = f.get(c);
      mix(h, &v, sizeof v);
    }
  return h;
}

}  // namespace oscidrum::io
