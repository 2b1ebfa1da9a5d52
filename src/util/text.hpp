// Internal: text helpers for messages ("did you mean ..."), shared by the core and oscidrum_io.
#pragma once

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string_view>
#include <vector>

namespace oscidrum::detail {

/// Levenshtein distance ignoring ASCII case.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// The part of a dotted key after its last dot ("contact.mu" -> "mu").
inline std::string_view key_last_part(std::string_view key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

/// The key of `keys` a user most likely meant by `key`, or an empty view: 1. the same name in
/// another (or no) section, any case ("G" -> "soil.G", "soil.g" -> "soil.G", "M0" ->
/// "roller.M0"); 2. a near miss, at most one edit per four characters and at most three, against
/// the whole key or, for a key without a section, against each key's name in its section ("muu"
/// -> "contact.mu", where the whole keys' nearest was "MMd").
inline std::string_view closest_key(std::string_view key,
                                    const std::vector<std::string_view>& keys) {
  const auto same = [](std::string_view a, std::string_view b) {
    return a.size() == b.size() && edit_distance(a, b) == 0;  // equal ignoring ASCII case
  };
  for (std::string_view k : keys)
    if (k == key) return k;
  for (std::string_view k : keys)
    if (same(k, key)) return k;
  for (std::string_view k : keys)
    if (key_last_part(k) == key_last_part(key)) return k;
  for (std::string_view k : keys)
    if (same(key_last_part(k), key_last_part(key))) return k;
  std::string_view best;
  std::size_t best_d = std::clamp<std::size_t>(key.size() / 4, 1, 3) + 1;
  const bool bare = key.find('.') == std::string_view::npos;
  for (std::string_view k : keys) {
    std::size_t d = edit_distance(key, k);
    if (bare) d = std::min(d, edit_distance(key, key_last_part(k)));
    if (d < best_d) best_d = d, best = k;
  }
  return best;
}

}  // namespace oscidrum::detail
