// tests/io/io_test_util.hpp: what the tests of oscidrum_io share: reading a case or a study from
// TOML text, the message of an error, the comparison of two cases by the keys in effect, and a
// temporary directory.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io::test {

inline Case read(const std::string& text) {
  CaseSpec spec;
  read_case_text(text, "case.toml", spec);
  const Case c = finalize(spec);
  validate(c, spec);
  return c;
}

// The message of the oscidrum::Error that `f` throws ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline std::string case_error(const std::string& text) {
  return error_of([&] { read(text); });
}

inline std::string study_error(const std::string& text) {
  return error_of([&] { expand(read_study_text(text, "study.toml", "")); });
}

// The same case: every key in effect (key_in_effect) has the same value (a key without effect, such
// as soil.ksh under soil.input = "table2", is written as a comment and not read back).
inline bool same_case(const Case& a, const Case& b) {
  for (const Field& f : fields()) {
    if (key_in_effect(a, f.key) != key_in_effect(b, f.key)) return false;
    if (key_in_effect(a, f.key) && f.get(a) != f.get(b)) return false;
  }
  return true;
}

// A fresh temporary directory per test.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("oscidrum_test_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  static inline int counter_ = 0;
  std::filesystem::path path_;
};

}  // namespace oscidrum::io::test
