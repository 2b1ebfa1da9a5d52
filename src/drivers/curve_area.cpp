// curve_area.cpp: the area enclosed by the z_M''-x_M'' curve of a recorded steady period
// (curve_area.hpp; docs/model.md section 8, paper Figs. 16 and 22).
//
// The curve is piecewise: on each piece (an integrator step in one phase) x_M'' and z_M'' are
// Chebyshev interpolants in t, accurate to round-off; where a switch makes the accelerations jump,
// a straight segment joins the end of one piece to the start of the next. The area counted is that
// of the points with non-zero winding number (a figure eight's two lobes both count).
//
// Green's theorem (green_curve_area, the method used first): the region R = {w != 0} is bounded by
// the arcs of the curve between its self-intersections, each traversed with R on its left, so that
// area(R) = sum over the arcs of c times the integral of x dz along the arc, where
// c = [w just left of the arc != 0] - [w just right of it != 0] is +1, -1 or 0 and constant along
// an arc (the winding number changes only across the curve). Crossing the curve from its right to
// its left raises w by one, so c follows from one winding number per arc, that just to its right,
// counted along a ray from a point of the arc (a polygon vertex inside a piece, away from the
// crossings) over the polygon through the pieces. The integrals are exact: on a piece, x dz/dt is
// a polynomial whose antiderivative is summed at the arc's ends (BulgeSeries); on a straight
// segment the trapezoid. Where a point is nearer another branch than that branch's chord may stray
// from its arc, the arc itself is counted along the ray. An arc none of whose points can tell
// takes its c from the boundary's closing at one of its crossings (the c of the two arcs arriving
// sum to those of the two leaving); a loop of round-off's size that no crossing decides is left
// out. Checks: at every crossing the boundary must close; a curve without crossings must have
// c = +-1; the area must not be negative. Any failure, or a crossing that Newton cannot place on
// the arcs, leaves the area to the sweep below.
//
// The sweep (swept_curve_area): a polygon through kAreaPoints + 1 points per piece with every
// self-intersection inserted as a point of both branches, swept by enclosed_area with the exact
// area between each arc and its chord (bulges). Where Newton cannot place a crossing of two chords
// on the arcs (a sharp corner where two pieces join), polygons of the interpolants, n points per
// piece doubled and Richardson-extrapolated to 1e-11 (extrapolated_curve_area). The three agree to
// round-off (tests/drivers/test_curve_area.cpp).
//
// Crossings are found where two chords of the polygon cross, and also where two chords that do
// not cross come closer than a bound on how far their arcs stray from them (a small loop, or a
// shallow crossing drawn by long pieces, can cross on the arcs between chords that pass each
// other; Newton from several starts, as two arcs that bulge past each other cross twice). Both
// kinds come from one broad phase, near_pairs (boxes of the pieces' edges, swept in z).
// Not found: a loop made within two consecutive polygon edges (a quarter of a piece each, or the
// two sides of a switch where the accelerations are continuous); its area, a few 1e-9 of the
// figure's where seen on steady periods, is then missing.
#include "drivers/curve_area.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "metrics/area.hpp"
#include "metrics/piece_interpolant.hpp"
#include "oscidrum/metrics.hpp"

namespace oscidrum::detail {
namespace {

using recording::kDegree;
using recording::Piece;
using enum recording::Quantity;

constexpr int kAreaPoints = 8;  // polygon points per piece for the area (the arcs are exact)

// The fallback: polygons through n points per piece of the interpolants, n doubled and
// Richardson-extrapolated (error ~ n^-2) until two estimates agree to `tolerance` relative (1e-11
// for the default integration; looser for a looser one, see steady_metrics.cpp), or until the
// sweep of the next polygon would cost more than kFallbackVisits (edge, slab) visits (area.hpp,
// sweep_visits; always at least n = 8, one extrapolation). A period of thousands of pieces (10 000
// at 0.1 Hz), or a curve that winds thousands of times around one place (a drum barely excited:
// the accelerations ring down after each switch), must not be refined to 4096 points per piece
// (millions of points, each slab crossed by thousands of edges: seconds to minutes). Then the last
// extrapolation stands, with an error of the order of its difference from the one before (7e-9
// relative for the paper's roller at 0.1 Hz, tests/drivers/test_steady_metrics.cpp).
constexpr std::size_t kFallbackVisits = 30'000'000;

double extrapolated_area(const std::vector<Piece>& pieces, double tolerance) {
  double previous = std::numeric_limits<double>::quiet_NaN(), coarse = 0.0, area = 0.0;
  std::vector<double> x, z;
  for (int n = 4; n <= (1 << 12); n *= 2) {
    x.clear();
    z.clear();
    for (const Piece& pc : pieces) {
      for (int k = 0; k <= n; ++k) {
        const double t = k == n ? pc.b : pc.a + (pc.b - pc.a) * k / n;
        x.push_back(pc.f[kDdx](t));
        z.push_back(pc.f[kDdz](t));
      }
    }
    if (n > 8 && detail::sweep_visits(x, z) > kFallbackVisits) break;
    const double fine = enclosed_area(x, z);
    if (n > 4) {
      area = (4.0 * fine - coarse) / 3.0;
      if (std::abs(area - previous) <= tolerance * std::abs(area)) break;
      previous = area;
    }
    coarse = fine;
  }
  return area;
}
// A polygon vertex on the curve: the point of piece `piece` at time t (or, for a crossing, the
// point shared by both branches).
struct Vertex {
  int piece;
  double t;       // [s]
  double x, z;    // x_M'', z_M'' [m/s^2]
  bool crossing;  // a self-intersection (x, z shared with the other branch)
};

// A point of an edge as a function of its parameter: an arc edge (both ends in one piece) by its
// time, a straight edge between pieces by s in [0, 1].
struct EdgeCurve {
  const Piece* piece;  // null: straight
  double u0, u1;       // parameter range of the edge (t, or 0 and 1)
  double x0, z0, x1, z1;
  std::array<double, 2> at(double u) const {
    if (piece != nullptr) return {piece->f[kDdx](u), piece->f[kDdz](u)};
    return {x0 + u * (x1 - x0), z0 + u * (z1 - z0)};
  }
  std::array<double, 2> tangent(double u) const {
    if (piece != nullptr) return {piece->dx(u), piece->dz(u)};
    return {x1 - x0, z1 - z0};
  }
  // Newton may move into the neighbouring edges of the same piece (the interpolant holds on the
  // whole piece) and a little past its ends: a crossing at the point where two pieces join (the
  // end of one, the start of the next, one point when no switch lies between them) lies there up
  // to round-off. A straight edge only slightly past its ends.
  bool admissible(double u) const {
    if (piece != nullptr) {
      const double slack = 1e-5 * (piece->b - piece->a);
      return u >= piece->a - slack && u <= piece->b + slack;
    }
    return u >= -1e-9 && u <= 1.0 + 1e-9;
  }
  double clamp(double u) const {
    return piece != nullptr ? std::clamp(u, piece->a, piece->b) : std::clamp(u, 0.0, 1.0);
  }
};

EdgeCurve edge_curve(const std::vector<Piece>& pieces, const std::vector<Vertex>& v,
                     std::size_t i) {
  const Vertex& p = v[i];
  const Vertex& q = v[(i + 1) % v.size()];
  if (p.piece == q.piece && q.t > p.t) return {&pieces[p.piece], p.t, q.t, p.x, p.z, q.x, q.z};
  return {nullptr, 0.0, 1.0, p.x, p.z, q.x, q.z};
}

// Newton on e(u) = g(w) from the start (u, w). False if it does not converge inside the edges'
// pieces.
bool newton_crossing(const EdgeCurve& e, const EdgeCurve& g, double& u, double& w) {
  for (int it = 0; it < 30; ++it) {
    const auto pe = e.at(u), pg = g.at(w), te = e.tangent(u), tg = g.tangent(w);
    const double fx = pe[0] - pg[0], fz = pe[1] - pg[1];
    const double d = te[0] * (-tg[1]) - te[1] * (-tg[0]);
    if (d == 0.0 || !std::isfinite(d)) return false;
    const double du = -(fx * (-tg[1]) - fz * (-tg[0])) / d;
    const double dw = -(te[0] * fz - te[1] * fx) / d;
    u += du;
    w += dw;
    if (!e.admissible(u) || !g.admissible(w)) return false;
    const double scale_u = e.piece != nullptr ? e.piece->b - e.piece->a : 1.0;
    const double scale_w = g.piece != nullptr ? g.piece->b - g.piece->a : 1.0;
    // Quadratic convergence: a step of 1e-10 leaves ~1e-20, below the round-off of the points.
    if (std::abs(du) <= 1e-10 * scale_u && std::abs(dw) <= 1e-10 * scale_w) return true;
  }
  return false;
}

// The crossing of the curve near the crossing chords e and g: Newton on e(u) = g(w) from the
// chords' crossing. False if it does not converge inside the edges' pieces.
bool locate_crossing(const EdgeCurve& e, const EdgeCurve& g, double& u, double& w) {
  // The chords' crossing: fractions along each chord.
  const double ax = e.x1 - e.x0, az = e.z1 - e.z0, bx = g.x1 - g.x0, bz = g.z1 - g.z0;
  const double det = ax * (-bz) - az * (-bx);
  if (det == 0.0) return false;
  const double rx = g.x0 - e.x0, rz = g.z0 - e.z0;
  const double se = (rx * (-bz) - rz * (-bx)) / det, sg = (ax * rz - az * rx) / det;
  u = e.u0 + se * (e.u1 - e.u0);
  w = g.u0 + sg * (g.u1 - g.u0);
  return newton_crossing(e, g, u, w);
}

// Whether the arcs meet at an angle where e(u) = g(w): at parallel tangents they touch, or, near
// the joint of two pieces, one arc's interpolant continued past its end runs along the other (a
// solution of Newton's equations that is no crossing of the curve).
bool transversal(const EdgeCurve& e, const EdgeCurve& g, double u, double w) {
  const auto te = e.tangent(u), tg = g.tangent(w);
  const double cross = te[0] * tg[1] - te[1] * tg[0];
  return std::abs(cross) > 1e-6 * std::hypot(te[0], te[1]) * std::hypot(tg[0], tg[1]);
}

// The fractions (se, sg) along chords e and g of their closest points, and the squared distance
// between them.
double closest_points(const EdgeCurve& e, const EdgeCurve& g, double& se, double& sg) {
  const double ax = e.x1 - e.x0, az = e.z1 - e.z0, bx = g.x1 - g.x0, bz = g.z1 - g.z0;
  const double rx = e.x0 - g.x0, rz = e.z0 - g.z0;
  const double aa = ax * ax + az * az, bb = bx * bx + bz * bz, ab = ax * bx + az * bz;
  const double ar = ax * rx + az * rz, br = bx * rx + bz * rz;
  const auto point_on_g = [&](double s_e) {  // the closest point of g to e(s_e), clamped
    return bb > 0.0 ? std::clamp((ab * s_e + br) / bb, 0.0, 1.0) : 0.0;
  };
  const auto point_on_e = [&](double s_g) {
    return aa > 0.0 ? std::clamp((ab * s_g - ar) / aa, 0.0, 1.0) : 0.0;
  };
  const double den = aa * bb - ab * ab;
  se = den > 0.0 ? std::clamp((ab * br - bb * ar) / den, 0.0, 1.0) : 0.0;
  sg = point_on_g(se);
  se = point_on_e(sg);
  sg = point_on_g(se);
  const double dx = rx + se * ax - sg * bx, dz = rz + se * az - sg * bz;
  return dx * dx + dz * dz;
}

// How far the arc of edge i may stray from its chord: twice the distance of the arc's middle
// from the chord's (an arc of a few degrees' turn is nearly a parabola, whose largest distance
// from its chord is at its middle), plus `tiny`; `tiny` for the straight segments.
double arc_deviation(const EdgeCurve& e, double tiny) {
  if (e.piece == nullptr) return tiny;
  const auto mid = e.at(0.5 * (e.u0 + e.u1));
  const double dx = mid[0] - 0.5 * (e.x0 + e.x1), dz = mid[1] - 0.5 * (e.z0 + e.z1);
  return 2.0 * std::sqrt(dx * dx + dz * dz) + tiny;
}

// The integral of (x - c) dz/dt over t on one piece, x = x_M'' and z = z_M'' its interpolants and
// c the mean coefficient of x (so that the integrand is of the size of the piece's variation): the
// product of the Chebyshev series of x - c (degree kDegree) and dz/dt (kDegree - 1),
// T_i T_j = (T_(i+j) + T_|i-j|) / 2, and its antiderivative G in u = (2 t - a - b) / (b - a)
// (integral of T_k = T_(k+1) / (2 (k + 1)) - T_(k-1) / (2 (k - 1))), exact up to round-off.
class BulgeSeries {
 public:
  static constexpr int kG = 2 * kDegree;  // degree of G
  BulgeSeries() = default;
  explicit BulgeSeries(const Piece& pc) : a_(pc.a), b_(pc.b) {
    const auto& c = pc.f[kDdx].coefficients();
    const auto& d = pc.dz.coefficients();
    x_offset_ = c[0];
    std::array<double, kG> product{};  // degree 2 kDegree - 1
    for (int i = 1; i <= kDegree; ++i) {
      for (int j = 0; j < kDegree; ++j) {
        const double h = 0.5 * c[i] * d[j];
        product[i + j] += h;
        product[std::abs(i - j)] += h;
      }
    }
    g_[0] = 0.0;  // the constant cancels in differences
    for (int k = 1; k <= kG; ++k) {
      const double below = k == 1 ? 2.0 * product[0] : product[k - 1];
      const double above = k + 1 < kG ? product[k + 1] : 0.0;
      g_[k] = (below - above) / (2.0 * k);
    }
  }
  double x_offset() const { return x_offset_; }
  // The integral from t0 to t1 (both in the piece), from G(t0) and G(t1).
  double integral(double G0, double G1) const { return 0.5 * (b_ - a_) * (G1 - G0); }
  // The antiderivative at t (in u; times (b - a) / 2 it is in t).
  double G(double t) const { return detail::chebyshev_sum(g_, (2.0 * t - a_ - b_) / (b_ - a_)); }

 private:
  double a_ = 0.0, b_ = 1.0, x_offset_ = 0.0;
  std::array<double, kG + 1> g_{};
};

// The polygon: kAreaPoints + 1 points per piece, vertex p (kAreaPoints + 1) + k the k-th of piece
// p.
std::vector<Vertex> polygon(const std::vector<Piece>& pieces) {
  std::vector<Vertex> v;
  v.reserve(pieces.size() * (kAreaPoints + 1));
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const Piece& pc = pieces[p];
    for (int k = 0; k <= kAreaPoints; ++k) {
      const double t = k == kAreaPoints ? pc.b : pc.a + (pc.b - pc.a) * k / kAreaPoints;
      // The ends from the exact node values, not the interpolant (which reproduces them only to
      // an ulp): where two pieces join without a switch both evaluate the same state, and the
      // shared point must be the same bit for bit. One ulp apart, the chords on either side of a
      // turning point of the curve would cross at the joint, a crossing that is not one.
      const int node = k == 0 ? kDegree : k == kAreaPoints ? 0 : -1;
      const double x = node >= 0 ? pc.values[kDdx][node] : pc.f[kDdx](t);
      const double z = node >= 0 ? pc.values[kDdz][node] : pc.f[kDdz](t);
      v.push_back({static_cast<int>(p), t, x, z, false});
    }
  }
  return v;
}

// The pairs (i < j) of polygon edges that do not join (|i - j| > 1 around the polygon) and whose
// chords come closer than the sum of their arcs' deviation bounds: where the arcs may cross
// although the chords do not (a shallow crossing of arcs that stray from their chords by more
// than the chords' distance, as in a small loop of the curve drawn by few pieces). `v` is the
// polygon of `polygon(pieces)` (kAreaPoints + 1 vertices per piece); the boxes of the chords,
// widened by the bounds, are compared piece by piece where the pieces' boxes overlap.
std::vector<std::pair<std::size_t, std::size_t>> near_pairs(const std::vector<Piece>& pieces,
                                                            const std::vector<Vertex>& v,
                                                            double tiny) {
  struct Box {
    double x0, x1, z0, z1, deviation;
    std::size_t edge;
  };
  const std::size_t n = v.size();
  if (n < kAreaPoints + 1 || n % (kAreaPoints + 1) != 0) return {};
  // A bound on how far a piece's arcs stray from the chords of its polygon edges (a quarter of
  // the piece each): |f - chord| <= (h^2 / 8) max |f''| with h = 1/2 in the Chebyshev variable
  // s in [-1, 1], and max |T_j''| = j^2 (j^2 - 1) / 3 (at s = +-1).
  const auto piece_deviation = [&](const Piece& pc) {
    double d2[2] = {0.0, 0.0};
    for (int q = 0; q < 2; ++q) {
      const auto& c = pc.f[q == 0 ? kDdx : kDdz].coefficients();
      for (int j = 2; j <= kDegree; ++j) d2[q] += std::abs(c[j]) * (j * j * (j * j - 1)) / 3.0;
    }
    return std::sqrt(d2[0] * d2[0] + d2[1] * d2[1]) / 32.0 + tiny;
  };
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vertex &p = v[i], &q = v[(i + 1) % n];
    const bool arc = p.piece >= 0 && p.piece == q.piece && q.t > p.t;
    const double d = !arc                                 ? tiny
                     : i > 0 && v[i - 1].piece == p.piece ? boxes[i - 1].deviation
                                                          : piece_deviation(pieces[p.piece]);
    boxes[i] = {std::min(p.x, q.x) - d,
                std::max(p.x, q.x) + d,
                std::min(p.z, q.z) - d,
                std::max(p.z, q.z) + d,
                d,
                i};
  }
  const auto overlap = [](const Box& a, const Box& b) {
    return !(a.x1 < b.x0 || b.x1 < a.x0 || a.z1 < b.z0 || b.z1 < a.z0);
  };
  // Edges a and b whose boxes overlap: a near pair unless they join, or their chords are farther
  // apart than their bounds.
  std::vector<std::pair<std::size_t, std::size_t>> out;
  const auto near_pair = [&](const Box& a, const Box& b) {
    const std::size_t i = std::min(a.edge, b.edge), j = std::max(a.edge, b.edge);
    if (j - i <= 1 || (i == 0 && j == n - 1)) return;  // edges that join
    // Edges that meet through a straight segment of no length (a joint without a switch: equal
    // up to the round-off of the two pieces' ends).
    const auto meets = [&](std::size_t k, std::size_t l) {
      return std::abs(v[k].x - v[l].x) <= tiny && std::abs(v[k].z - v[l].z) <= tiny;
    };
    if (meets((i + 1) % n, j) || meets((j + 1) % n, i)) return;
    double se = 0.0, sg = 0.0;
    const double reach = a.deviation + b.deviation;
    if (closest_points(edge_curve(pieces, v, i), edge_curve(pieces, v, j), se, sg) < reach * reach)
      out.emplace_back(i, j);
  };
  // First the groups of a piece's edges (its arcs and the segment after it), each in the union
  // of its edges' boxes; the edges of two groups only where the groups' boxes overlap. A group
  // with itself and with the next always.
  constexpr std::size_t kPer = kAreaPoints + 1;
  const std::size_t G = n / kPer;
  std::vector<Box> groups(G);
  double z_lo = boxes[0].z0, z_hi = boxes[0].z0;
  for (std::size_t g = 0; g < G; ++g) {
    Box u = boxes[g * kPer];
    for (std::size_t k = 1; k < kPer; ++k) {
      const Box& b = boxes[g * kPer + k];
      u.x0 = std::min(u.x0, b.x0), u.x1 = std::max(u.x1, b.x1);
      u.z0 = std::min(u.z0, b.z0), u.z1 = std::max(u.z1, b.z1);
    }
    u.edge = g;
    groups[g] = u;
    z_lo = std::min(z_lo, u.z0), z_hi = std::max(z_hi, u.z0);
  }
  const auto edges_of = [&](std::size_t g, std::size_t h) {
    for (std::size_t i = g * kPer; i < (g + 1) * kPer; ++i)
      for (std::size_t j = g == h ? i + 2 : h * kPer; j < (h + 1) * kPer; ++j)
        if (overlap(boxes[i], boxes[j])) near_pair(boxes[i], boxes[j]);
  };
  for (std::size_t g = 0; g < G; ++g) {
    edges_of(g, g);
    if (G > 2 || (G == 2 && g == 0)) edges_of(g, (g + 1) % G);
  }
  // The groups in buckets of their lowest z (a counting sort, G buckets): a group leaves the
  // sweep once it ends below the bucket being swept.
  const double per_bucket = (z_hi - z_lo) / static_cast<double>(G);
  const auto bucket = [&](double z) {
    return per_bucket > 0.0 ? std::min(G - 1, static_cast<std::size_t>((z - z_lo) / per_bucket))
                            : std::size_t{0};
  };
  std::vector<std::size_t> start(G + 1, 0), order(G);
  for (const Box& b : groups) ++start[bucket(b.z0) + 1];
  for (std::size_t k = 0; k < G; ++k) start[k + 1] += start[k];
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t g = 0; g < G; ++g) order[fill[bucket(groups[g].z0)]++] = g;
  }
  std::vector<const Box*> active;
  for (std::size_t k = 0; k < G; ++k) {
    if (start[k] == start[k + 1]) continue;
    const double floor_z = z_lo + static_cast<double>(k) * per_bucket;
    std::erase_if(active, [&](const Box* a) { return a->z1 < floor_z; });
    for (std::size_t m = start[k]; m < start[k + 1]; ++m) {
      const Box& b = groups[order[m]];
      for (const Box* a : active) {
        const std::size_t g = std::min(a->edge, b.edge), h = std::max(a->edge, b.edge);
        if (h - g <= 1 || (g == 0 && h == G - 1) || !overlap(*a, b)) continue;  // done above
        edges_of(g, h);
      }
      active.push_back(&b);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// The crossings (u, w) of the arcs of edges e and g whose chords come close: Newton from the
// chords' closest points, their middles and their ends (two arcs that bulge past each other cross
// twice). A solution counts inside the edges' pieces only (strictly: arcs continued past a switch
// meet there) and where the arcs cross at an angle (not at a tangency, nor where one arc is the
// continuation of the other).
std::vector<std::array<double, 2>> near_crossings(const EdgeCurve& e, const EdgeCurve& g) {
  std::vector<std::array<double, 2>> out;
  double se = 0.0, sg = 0.0;
  closest_points(e, g, se, sg);
  const std::array<std::array<double, 2>, 6> starts{
      {{se, sg}, {0.5, 0.5}, {0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}, {1.0, 1.0}}};
  const double width_e = e.u1 - e.u0, width_g = g.u1 - g.u0;
  for (const auto& [fe, fg] : starts) {
    double u = e.u0 + fe * width_e, w = g.u0 + fg * width_g;
    if (!newton_crossing(e, g, u, w) || e.clamp(u) != u || g.clamp(w) != w ||
        !transversal(e, g, u, w))
      continue;
    const bool seen = std::any_of(out.begin(), out.end(), [&](const auto& c) {
      return std::abs(c[0] - u) <= 1e-9 * std::abs(width_e) &&
             std::abs(c[1] - w) <= 1e-9 * std::abs(width_g);
    });
    if (!seen) out.push_back({u, w});
  }
  return out;
}

double swept_area(const std::vector<Piece>& pieces) {
  std::vector<Vertex> v = polygon(pieces);
  auto coordinates = [&](std::vector<double>& x, std::vector<double>& z) {
    x.resize(v.size());
    z.resize(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) x[i] = v[i].x, z[i] = v[i].z;
  };
  std::vector<double> x, z;
  coordinates(x, z);

  // Self-intersections: each crossing of two chords refined to the crossing of the arcs, then
  // inserted into both branches as one shared point (a straight edge between pieces takes it as
  // a new point in its piece-less position: after the end of its first piece).
  struct Insert {
    std::size_t edge;  // inserted after vertex `edge`
    double key;        // t (arc) or s (straight), for the order inside the edge
    Vertex vertex;
  };
  std::vector<Insert> inserts;
  for (const auto& [i, j] : detail::polygon_crossings(x, z)) {
    const EdgeCurve e = edge_curve(pieces, v, i), g = edge_curve(pieces, v, j);
    double u = 0.0, w = 0.0;
    // A crossing of the chords that Newton cannot place on the arcs of their pieces (a crossing
    // at a piece's end, or a near-tangency): no exact area; the caller falls back.
    if (!locate_crossing(e, g, u, w)) return std::numeric_limits<double>::quiet_NaN();
    if (!transversal(e, g, u, w)) continue;  // arcs that meet without an angle: no crossing
    const auto pe = e.at(u), pg = g.at(w);
    u = e.clamp(u);
    w = g.clamp(w);
    const double cx = 0.5 * (pe[0] + pg[0]), cz = 0.5 * (pe[1] + pg[1]);
    for (const auto& [edge, curve, par] : {std::tuple{i, e, u}, std::tuple{j, g, w}}) {
      // The edge of the polygon that holds the parameter (Newton may have moved to a
      // neighbouring edge of the same piece).
      std::size_t k = edge;
      if (curve.piece != nullptr) {
        while (k > 0 && v[k].piece == v[edge].piece && v[k].t > par) --k;
        while (k + 1 < v.size() && v[k + 1].piece == v[edge].piece && v[k + 1].t < par) ++k;
      }
      inserts.push_back({k, par, {curve.piece != nullptr ? v[edge].piece : -1, par, cx, cz, true}});
    }
  }
  // A crossing of arcs whose chords do not cross (see near_pairs): not among those inserted, the
  // polygon would miss it; no exact area then (the caller falls back).
  {
    double scale = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i)
      scale = std::max({scale, std::abs(x[i]), std::abs(z[i])});
    const double tol = 1e-9 * scale;
    for (const auto& [i, j] : near_pairs(pieces, v, tol)) {
      const EdgeCurve e = edge_curve(pieces, v, i), g = edge_curve(pieces, v, j);
      for (const auto& [u, w] : near_crossings(e, g)) {
        // One point of one piece, not a crossing.
        if (e.piece != nullptr && e.piece == g.piece &&
            std::abs(u - w) <= 1e-9 * (e.piece->b - e.piece->a))
          continue;
        const auto pe = e.at(u);
        const bool known = std::any_of(inserts.begin(), inserts.end(), [&](const Insert& in) {
          return std::abs(in.vertex.x - pe[0]) <= tol && std::abs(in.vertex.z - pe[1]) <= tol;
        });
        if (!known) return std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  if (!inserts.empty()) {
    std::sort(inserts.begin(), inserts.end(), [](const Insert& a, const Insert& b) {
      return a.edge != b.edge ? a.edge < b.edge : a.key < b.key;
    });
    std::vector<Vertex> merged;
    merged.reserve(v.size() + inserts.size());
    std::size_t next = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      merged.push_back(v[i]);
      while (next < inserts.size() && inserts[next].edge == i) {
        const Vertex& c = inserts[next++].vertex;
        const Vertex& last = merged.back();
        // The same crossing found twice, or at an existing point: keep one, shared.
        if (c.piece >= 0 && last.piece == c.piece &&
            std::abs(c.t - last.t) <= 1e-12 * (pieces[c.piece].b - pieces[c.piece].a)) {
          merged.back().x = c.x, merged.back().z = c.z, merged.back().crossing = true;
          continue;
        }
        if (c.piece < 0 && last.crossing && last.x == c.x && last.z == c.z) continue;
        if (c.piece < 0) {
          // On a straight edge between pieces: a point of no piece (its arc edges are straight).
          merged.push_back({-1, 0.0, c.x, c.z, true});
        } else {
          merged.push_back(c);
        }
      }
    }
    v = std::move(merged);
    coordinates(x, z);
  }

  // Bulges: for an edge inside a piece, the area between the arc and its chord, the integral of
  // (x - x_mean) dz along the arc (minus the chord's, which is zero for x_mean the mean of its
  // ends), exact from the antiderivative of the polynomial integrand (BulgeSeries).
  std::vector<double> bulge(v.size(), 0.0);
  BulgeSeries series;
  int series_piece = -1;
  // G and z at the end of the last edge: the start of the next one in the same piece.
  double last_t = std::numeric_limits<double>::quiet_NaN(), last_G = 0.0, last_z = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vertex& p = v[i];
    const Vertex& q = v[(i + 1) % v.size()];
    if (p.piece < 0 || p.piece != q.piece || !(q.t > p.t)) continue;
    const Piece& pc = pieces[p.piece];
    if (series_piece != p.piece) {
      series = BulgeSeries(pc);
      series_piece = p.piece;
      last_t = std::numeric_limits<double>::quiet_NaN();
    }
    const double G_p = p.t == last_t ? last_G : series.G(p.t);
    const double z_p = p.t == last_t ? last_z : pc.f[kDdz](p.t);
    const double G_q = series.G(q.t), z_q = pc.f[kDdz](q.t);
    last_t = q.t, last_G = G_q, last_z = z_q;
    // The arc's ends may differ from the (shared) crossing points by round-off: the chord's
    // integral of (x - x_mean) dz is zero.
    const double x_mean = 0.5 * (p.x + q.x);
    bulge[i] = series.integral(G_p, G_q) - (x_mean - series.x_offset()) * (z_q - z_p);
  }
  return enclosed_area(x, z, bulge);
}

// A place on the closed curve: segment 2p is piece p's arc (key: t), segment 2p + 1 the straight
// segment from piece p's end to the next piece's start (key: s in [0, 1]; the last one joins the
// last piece to the first).
struct Place {
  std::size_t segment;
  double key;
};

bool before(const Place& a, const Place& b) {
  return a.segment != b.segment ? a.segment < b.segment : a.key < b.key;
}

// One branch's passage through a self-intersection.
struct Cut {
  Place place;
  std::size_t crossing;  // which crossing (both of its cuts carry the same)
};

// The point (x, z) relative to (px, pz), turned so that the ray along `axis` (0: +x, 1: -x,
// 2: +z, 3: -z) is the positive u axis (rotations only: winding numbers keep their sign).
std::array<double, 2> turned_to_ray(double x, double z, double px, double pz, int axis) {
  const double dx = x - px, dz = z - pz;
  switch (axis) {
    case 0:
      return {dx, dz};
    case 1:
      return {-dx, -dz};
    case 2:
      return {dz, -dx};
    default:
      return {-dz, dx};
  }
}

// The signed number of times the arc of edge e (from its chord's start a to its end b, both
// turned) crosses the ray, counted as winding_right_of counts a chord's crossing (half-open at
// w = 0), for a point between the chord and its arc, where the chord's count would be wrong. The
// arc is followed through kArcSamples pieces (it turns by a few degrees along an edge: it crosses
// the ray's line at most once in each), each crossing placed by bisection. Nothing where the arc
// passes within `tiny` of the point.
std::optional<int> arc_ray_crossings(const EdgeCurve& e, std::array<double, 2> a,
                                     std::array<double, 2> b, double px, double pz, int axis,
                                     double tiny) {
  constexpr int kArcSamples = 16;
  const auto at = [&](double u) {
    const auto p = e.at(u);
    return turned_to_ray(p[0], p[1], px, pz, axis);
  };
  int count = 0;
  double u_from = e.u0;
  std::array<double, 2> from = a;
  for (int k = 1; k <= kArcSamples; ++k) {
    const double u_to = k == kArcSamples ? e.u1 : e.u0 + (e.u1 - e.u0) * k / kArcSamples;
    const std::array<double, 2> to = k == kArcSamples ? b : at(u_to);
    if (to[0] * to[0] + to[1] * to[1] <= tiny * tiny) return std::nullopt;
    if ((from[1] <= 0.0) != (to[1] <= 0.0)) {
      double lo = u_from, hi = u_to;  // w(lo) on from's side, w(hi) on to's
      std::array<double, 2> mid = from;
      for (int it = 0; it < 60 && hi - lo > 1e-15 * (e.u1 - e.u0); ++it) {
        const double u = 0.5 * (lo + hi);
        mid = at(u);
        ((mid[1] <= 0.0) == (from[1] <= 0.0) ? lo : hi) = u;
      }
      if (std::abs(mid[0]) <= tiny) return std::nullopt;
      if (mid[0] > 0.0) count += to[1] > from[1] ? 1 : -1;
    }
    u_from = u_to, from = to;
  }
  return count;
}

// The winding number of the closed polygon (x, z) just to the right of a point (px, pz) of the
// curve, seen along the curve's tangent (tx, tz) there: counted along a ray from the point in the
// axis direction closest to the right-hand normal (at least 45 degrees from the tangent). The
// point is a vertex of the polygon (`own` its two edges) or lies on the arc of edge `own[0]` (=
// own[1]), which the polygon then passes through the point instead: either way the edges at the
// point cannot meet the ray and are skipped. The result is the curve's winding number there unless
// the point lies between another edge and its arc: where an edge passes closer to it than the
// bound on how far the edge's arc strays from its chord (arc_deviation of `edge(i)`, the
// EdgeCurve of edge i), the arc's own crossings of the ray count (two branches of the curve
// running close together, as near a tangency of the figure). Nothing when the point lies within
// `tiny` of an edge or its arc, or an edge meets the ray's line within `tiny` of it.
template <class Edge>
std::optional<int> winding_right_of(const std::vector<double>& x, const std::vector<double>& z,
                                    double px, double pz, std::array<std::size_t, 2> own, double tx,
                                    double tz, double tiny, const Edge& edge) {
  const std::size_t n = x.size();
  // The right-hand normal is (tz, -tx); its dot products with +x, -x, +z, -z.
  const std::array<double, 4> dot{tz, -tz, -tx, tx};
  const int axis = static_cast<int>(std::max_element(dot.begin(), dot.end()) - dot.begin());
  if (!(dot[axis] > 0.0)) return std::nullopt;
  // Coordinates relative to the vertex, turned so that the ray is the positive u axis.
  const auto turned = [&](std::size_t i) { return turned_to_ray(x[i], z[i], px, pz, axis); };
  int w = 0;
  auto next = turned(0);  // the turned coordinates of vertex i + 1, carried to the next edge
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = i + 1 == n ? 0 : i + 1;
    const auto [ua, wa] = next;
    next = turned(k);
    if (i == own[0] || i == own[1]) continue;  // the point's own edges
    const auto [ub, wb] = next;
    // The vertex's distance from the edge; where it is within a quarter of the edge's length,
    // against the bound on the arc's deviation (evaluated only there). The edge's box, farther
    // from the vertex than tiny and a quarter of the edge's length, rules both out at once (most
    // edges: no division).
    {
      const double ex = ub - ua, ew = wb - wa, len2 = ex * ex + ew * ew;
      const double gap_u = std::max({0.0, std::min(ua, ub), -std::max(ua, ub)});
      const double gap_w = std::max({0.0, std::min(wa, wb), -std::max(wa, wb)});
      const double gap2 = gap_u * gap_u + gap_w * gap_w;
      if (gap2 > tiny * tiny && gap2 > 0.0625 * len2) {
        if ((wa <= 0.0) == (wb <= 0.0)) continue;  // does not cross the ray's line (half-open)
        const double u = ua + (ub - ua) * (-wa) / (wb - wa);
        if (u > 0.0) w += wb > wa ? 1 : -1;  // (u, 0) lies in the box: |u| > tiny
        continue;
      }
      const double s = len2 > 0.0 ? std::clamp(-(ua * ex + wa * ew) / len2, 0.0, 1.0) : 0.0;
      const double nu = ua + s * ex, nw = wa + s * ew, dist2 = nu * nu + nw * nw;
      if (dist2 <= tiny * tiny) return std::nullopt;
      if (dist2 <= 0.0625 * len2) {
        const EdgeCurve e = edge(i);
        const double d = arc_deviation(e, tiny);
        if (dist2 <= d * d) {  // between the chord and its arc, maybe: the arc counts
          const auto crossings = arc_ray_crossings(e, {ua, wa}, {ub, wb}, px, pz, axis, tiny);
          if (!crossings) return std::nullopt;
          w += *crossings;
          continue;
        }
      }
    }
    if ((wa <= 0.0) == (wb <= 0.0)) continue;  // does not cross the ray's line (half-open)
    const double u = ua + (ub - ua) * (-wa) / (wb - wa);
    if (std::abs(u) <= tiny) return std::nullopt;
    if (u > 0.0) w += wb > wa ? 1 : -1;
  }
  return w;
}

double green_area(const std::vector<Piece>& pieces) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t P = pieces.size();
  if (P == 0) return 0.0;
  constexpr std::size_t kPer = kAreaPoints + 1;  // polygon vertices per piece
  const std::vector<Vertex> v = polygon(pieces);
  const std::size_t n = v.size();
  std::vector<double> x(n), z(n);
  double scale = 0.0, x_lo = v[0].x, x_hi = v[0].x;
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = v[i].x, z[i] = v[i].z;
    scale = std::max({scale, std::abs(x[i]), std::abs(z[i])});
    x_lo = std::min(x_lo, x[i]), x_hi = std::max(x_hi, x[i]);
  }
  if (!(scale > 0.0)) return 0.0;

  // The self-intersections, each located on the arcs and cut into both branches.
  std::vector<Cut> cuts;
  std::vector<bool> near_cut(n, false);  // vertices too close to a cut to decide an arc's c
  std::vector<std::array<Place, 2>> crossings;
  const auto place_of = [&](std::size_t edge, const EdgeCurve& e,
                            double u) -> std::optional<Place> {
    const bool jump = edge % kPer == kAreaPoints;  // the edge from a piece's end to the next
    if (jump != (e.piece == nullptr)) return std::nullopt;  // a degenerate piece
    const std::size_t p = edge / kPer;
    return Place{jump ? 2 * p + 1 : 2 * p, u};
  };
  // The places where two pieces join as one: the end of a piece is the start of the straight
  // segment after it (key 0), the start of a piece the end of the segment before it (key 1), and
  // a segment of no length one place, key 0 (no switch between the pieces, or one where the
  // accelerations are continuous, as at the onset of slip: equal up to round-off).
  const std::size_t segments = 2 * P;
  const double joint_tol = 1e-12 * scale;
  const auto joint = [&](std::size_t segment, double key) {
    const Piece& from = pieces[segment / 2];
    const Piece& to = pieces[(segment / 2 + 1) % P];
    const bool empty = std::abs(from.values[kDdx][0] - to.values[kDdx][kDegree]) <= joint_tol &&
                       std::abs(from.values[kDdz][0] - to.values[kDdz][kDegree]) <= joint_tol;
    return Place{segment, empty ? 0.0 : key};
  };
  const auto canonical = [&](const Place& pl) {
    if (pl.segment % 2 == 1) {
      if (pl.key <= 1e-12) return joint(pl.segment, 0.0);
      if (pl.key >= 1.0 - 1e-12) return joint(pl.segment, 1.0);
      return joint(pl.segment, pl.key);  // on a segment of no length: the joint's one place
    }
    const Piece& pc = pieces[pl.segment / 2];
    const double tol = 1e-12 * (pc.b - pc.a);
    if (pl.key >= pc.b - tol) return joint(pl.segment + 1, 0.0);
    if (pl.key <= pc.a + tol) return joint((pl.segment + segments - 1) % segments, 1.0);
    return pl;
  };
  const auto same_place = [&](const Place& a, const Place& b) {
    if (a.segment != b.segment) return false;
    const double width =
        a.segment % 2 == 0 ? pieces[a.segment / 2].b - pieces[a.segment / 2].a : 1.0;
    return std::abs(a.key - b.key) <= 1e-12 * width;
  };
  // The point where chords e and g cross (at parameters u and w).
  const auto crossing_point = [](const EdgeCurve& e, const EdgeCurve& g, double u, double w) {
    const auto pe = e.at(u), pg = g.at(w);
    return std::array<double, 2>{0.5 * (pe[0] + pg[0]), 0.5 * (pe[1] + pg[1])};
  };
  // Whether the curve from place a to place b (or from b to a) through the crossing point c is a
  // loop of length below 1e-9 of the curve's size (a few polygon vertices at most between them).
  const auto tiny_loop = [&](Place a, Place b, const std::array<double, 2>& c) {
    const auto place = [&](std::size_t i) { return Place{2 * (i / kPer), v[i].t}; };
    for (int direction = 0; direction < 2; ++direction, std::swap(a, b)) {
      // Walk the polygon's vertices from a to b (around the curve's start if b comes first).
      const bool around = before(b, a);
      std::size_t i = (a.segment / 2) * kPer;
      while (i < n && !before(a, place(i))) ++i;  // the first vertex after a
      bool passed_start = false, reached = false;
      double length = 0.0, px = c[0], pz = c[1];
      for (std::size_t steps = 0; steps <= 2 * kPer && length <= 1e-9 * scale; ++steps) {
        if (i == n) i = 0, passed_start = true;
        if ((!around && (passed_start || !before(place(i), b))) ||
            (around && passed_start && !before(place(i), b))) {
          reached = true;
          break;
        }
        length += std::hypot(x[i] - px, z[i] - pz);
        px = x[i], pz = z[i], ++i;
      }
      if (reached && length + std::hypot(c[0] - px, c[1] - pz) <= 1e-9 * scale) return true;
    }
    return false;
  };
  // The crossing of the arcs near chords i and j crossing: Newton from the chords' crossing; where
  // it leaves the chords' pieces (the arcs cross just beyond a joint of two pieces, while their
  // chords cross before it), from the neighbouring edges' chords, up to two edges away.
  const auto locate = [&](std::size_t i, std::size_t j, std::size_t& ei, std::size_t& ej, double& u,
                          double& w) {
    for (const int di : {0, -1, 1, -2, 2})
      for (const int dj : {0, -1, 1, -2, 2}) {
        ei = (i + n + static_cast<std::size_t>(di + 2) - 2) % n;
        ej = (j + n + static_cast<std::size_t>(dj + 2) - 2) % n;
        if (locate_crossing(edge_curve(pieces, v, ei), edge_curve(pieces, v, ej), u, w))
          return true;
      }
    return false;
  };
  // The crossing of the arcs of edges i and j at parameters u and w, cut into both branches
  // unless it is none or already known; false where it cannot be placed (the caller gives up).
  const auto add_crossing = [&](std::size_t i, std::size_t j, double u, double w) {
    const EdgeCurve e = edge_curve(pieces, v, i), g = edge_curve(pieces, v, j);
    auto a = place_of(i, e, e.clamp(u)), b = place_of(j, g, g.clamp(w));
    if (!a || !b) return false;
    a = canonical(*a), b = canonical(*b);
    // Chords that cross where two pieces join at a turning point of the curve: one place of the
    // curve, or a loop of no size (where the accelerations are continuous only up to the
    // event location's round-off), or arcs that meet without an angle, not a crossing.
    if (same_place(*a, *b) || tiny_loop(*a, *b, crossing_point(e, g, u, w)) ||
        !transversal(e, g, u, w))
      return true;
    // The same crossing met by two pairs of chords (at a vertex): once.
    const bool seen = std::any_of(crossings.begin(), crossings.end(), [&](const auto& c) {
      return (same_place(c[0], *a) && same_place(c[1], *b)) ||
             (same_place(c[0], *b) && same_place(c[1], *a));
    });
    if (seen) return true;
    crossings.push_back({*a, *b});
    for (const Place& pl : {*a, *b}) {
      cuts.push_back({pl, crossings.size() - 1});
      // The vertices of the edge that holds the cut and their neighbours; on a straight segment
      // those of the pieces on either side.
      const std::size_t p = pl.segment / 2, first = p * kPer;
      if (pl.segment % 2 == 0) {
        std::size_t k = 0;
        while (k + 1 < kAreaPoints && v[first + k + 1].t <= pl.key) ++k;
        for (std::size_t q = k == 0 ? 0 : k - 1; q <= std::min<std::size_t>(k + 2, kAreaPoints);
             ++q)
          near_cut[first + q] = true;
      } else {
        const std::size_t next_first = ((p + 1) % P) * kPer;
        for (std::size_t q = 0; q < 2; ++q)
          near_cut[first + kAreaPoints - q] = near_cut[next_first + q] = true;
      }
    }
    return true;
  };
  // The chords that come within their arcs' deviation bounds of each other (near_pairs): those
  // that cross among them (crossing chords come as near as chords can), and those whose arcs may
  // cross although the chords do not. (One broad phase for both: the slab sweep of the polygon,
  // polygon_crossings, found the crossing chords again at about the cost of the rest of the area.)
  const auto near = near_pairs(pieces, v, 1e-9 * scale);
  for (const auto& [i0, j0] : near) {
    if (!detail::chords_cross(x, z, i0, j0)) continue;
    std::size_t i = i0, j = j0;
    double u = 0.0, w = 0.0;
    if (!locate(i0, j0, i, j, u, w) || !add_crossing(i, j, u, w)) return kNaN;
  }
  // Crossings of arcs whose chords do not cross (none on most curves); those of crossing chords
  // again, known already. Newton that finds no crossing there finds none to add.
  for (const auto& [i, j] : near)
    for (const auto& [u, w] : near_crossings(edge_curve(pieces, v, i), edge_curve(pieces, v, j)))
      if (!add_crossing(i, j, u, w)) return kNaN;
  std::sort(cuts.begin(), cuts.end(),
            [](const Cut& a, const Cut& b) { return before(a.place, b.place); });
  const std::size_t m = cuts.size();
  for (std::size_t k = 0; k + 1 < m; ++k)  // two crossings at one place: a tangency, or worse
    if (same_place(cuts[k].place, cuts[k + 1].place)) return kNaN;

  // The arcs: arc k runs from cut k to cut k + 1 (the last one around the curve's start to the
  // first); without crossings, one arc, the whole curve. The integral of (x - xc) dz along each.
  const std::size_t arcs = m == 0 ? 1 : m;
  const double xc = 0.5 * (x_lo + x_hi);  // any constant: it cancels on the closed boundary
  std::vector<double> integral(arcs, 0.0);
  std::size_t arc = arcs - 1, next = 0;
  for (std::size_t p = 0; p < P; ++p) {
    const Piece& pc = pieces[p];
    const BulgeSeries series(pc);
    const double offset = series.x_offset() - xc;
    double G_from = series.G(pc.a), z_from = pc.values[kDdz][kDegree];
    const auto arc_to = [&](double G_to, double z_to) {
      integral[arc] += series.integral(G_from, G_to) + offset * (z_to - z_from);
      G_from = G_to, z_from = z_to;
    };
    for (; next < m && cuts[next].place.segment == 2 * p; ++next) {
      const double t = cuts[next].place.key;
      arc_to(series.G(t), pc.f[kDdz](t));
      arc = next;
    }
    arc_to(series.G(pc.b), pc.values[kDdz][0]);
    // The straight segment to the next piece's start (empty where no switch lies between them).
    const Piece& after = pieces[(p + 1) % P];
    const double x0 = pc.values[kDdx][0], z0 = pc.values[kDdz][0];
    const double x1 = after.values[kDdx][kDegree], z1 = after.values[kDdz][kDegree];
    double s_from = 0.0;
    const auto segment_to = [&](double s) {
      const double x_mid = x0 + 0.5 * (s_from + s) * (x1 - x0);
      integral[arc] += (x_mid - xc) * (s - s_from) * (z1 - z0);
      s_from = s;
    };
    for (; next < m && cuts[next].place.segment == 2 * p + 1; ++next) {
      segment_to(cuts[next].place.key);
      arc = next;
    }
    segment_to(1.0);
  }

  // c of each arc from the winding number just to its right, at polygon vertices inside a piece
  // and away from the cuts: at a quarter and three quarters along the arc (and its middle if one
  // of them cannot tell), which must agree (a crossing missed between them would not let them).
  std::vector<std::vector<std::size_t>> candidates(arcs);
  {
    std::size_t cut = 0;
    arc = arcs - 1;
    for (std::size_t i = 0; i < n; ++i) {
      const Place here{2 * (i / kPer), v[i].t};
      for (; cut < m && !before(here, cuts[cut].place); ++cut) arc = cut;
      const std::size_t k = i % kPer;
      if (k != 0 && k != kAreaPoints && !near_cut[i]) candidates[arc].push_back(i);
    }
  }
  const double tiny = 1e-9 * scale;
  // The curve of edge i: its arc's deviation bound (arc_deviation) and, for a point near it, the
  // arc itself.
  const auto edge = [&](std::size_t i) { return edge_curve(pieces, v, i); };
  // The winding just right of vertex i (inside a piece).
  const auto right_of_vertex = [&](std::size_t i) {
    const Piece& pc = pieces[v[i].piece];
    return winding_right_of(x, z, x[i], z[i], {(i + n - 1) % n, i}, pc.dx(v[i].t), pc.dz(v[i].t),
                            tiny, edge);
  };
  // An arc too short to hold a vertex away from the cuts (between two close crossings): the
  // point at the middle of its longest part in one piece (it spans a few pieces at most).
  const auto right_of_middle = [&](std::size_t k) -> std::optional<int> {
    const Place from = cuts[k].place, to = cuts[(k + 1) % m].place;
    double longest = 0.0, t = 0.0;
    std::size_t piece = P;
    for (std::size_t seg = from.segment, steps = 0; steps < 8;
         seg = (seg + 1) % segments, ++steps) {
      if (seg % 2 == 0) {
        const Piece& pc = pieces[seg / 2];
        const double lo = seg == from.segment && steps == 0 ? from.key : pc.a;
        const double hi = seg == to.segment && (steps > 0 || before(from, to)) ? to.key : pc.b;
        if (hi - lo > longest) longest = hi - lo, t = 0.5 * (lo + hi), piece = seg / 2;
      }
      if (seg == to.segment && (steps > 0 || before(from, to))) break;
    }
    if (piece == P) return std::nullopt;
    const Piece& pc = pieces[piece];
    std::size_t e = piece * kPer;
    while (e + 1 < (piece + 1) * kPer - 1 && v[e + 1].t <= t) ++e;
    return winding_right_of(x, z, pc.f[kDdx](t), pc.f[kDdz](t), {e, e}, pc.dx(t), pc.dz(t), tiny,
                            edge);
  };
  // An arc whose points cannot tell (too short to hold a point away from its crossings, as a
  // loop of 1e-7 m/s^2 at a corner of the curve, or all its points near the other branch's
  // edges): its c from the boundary's closing at one of its crossings, where it is the one arc
  // not known (one point that could tell must agree).
  constexpr int kUnknown = 2;  // c is -1, 0 or +1
  std::vector<int> c(arcs, kUnknown);
  std::vector<std::optional<int>> hint(arcs);
  for (std::size_t k = 0; k < arcs; ++k) {
    const auto& cand = candidates[k];
    const std::size_t size = cand.size();
    int agreeing = 0;
    std::optional<int> right;
    if (size == 0) {
      if (m == 0) return kNaN;
      right = right_of_middle(k);
      agreeing = right ? 1 : 0;
    }
    std::array<std::size_t, 3> tried{size, size, size};
    for (std::size_t attempt = 0; attempt < 3 && size > 0; ++attempt) {
      if (agreeing == 2 || (size == 1 && agreeing == 1)) break;
      const std::size_t idx = std::array{size / 4, (3 * size) / 4, size / 2}[attempt];
      if (std::find(tried.begin(), tried.end(), idx) != tried.end()) continue;
      tried[attempt] = idx;
      const auto w = right_of_vertex(cand[idx]);
      if (!w) continue;
      if (right && *right != *w) return kNaN;
      right = w;
      ++agreeing;
    }
    const auto c_of = [](int w) { return int{w + 1 != 0} - int{w != 0}; };
    if (right && (size <= 1 || agreeing >= 2)) {
      c[k] = c_of(*right);
    } else {
      if (m == 0) return kNaN;
      if (right) hint[k] = c_of(*right);
    }
  }
  std::vector<std::array<std::size_t, 2>> at(crossings.size());
  std::vector<int> seen_count(crossings.size(), 0);
  for (std::size_t k = 0; k < m; ++k) at[cuts[k].crossing][seen_count[cuts[k].crossing]++] = k;
  // The closing at a crossing: the c of the two arcs arriving (+1) equal those of the two leaving
  // (-1); an arc that both arrives and leaves there (a loop) cancels.
  const auto terms = [&](std::size_t ka, std::size_t kb) {
    return std::array<std::pair<std::size_t, int>, 4>{
        {{(ka + m - 1) % m, 1}, {(kb + m - 1) % m, 1}, {ka, -1}, {kb, -1}}};
  };
  for (bool progress = true; progress;) {
    progress = false;
    for (const auto& [ka, kb] : at) {
      int known = 0, coefficient = 0;
      std::optional<std::size_t> unknown;
      bool several = false;
      for (const auto& [k, sign] : terms(ka, kb)) {
        if (c[k] != kUnknown) {
          known += sign * c[k];
        } else if (!unknown || *unknown == k) {
          unknown = k, coefficient += sign;
        } else {
          several = true;
        }
      }
      if (!unknown || several || coefficient == 0) continue;
      if (known % coefficient != 0) return kNaN;
      const int value = -known / coefficient;
      if (value < -1 || value > 1 || (hint[*unknown] && *hint[*unknown] != value)) return kNaN;
      c[*unknown] = value;
      progress = true;
    }
  }
  // A loop left unknown (its c cancels at its one crossing): where it encloses less than 1e-12
  // of what the arcs sweep in all (a loop of round-off's size at a corner of the curve), it is
  // left out, as a loop within two consecutive polygon edges is.
  double swept = 0.0;
  for (const double i : integral) swept += std::abs(i);
  for (std::size_t k = 0; k < arcs; ++k)
    if (c[k] == kUnknown && m > 0 && cuts[k].crossing == cuts[(k + 1) % m].crossing &&
        std::abs(integral[k]) <= 1e-12 * swept)
      c[k] = 0;
  if (std::find(c.begin(), c.end(), kUnknown) != c.end()) return kNaN;
  // Checks: the boundary closes at every crossing; a curve without crossings bounds its region.
  if (m == 0 && c[0] == 0) return kNaN;
  for (const auto& [ka, kb] : at) {
    int balance = 0;
    for (const auto& [k, sign] : terms(ka, kb)) balance += sign * c[k];
    if (balance != 0) return kNaN;
  }
  double area = 0.0;
  for (std::size_t k = 0; k < arcs; ++k) area += c[k] * integral[k];
  if (area < 0.0) return kNaN;
  return area;
}

}  // namespace

double green_curve_area(const std::vector<Piece>& pieces) { return green_area(pieces); }

double swept_curve_area(const std::vector<Piece>& pieces) { return swept_area(pieces); }

double extrapolated_curve_area(const std::vector<Piece>& pieces, double tolerance) {
  return extrapolated_area(pieces, tolerance);
}

double curve_area(const std::vector<Piece>& pieces, double tolerance) {
  double area = green_area(pieces);
  if (std::isnan(area)) area = swept_area(pieces);
  if (std::isnan(area)) area = extrapolated_area(pieces, tolerance);
  return area;
}

}  // namespace oscidrum::detail
