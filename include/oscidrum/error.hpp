// oscidrum/error.hpp: the one exception root of the library.
#pragma once

#include <stdexcept>
#include <string>

namespace oscidrum {

/// Every error the library raises. Messages name the field, the rule and the value received,
/// e.g. "soil.G must be > 0 [Pa]; got -5e+06".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace oscidrum
