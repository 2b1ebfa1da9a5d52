// oscidrum/error.hpp: the one exception root of the library.
#pragma once

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace oscidrum {

/// Every error the library raises. Messages name the field, the rule and the value received,
/// e.g. "soil.G must be > 0 [Pa]; got -5e+06". An error about one parameter carries its key
/// ("soil.G") and, when it is a number, the value received, so that front ends can point at the
/// input without reading the message.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  Error(const std::string& message, std::string key,
        double value = std::numeric_limits<double>::quiet_NaN())
      : std::runtime_error(message), key_(std::move(key)), value_(value) {}

  /// The same error with `prefix` before its message ("case.toml:3:1: "), key and value kept.
  Error prefixed(const std::string& prefix) const { return Error(prefix + what(), key_, value_); }

  /// The key of the parameter the error is about ("soil.G"), or "" if it is about no one key.
  const std::string& key() const { return key_; }
  /// The value received [unit of the key], or NaN if there is none (or it is not a number).
  double value() const { return value_; }

 private:
  std::string key_;
  double value_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace oscidrum
