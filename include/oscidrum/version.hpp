// oscidrum/version.hpp
#pragma once

namespace oscidrum {
inline constexpr const char* version = "0.1.0";
}  // namespace oscidrum
