// area.hpp: internals of the enclosed area (area.cpp) used by the steady-state metrics.
#pragma once

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

namespace oscidrum::detail {

/// The pairs of edges (i, j) of the closed polygon (x, y) that cross strictly inside both (edge i
/// joins point i to point i + 1, the last edge the last point to the first). Edges meeting at a
/// shared point, and crossings exactly at the height of a point, are not reported.
std::vector<std::pair<std::size_t, std::size_t>> polygon_crossings(std::span<const double> x,
                                                                   std::span<const double> y);

/// Whether edges i and j of the closed polygon (x, y) (edge k joins point k to point k + 1, the
/// last edge the last point to the first) cross strictly inside both: the ends of each strictly on
/// either side of the other's line. polygon_crossings's pairs, one pair at a time.
bool chords_cross(std::span<const double> x, std::span<const double> y, std::size_t i,
                  std::size_t j);

/// The work of the area's slab sweep over the closed polygon (x, y): the number of (edge, slab)
/// pairs it visits, the sum over the edges of the distinct point heights each spans (O(n log n)
/// to count). The sweep's time is about proportional to it (plus its crossings): a caller that
/// refines a polygon checks it before sweeping.
std::size_t sweep_visits(std::span<const double> x, std::span<const double> y);

}  // namespace oscidrum::detail
