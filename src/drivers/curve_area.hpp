// Internal: the area enclosed by the z_M''-x_M'' curve of one recorded steady period (metrics
// `area`; docs/model.md section 8, paper Figs. 16 and 22), exact for the piecewise curve of the
// recording's interpolants (src/drivers/period_recording.hpp): the region of non-zero winding
// number, so that both lobes of a figure eight count.
#pragma once

#include <vector>

#include "drivers/period_recording.hpp"

namespace oscidrum::detail {

/// The area, by the first of the three methods below that answers: Green's theorem on the arcs
/// between the curve's self-intersections, else the polygon sweep with bulges, else refined
/// polygons extrapolated until two estimates agree to `tolerance` (relative).
double curve_area(const std::vector<recording::Piece>& pieces, double tolerance = 1e-11);

/// Green's theorem on the region's boundary: the curve cut at its self-intersections (each
/// located by Newton on the interpolants) into arcs; an arc bounds the region with it on its left
/// (c = +1), on its right (c = -1) or not at all (c = 0), decided by the winding number just to
/// its right; the area is the sum of c times the integral of x dz along each arc, exact from the
/// antiderivative of the polynomial integrand. NaN when a crossing cannot be placed, when an arc
/// has no point far enough from the crossings to decide its c, or when the c do not close into a
/// boundary at every crossing (the callers fall back).
double green_curve_area(const std::vector<recording::Piece>& pieces);

/// The polygon through a few points per piece with every self-intersection inserted as a point of
/// both branches, swept (enclosed_area with bulges: each edge inside a piece corrected by the
/// exact area between its arc and its chord). NaN when a crossing cannot be placed.
double swept_curve_area(const std::vector<recording::Piece>& pieces);

/// Polygons of the interpolants through n points per piece, n doubled and
/// Richardson-extrapolated until two estimates agree to `tolerance` (relative): the last resort
/// (see curve_area.cpp for its bounded cost).
double extrapolated_curve_area(const std::vector<recording::Piece>& pieces,
                               double tolerance = 1e-11);

}  // namespace oscidrum::detail
