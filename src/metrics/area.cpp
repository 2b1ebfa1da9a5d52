// area.cpp: the area enclosed by the z_M''-x_M'' curve (docs/model.md section 8, paper Figs. 16,
// 22). The curve is a figure-eight or a twisted bow tie, so the signed shoelace sum would cancel
// its lobes: the area counted here is that of the points with non-zero winding number.
//
// Algorithm (a slab sweep; no pairwise edge test over the whole polygon):
//  1. Cut the plane into horizontal slabs between consecutive distinct vertex heights. Every
//     non-horizontal edge either spans a slab completely or does not enter it, so inside a slab the
//     active edges are straight lines x_e(y).
//  2. Two active edges may cross inside a slab. Their order at the bottom and at the top differ
//     exactly by the crossing pairs; an insertion sort from the bottom order to the top order
//     visits each crossing pair once (cost O(k + crossings) for k active edges). The crossing
//     heights split the slab into sub-slabs free of crossings.
//  3. In a crossing-free sub-slab the left-to-right order of the edges is fixed. Walking left to
//     right, the winding number changes by +-1 at each edge (sign = edge direction). The region
//     between two neighbouring edges is a trapezoid whose area is exactly
//     height * (x_right(y_mid) - x_left(y_mid)) for straight edges; it counts if the winding
//     there is non-zero.
// Cost: O(n log n) to sort, O(k) per slab (the edges stay in the order of the slab below, which an
// insertion sort repairs) and O(k log k) more per crossing, so O(n k + c k log k) for c crossings.
// The drum curves have k of a handful and a few crossings per period (4096 vertices: well under a
// millisecond); only contrived stars with ~n^2 crossings are slow (a {1001/400} star takes about
// two seconds). Curves (enclosed_area with bulges): the same sweep also records, for every edge,
// where it bounds the region (winding zero on one side, non-zero on the other; c = +1 with the
// region on its left, -1 on its right, 0 elsewhere, as a fraction of the edge's height). The region
// enclosed by the curve differs from the polygon's by the segment between each such edge and its
// arc, so the curve's area is the polygon's plus the sum of c times bulge (Green's theorem on the
// region's boundary: bulge = integral of x dy along the arc minus along the chord).
// polygon_crossings (area.hpp) reports the crossing edge pairs the sweep meets; sweep_visits its
// work, before it runs.
#include "metrics/area.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"

namespace oscidrum {

namespace {

/// A non-horizontal polygon edge, stored bottom (y0) to top (y1), y0 < y1.
struct Edge {
  double x0, y0, x1, y1;
  double dxdy;        ///< (x1 - x0) / (y1 - y0)
  int direction;      ///< +1: traversed upwards, -1: downwards
  std::size_t index;  ///< the edge joins point index and index + 1 (the last: to the first)

  /// x on the edge's line at height y; exact at both end points, so that edges sharing a vertex
  /// agree there, and monotonic in y.
  double x_at(double y) const {
    if (y <= y0) return x0;
    if (y >= y1) return x1;
    return x0 + (y - y0) * dxdy;
  }
};

/// The left-to-right walk over the edges of a crossing-free slab of height `height`, by_x their x
/// at mid-height in increasing order: the area with non-zero winding, and the boundary
/// coefficients (see crossing_free_slab_area).
double walk_slab(const std::vector<std::pair<double, const Edge*>>& by_x, double height,
                 std::vector<double>* boundary) {
  double width = 0.0;
  int winding = 0;
  for (std::size_t i = 0; i + 1 < by_x.size(); ++i) {
    const int before = winding;
    winding += by_x[i].second->direction;
    if (boundary != nullptr) {
      // Going up, the edge's left is the side of smaller x; going down, the side of larger x.
      const bool left = (by_x[i].second->direction > 0 ? before : winding) != 0;
      const bool right = (by_x[i].second->direction > 0 ? winding : before) != 0;
      (*boundary)[by_x[i].second->index] += height * (int{left} - int{right});
    }
    // The integral of a linear width over the slab is the height times the width at mid-height.
    if (winding != 0) width += by_x[i + 1].first - by_x[i].first;
  }
  if (boundary != nullptr && !by_x.empty()) {
    // The rightmost edge: winding 0 to its right (x), `winding` to its left.
    const Edge* e = by_x.back().second;
    const bool inside = winding != 0;
    (*boundary)[e->index] += height * (e->direction > 0 ? int{inside} : -int{inside});
  }
  return height * width;
}

/// Area with non-zero winding between heights lo < hi, where the order of `active` by x is the
/// same at every height inside (lo, hi). `scratch` holds x at mid-height for sorting.
/// If `boundary` is not null, boundary[e.index] accumulates height * c for every edge, with
/// c = [winding on the edge's left != 0] - [winding on its right != 0] (left and right seen along
/// the edge's direction): +1 or -1 where the edge bounds the enclosed region, 0 inside or outside.
double crossing_free_slab_area(std::span<const Edge* const> active, double lo, double hi,
                               std::vector<std::pair<double, const Edge*>>& scratch,
                               std::vector<double>* boundary) {
  const double height = hi - lo;
  if (!(height > 0.0)) return 0.0;
  const double mid = lo + 0.5 * height;
  scratch.clear();
  for (const Edge* e : active) scratch.emplace_back(e->x_at(mid), e);
  std::sort(scratch.begin(), scratch.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return walk_slab(scratch, height, boundary);
}

/// An active edge with its x at the bottom and the top of the slab.
struct Spanning {
  const Edge* edge;
  double lo, hi;
};

/// Buffers reused from slab to slab (the sweep allocates only while they grow).
struct Workspace {
  std::vector<Spanning> bottom, order;
  std::vector<double> cuts;
  std::vector<std::pair<double, const Edge*>> by_x;
  std::vector<double>* boundary = nullptr;  ///< see crossing_free_slab_area (optional)
  std::vector<std::pair<std::size_t, std::size_t>>* crossings = nullptr;  ///< (optional)
  bool area = true;  ///< false: only the crossings are wanted
};

/// Area with non-zero winding inside the slab [lo, hi] (every active edge spans it). `active` is
/// left in the bottom order, which is nearly that of the next slab up.
double slab_area(std::vector<const Edge*>& active, double lo, double hi, Workspace& ws) {
  // Bottom order: x at lo, ties broken by x at hi (edges sharing a vertex at lo are ordered by
  // where they go, so they do not count as crossing). An insertion sort: `active` comes in the
  // order of the slab below, with the edges that start at lo appended.
  std::vector<Spanning>& bottom = ws.bottom;
  bottom.clear();
  for (const Edge* e : active) bottom.push_back({e, e->x_at(lo), e->x_at(hi)});
  for (std::size_t i = 1; i < bottom.size(); ++i) {
    const Spanning key = bottom[i];
    std::size_t j = i;
    for (; j > 0 &&
           (key.lo != bottom[j - 1].lo ? key.lo < bottom[j - 1].lo : key.hi < bottom[j - 1].hi);
         --j)
      bottom[j] = bottom[j - 1];
    bottom[j] = key;
  }
  for (std::size_t i = 0; i < bottom.size(); ++i) active[i] = bottom[i].edge;
  // Without a crossing the bottom order holds throughout the slab, and x at mid-height is the
  // mean of the ends (the edges are straight).
  bool crossing = false;
  for (std::size_t i = 1; i < bottom.size() && !crossing; ++i)
    crossing = bottom[i - 1].hi > bottom[i].hi;
  if (!crossing) {
    if (!ws.area) return 0.0;
    ws.by_x.clear();
    for (const Spanning& b : bottom) ws.by_x.emplace_back(0.5 * (b.lo + b.hi), b.edge);
    return walk_slab(ws.by_x, hi - lo, ws.boundary);
  }
  // Insertion sort by x at hi (strict comparison: edges meeting at hi do not cross inside).
  // Each swap exchanges a pair whose order differs at lo and hi: a crossing strictly inside.
  std::vector<double>& cuts = ws.cuts;
  std::vector<Spanning>& order = ws.order;
  cuts.clear();
  order.assign(bottom.begin(), bottom.end());
  for (std::size_t i = 1; i < order.size(); ++i) {
    for (std::size_t j = i; j > 0 && order[j - 1].hi > order[j].hi; --j) {
      const Spanning& left = order[j - 1];  // left at lo, right at hi
      const Spanning& right = order[j];
      const double gap_lo = right.lo - left.lo;     // >= 0
      const double gap_hi = right.hi - left.hi;     // < 0
      const double s = gap_lo / (gap_lo - gap_hi);  // in [0, 1)
      cuts.push_back(lo + std::clamp(s, 0.0, 1.0) * (hi - lo));
      if (ws.crossings != nullptr) ws.crossings->emplace_back(left.edge->index, right.edge->index);
      std::swap(order[j - 1], order[j]);
    }
  }
  if (!ws.area) return 0.0;
  std::sort(cuts.begin(), cuts.end());
  double area = 0.0;
  double below = lo;
  for (double cut : cuts) {
    area += crossing_free_slab_area(active, below, cut, ws.by_x, ws.boundary);
    below = std::max(below, cut);
  }
  area += crossing_free_slab_area(active, below, hi, ws.by_x, ws.boundary);
  return area;
}

}  // namespace

namespace {

void check_points(const char* who, std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) {
    throw Error(std::string(who) + ": x and y must have the same size; got " +
                std::to_string(x.size()) + " and " + std::to_string(y.size()));
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw Error(std::string(who) + ": the points must be finite; point " + std::to_string(i) +
                  " is (" + std::to_string(x[i]) + ", " + std::to_string(y[i]) + ")");
    }
  }
}

/// The slab sweep over the polygon (x, y); fills ws.boundary (one entry per edge, summed
/// height * c) and ws.crossings when they are set.
double sweep(std::span<const double> x, std::span<const double> y, Workspace& ws) {
  const std::size_t n = x.size();
  if (n < 3) return 0.0;

  // Horizontal edges (and repeated points) bound no slab and change no winding: skip them.
  std::vector<Edge> edges;
  edges.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1 == n) ? 0 : i + 1;
    if (y[i] < y[k]) {
      edges.push_back({x[i], y[i], x[k], y[k], (x[k] - x[i]) / (y[k] - y[i]), +1, i});
    } else if (y[i] > y[k]) {
      edges.push_back({x[k], y[k], x[i], y[i], (x[i] - x[k]) / (y[i] - y[k]), -1, i});
    }
  }
  if (edges.size() < 2) return 0.0;
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.y0 < b.y0; });

  std::vector<double> levels(y.begin(), y.end());
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());

  std::vector<const Edge*> active;
  std::size_t next_edge = 0;
  double area = 0.0;
  for (std::size_t s = 0; s + 1 < levels.size(); ++s) {
    const double lo = levels[s], hi = levels[s + 1];
    // Edges end only at vertex heights, so an active edge with y1 > lo spans [lo, hi].
    std::erase_if(active, [lo](const Edge* e) { return e->y1 <= lo; });
    while (next_edge < edges.size() && edges[next_edge].y0 <= lo) {
      active.push_back(&edges[next_edge]);
      ++next_edge;
    }
    if (active.size() >= 2) area += slab_area(active, lo, hi, ws);
  }
  return area;
}

/// Winding number (counter-clockwise positive) of the closed polygon (x, y) around (px, py).
int winding_number(std::span<const double> x, std::span<const double> y, double px, double py) {
  int w = 0;
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1 == n) ? 0 : i + 1;
    const double cross = (x[k] - x[i]) * (py - y[i]) - (px - x[i]) * (y[k] - y[i]);
    if (y[i] <= py && y[k] > py && cross > 0.0) ++w;
    if (y[i] > py && y[k] <= py && cross < 0.0) --w;
  }
  return w;
}

}  // namespace

double enclosed_area(std::span<const double> x, std::span<const double> y) {
  check_points("enclosed_area", x, y);
  Workspace ws;
  return sweep(x, y, ws);
}

double enclosed_area(std::span<const double> x, std::span<const double> y,
                     std::span<const double> bulge) {
  check_points("enclosed_area", x, y);
  if (bulge.size() != x.size()) {
    throw Error("enclosed_area: bulge must have one entry per point (arc); got " +
                std::to_string(bulge.size()) + " for " + std::to_string(x.size()) + " points");
  }
  const std::size_t n = x.size();
  if (n < 2) return 0.0;
  std::vector<double> boundary(n, 0.0);
  Workspace ws;
  ws.boundary = &boundary;
  double area = sweep(x, y, ws);
  // Each arc changes the area by its bulge where its chord bounds the region (c = +-1; 0 where
  // both sides are inside or both outside), weighted by the part of the chord's height where it
  // does (all or nothing when every crossing of the curve is one of the points).
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) scale = std::max({scale, std::abs(x[i]), std::abs(y[i])});
  for (std::size_t i = 0; i < n; ++i) {
    if (bulge[i] == 0.0) continue;
    const std::size_t k = (i + 1 == n) ? 0 : i + 1;
    const double height = std::abs(y[k] - y[i]);
    if (height > 0.0) {
      area += bulge[i] * boundary[i] / height;
    } else if (x[k] != x[i]) {
      // A horizontal chord bounds no slab: the windings just above and below its middle.
      const double mx = 0.5 * (x[i] + x[k]), eps = 1e-9 * scale;
      const int above = winding_number(x, y, mx, y[i] + eps);
      const int below = winding_number(x, y, mx, y[i] - eps);
      // Going right (x[k] > x[i]) the left is above.
      const int left = x[k] > x[i] ? above : below, right = x[k] > x[i] ? below : above;
      area += bulge[i] * (int{left != 0} - int{right != 0});
    }
  }
  return area;
}

std::vector<std::pair<std::size_t, std::size_t>> detail::polygon_crossings(
    std::span<const double> x, std::span<const double> y) {
  check_points("polygon_crossings", x, y);
  std::vector<std::pair<std::size_t, std::size_t>> crossings;
  Workspace ws;
  ws.crossings = &crossings;
  ws.area = false;
  sweep(x, y, ws);
  return crossings;
}

bool detail::chords_cross(std::span<const double> x, std::span<const double> y, std::size_t i,
                          std::size_t j) {
  const std::size_t n = x.size(), i1 = (i + 1) % n, j1 = (j + 1) % n;
  const auto side = [&](std::size_t a, std::size_t b, std::size_t c) {  // of c from a -> b
    return (x[b] - x[a]) * (y[c] - y[a]) - (y[b] - y[a]) * (x[c] - x[a]);
  };
  const double sj0 = side(i, i1, j), sj1 = side(i, i1, j1);
  if (!((sj0 < 0.0 && sj1 > 0.0) || (sj0 > 0.0 && sj1 < 0.0))) return false;
  const double si0 = side(j, j1, i), si1 = side(j, j1, i1);
  return (si0 < 0.0 && si1 > 0.0) || (si0 > 0.0 && si1 < 0.0);
}

std::size_t detail::sweep_visits(std::span<const double> x, std::span<const double> y) {
  check_points("sweep_visits", x, y);
  const std::size_t n = x.size();
  if (n < 3) return 0;
  std::vector<double> levels(y.begin(), y.end());
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  auto level = [&](double h) {
    return static_cast<std::size_t>(std::lower_bound(levels.begin(), levels.end(), h) -
                                    levels.begin());
  };
  std::size_t visits = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1 == n) ? 0 : i + 1;
    const std::size_t a = level(y[i]), b = level(y[k]);
    visits += a > b ? a - b : b - a;
  }
  return visits;
}

}  // namespace oscidrum
