// steady_metrics.cpp: metrics of a steady state from the dense output of the flow (metrics.hpp,
// compute_metrics(model, result)): one steady period is integrated again, once, from the first
// sample, and every metric is evaluated on the trajectory itself rather than on the uniform
// samples, so that it does not depend on numerics.samples_per_period. (A study's case passes the
// period its shooting orbit's sampling recorded on the way, src/drivers/period_recording.hpp:
// the same pieces, integrated once.)
// On each piece of the period (one integrator step in one phase) every quantity (x_M'', z_M''
// from (18), delta, phi, T/N, the friction power) is an analytic function of t: the
// Dormand-Prince interpolant (a polynomial) through the equations of motion. Each is replaced by
// its degree-10 Chebyshev interpolant through 11 right-hand-side evaluations (both ends among
// them), accurate to round-off (tests/drivers/test_steady_metrics.cpp), and everything below reads
// the interpolants:
//   peaks: at both ends of every piece (the one-sided limits at each switch instant) and at every
//     interior extremum, located by Newton's method on the derivative of the interpolant (only
//     on pieces where a bound on the curvature lets an extremum beat the nodes' values);
//   harmonics, phase lags, THD, friction work, phase fractions: integrals over each piece by
//     16-point Gauss-Legendre quadrature;
//   area: exact for the piecewise curve (enclosed_area with bulges): a polygon through 5 points
//     per piece, every self-intersection of the curve located by Newton on the interpolants and
//     made a point of both branches, and each edge corrected by the area between its arc and its
//     chord. The polygon's points where two pieces join are the exact node values, the same bits
//     on both sides (an ulp apart, the chords beside a turning point of the curve crossed at the
//     joint: 5 of the 112 cases of a Table 2 sweep). Where Newton cannot place a crossing of two
//     chords on the arcs (a sharp corner where two pieces join), polygons of the interpolants, n
//     points per piece doubled and Richardson-extrapolated to 1e-11, instead (the two agree
//     to 1.7e-12 on every regression profile).
#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "drivers/period_recording.hpp"
#include "equations/equations.hpp"
#include "metrics/area.hpp"
#include "metrics/indicators.hpp"
#include "metrics/piece_interpolant.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/metrics.hpp"
#include "roller/rollers.hpp"

namespace oscidrum {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kAreaPoints = 4;  // polygon points per piece for the area (the arcs are exact)

using detail::recording::Interpolant;
using detail::recording::kDegree;
using detail::recording::Piece;
using detail::recording::Quantity;
using detail::recording::Recorder;
using detail::recording::Recording;
using enum detail::recording::Quantity;

// T_j(x_i), j = 0 ... kDegree, at the abscissas x_i >= 0 of the 16-point Gauss-Legendre rule
// (by the recurrence T_j+1 = 2 x T_j - T_j-1): the Chebyshev sums at the quadrature nodes.
const std::vector<std::array<double, kDegree + 1>>& gauss_chebyshev() {
  static const auto table = [] {
    const auto& x = boost::math::quadrature::gauss<double, 16>::abscissa();
    std::vector<std::array<double, kDegree + 1>> T(x.size());
    for (std::size_t i = 0; i < T.size(); ++i) {
      T[i][0] = 1.0;
      T[i][1] = x[i];
      for (int j = 1; j < kDegree; ++j) T[i][j + 1] = 2.0 * x[i] * T[i][j] - T[i][j - 1];
    }
    return T;
  }();
  return table;
}

// Largest and smallest value of a quantity: ends and interior extrema of every piece.
struct Extremes {
  double hi = -std::numeric_limits<double>::infinity();
  double lo = std::numeric_limits<double>::infinity();
  void add(double v) {
    hi = std::max(hi, v);
    lo = std::min(lo, v);
  }
};

// The interior extrema of one piece, bracketed by its interpolation nodes (exact values, scanned
// in increasing t; the caller has added the node values themselves). Maxima only if want_max,
// minima only if want_min.
void add_extremes(const Interpolant& f, const std::array<double, Interpolant::kNodes>& values,
                  bool want_max, bool want_min, Extremes& out) {
  constexpr int kScan = kDegree;
  const double a = f.a(), b = f.b();
  std::array<double, kScan + 1> ts, scan;
  for (int k = 0; k <= kScan; ++k) {
    ts[k] = k == 0 ? a : k == kScan ? b : Interpolant::node(a, b, kScan - k);
    scan[k] = values[kScan - k];
  }
  // f' and f'' only for a piece that holds an extremum or ends on the way to one (most do not).
  Interpolant df, d2f;
  bool have_derivatives = false;
  const auto derivatives = [&] {
    if (have_derivatives) return;
    df = f.derivative_interpolant();
    d2f = df.derivative_interpolant();
    have_derivatives = true;
  };
  // A scan point not beaten by its neighbours brackets an extremum between them. At the ends of
  // the piece only one neighbour exists: an end that is not beaten by it may have the extremum
  // just inside the piece (between the last scan point and the end), which the end's value alone
  // misses by about half the curvature times the squared distance (up to ~1e-5 of a peak); the
  // one-sided bracket finds it (or returns the end itself).
  for (int k = 0; k <= kScan; ++k) {
    const int lo = std::max(0, k - 1), hi = std::min(kScan, k + 1);
    const double v = scan[k], l = scan[lo], r = scan[hi];
    for (double sign : {1.0, -1.0}) {
      if (!(sign > 0.0 ? want_max : want_min)) continue;
      if (!(sign * v >= sign * l && sign * v >= sign * r)) continue;
      // An end where the quantity still rises towards the end (falls, for a minimum) is the
      // extremum of its one-sided bracket: nothing to refine.
      derivatives();
      if (k == 0 && sign * df(a) <= 0.0) continue;
      if (k == kScan && sign * df(b) >= 0.0) continue;
      out.add(detail::extremum(f, df, d2f, ts[lo], ts[hi] - ts[lo], sign));
    }
  }
}

struct Node {  // a Gauss-Legendre node of one piece
  double tau, weight, ddx, ddz, phi, friction_power, vertical_force, z;
  double cos1, sin1;  // cos(nu tau), sin(nu tau)
};

// The area of the z_M''-x_M'' curve of the pieces: a polygon through kAreaPoints + 1 points per
// piece (the jumps of the accelerations at switches are straight edges between pieces), with
// every self-intersection of the curve located on the interpolants (Newton) and inserted as a
// point of both branches, and each polygon edge inside a piece corrected by the exact area
// between the arc and its chord (enclosed_area with bulges).
// NaN when a self-intersection could not be located.
double curve_area(const std::vector<Piece>& pieces);

// The fallback: polygons through n points per piece of the interpolants, n doubled and
// Richardson-extrapolated (error ~ n^-2) until two estimates agree to 1e-11 relative, or until the
// sweep of the next polygon would cost more than kFallbackVisits (edge, slab) visits (area.hpp,
// sweep_visits; always at least n = 8, one extrapolation). A period of thousands of pieces (10 000
// at 0.1 Hz), or a curve that winds thousands of times around one place (a drum barely excited:
// the accelerations ring down after each switch), must not be refined to 4096 points per piece
// (millions of points, each slab crossed by thousands of edges: seconds to minutes). Then the last
// extrapolation stands, with an error of the order of its difference from the one before (7e-9
// relative for the paper's roller at 0.1 Hz, tests/drivers/test_steady_metrics.cpp).
constexpr std::size_t kFallbackVisits = 30'000'000;

double extrapolated_area(const std::vector<Piece>& pieces) {
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
      if (std::abs(area - previous) <= 1e-11 * std::abs(area)) break;
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

double curve_area(const std::vector<Piece>& pieces) {
  // The polygon: kAreaPoints + 1 points per piece.
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

Spectrum spectrum(const std::vector<Node>& nodes, double Node::*m, double P, double t0, double f,
                  int cycles, int n_max) {
  Spectrum h(static_cast<std::size_t>(n_max) + 1);
  double mean = 0.0;
  for (const Node& nd : nodes) mean += nd.weight * (nd.*m);
  mean /= P;
  h[0] = {std::abs(mean), mean >= 0.0 ? kPi / 2.0 : -kPi / 2.0};
  // y = a_n cos(n nu tau) + b_n sin(n nu tau) + ...: cos and sin of n nu tau from those of
  // nu tau by the angle-addition recurrence (error ~n ulp).
  std::vector<double> a(static_cast<std::size_t>(n_max) + 1, 0.0), b(a.size(), 0.0);
  for (const Node& nd : nodes) {
    const double y = nd.weight * (nd.*m);
    double c = nd.cos1, s = nd.sin1;
    for (int n = 1; n <= n_max; ++n) {
      a[n] += y * c;
      b[n] += y * s;
      const double next = c * nd.cos1 - s * nd.sin1;
      s = s * nd.cos1 + c * nd.sin1;
      c = next;
    }
  }
  for (int n = 1; n <= n_max; ++n) {
    const double an = a[n] * 2.0 / P, bn = b[n] * 2.0 / P;
    // Phase at tau = 0, then in absolute time: n nu t = n nu tau + n nu t0 (reduced in cycles).
    double cyc = n * f * t0;
    cyc -= std::round(cyc);
    h[static_cast<std::size_t>(n)] = {std::hypot(an, bn),
                                      wrap_pi(std::atan2(an, bn) - 2.0 * kPi * cyc)};
  }
  (void)cycles;
  return h;
}

// The subharmonics A(f/2), A(3f/2), A(5f/2) of z_M'' over the steady period P = p / f: a
// p-periodic motion has frequencies k f / p only, so none for an odd p; for an even p the
// quadrature sums of z_M'' against cos and sin of (2j + 1) nu tau / 2.
detail::HalfHarmonics half_harmonics(const std::vector<Node>& nodes, double P, double f, int p) {
  detail::HalfHarmonics h;
  if (p % 2 != 0) return h;
  const double half_nu = kPi * f;
  std::array<double, 3> a{}, b{};
  for (const Node& nd : nodes) {
    const double y = nd.weight * nd.ddz;
    double c = std::cos(half_nu * nd.tau), s = std::sin(half_nu * nd.tau);
    for (std::size_t j = 0; j < 3; ++j) {  // (2j + 1) nu tau / 2: add nu tau each time
      a[j] += y * c;
      b[j] += y * s;
      const double next = c * nd.cos1 - s * nd.sin1;
      s = s * nd.cos1 + c * nd.sin1;
      c = next;
    }
  }
  h.a05 = std::hypot(a[0], b[0]) * 2.0 / P;
  h.a15 = std::hypot(a[1], b[1]) * 2.0 / P;
  h.a25 = std::hypot(a[2], b[2]) * 2.0 / P;
  return h;
}

// One steady period integrated again from the first sample, recorded piece by piece.
template <class R>
Recording record_period(const Model& model, const Samples& s, double t0, double t1) {
  using Dyn = detail::Dynamics<R>;
  const FlowOptions options = FlowOptions::from(model);
  const Dyn dynamics(model, options.baumgarte);
  BasicFlow<R> flow(model, options);
  flow.reset(t0, R::State::from_array(Dyn::sampled_state(s, 0)),
             dynamics.flow_phase(s.phase.front()));
  Recorder<R> rec(model, options.baumgarte, t0, t1);
  if (flow.advance(t1, &rec) != FlowStop::reached)
    throw Error("compute_metrics: the steady period did not integrate again: " + flow.message());
  return std::move(rec.out);
}

// Whether `rec` is the period of `s` from t0 to t1 as record_period would record it: the same
// span, from the same state and phase at a restart of the flow (so the same pieces, bit for bit).
template <class R>
bool is_the_period(const Recording& rec, const Model& model, const Samples& s, double t0,
                   double t1) {
  using Dyn = detail::Dynamics<R>;
  const auto x = Dyn::sampled_state(s, 0);
  const Dyn dynamics(model, FlowOptions::from(model).baumgarte);
  return rec.t_begin == t0 && rec.t_end == t1 && !rec.pieces.empty() &&
         rec.start.size() == x.size() &&
         std::memcmp(rec.start.data(), x.data(), x.size() * sizeof(double)) == 0 &&
         rec.phase == dynamics.flow_phase(s.phase.front());
}

}  // namespace

Metrics compute_metrics(const Model& model, const Result& result, int n_max) {
  return detail::compute_metrics(model, result, n_max, nullptr);
}

Metrics detail::compute_metrics(const Model& model, const Result& result, int n_max,
                                const recording::Recording* recorded) {
  const Samples& s = result.samples;
  if (s.size() == 0) throw Error("compute_metrics: the result holds no samples");
  if (!ok(result.status))
    throw Error(std::string("compute_metrics: the result has status ") + to_string(result.status) +
                ", not a steady state: no metrics");
  if (n_max < 0) throw Error("compute_metrics: n_max must be >= 0; got " + std::to_string(n_max));
  // The harmonics are integrals over the trajectory, but the spectrum a user compares them with is
  // that of the samples: the same bound as for the sampled metrics (and the cost, n_max times
  // the quadrature nodes, stays bounded).
  const int spp = model.parameters().numerics.samples_per_period;
  if (n_max >= spp / 2)
    throw Error("compute_metrics: n_max must be < numerics.samples_per_period / 2 = " +
                std::to_string(spp / 2) + " (the samples' Nyquist limit); got " +
                std::to_string(n_max));
  const int p = result.diagnostics.multiplicity >= 1 ? result.diagnostics.multiplicity : 1;
  const double f = result.frequency, P = p / f;
  const double t0 = s.t.front(), t1 = t0 + P;
  // The sampling's own recording of the period when it has one; else the period integrated again.
  const bool reuse = recorded != nullptr && detail::with_roller(model, [&]<class R>() {
                       return is_the_period<R>(*recorded, model, s, t0, t1);
                     });
  Recording again;
  if (!reuse)
    again =
        detail::with_roller(model, [&]<class R>() { return record_period<R>(model, s, t0, t1); });
  const Recording& rec = reuse ? *recorded : again;
  const std::vector<Piece>& pieces = rec.pieces;

  Metrics m;
  // Peaks: first the values at every node, then the interior extrema of only those pieces whose
  // extremum could beat the values already found by more than the interpolant's round-off (most
  // cannot: ChebyshevInterpolant::overshoot_bound, roundoff_bound; a flat piece at the peak, T/N
  // = -+mu in slip or the zero gap in contact, is not searched). The peaks are those of every
  // piece searched, to that round-off (about 1e-14 relative).
  constexpr std::array<Quantity, 5> kPeakQuantities = {kDdx, kDdz, kDelta, kTraction, kGap};
  std::array<Extremes, kPeakQuantities.size()> peaks;
  for (const Piece& pc : pieces)
    for (std::size_t q = 0; q < kPeakQuantities.size(); ++q)
      for (double v : pc.values[kPeakQuantities[q]]) peaks[q].add(v);
  for (const Piece& pc : pieces) {
    for (std::size_t q = 0; q < kPeakQuantities.size(); ++q) {
      const auto& values = pc.values[kPeakQuantities[q]];
      const Interpolant& fq = pc.f[kPeakQuantities[q]];
      const double bound = fq.overshoot_bound(), resolved = 2.0 * fq.roundoff_bound();
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      const bool want_max = *hi + bound - peaks[q].hi > resolved,
                 want_min = peaks[q].lo - (*lo - bound) > resolved;
      if (want_max || want_min)
        add_extremes(pc.f[kPeakQuantities[q]], values, want_max, want_min, peaks[q]);
    }
  }
  std::vector<Node> nodes;
  nodes.reserve(pieces.size() * 16);
  std::array<double, 4> time{};  // slip-, stick, slip+, flight [s]
  boost::math::quadrature::gauss<double, 16> rule;
  const double nu = 2.0 * kPi * f;
  for (const Piece& pc : pieces) {
    // Quadrature nodes (16-point Gauss-Legendre on each piece). cos and sin of nu tau from those
    // at the piece's middle and of the offsets by angle addition (error a few ulp): 9 sines and
    // cosines per piece instead of 16.
    const double half = 0.5 * (pc.b - pc.a), mid = 0.5 * (pc.a + pc.b);
    const double c_mid = std::cos(nu * (mid - t0)), s_mid = std::sin(nu * (mid - t0));
    const auto& x = rule.abscissa();
    const auto& w = rule.weights();
    // The quantities at the nodes mid -+ half x_i from their Chebyshev coefficients, the even and
    // odd parts of sum_j c_j T_j(x_i) apart (T_j(-x) = (-1)^j T_j(x)): both nodes of a pair from
    // one table row (gauss_chebyshev) instead of a Clenshaw sum at each.
    constexpr std::array<Quantity, 6> kNodeQuantities = {kDdx,           kDdz,           kPhi,
                                                         kFrictionPower, kVerticalForce, kZ};
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double c_off = std::cos(nu * half * x[i]), s_off = std::sin(nu * half * x[i]);
      const auto& T = gauss_chebyshev()[i];
      std::array<double, kNodeQuantities.size()> even{}, odd{};
      for (std::size_t q = 0; q < kNodeQuantities.size(); ++q) {
        const auto& c = pc.f[kNodeQuantities[q]].coefficients();
        for (int j = 0; j <= kDegree; j += 2) even[q] += c[j] * T[j];
        for (int j = 1; j <= kDegree; j += 2) odd[q] += c[j] * T[j];
      }
      for (double sign : {-1.0, 1.0}) {
        if (x[i] == 0.0 && sign > 0) continue;
        const double t = mid + sign * half * x[i];
        nodes.push_back({t - t0, half * w[i], even[0] + sign * odd[0], even[1] + sign * odd[1],
                         even[2] + sign * odd[2], std::abs(even[3] + sign * odd[3]),
                         even[4] + sign * odd[4], even[5] + sign * odd[5],
                         c_mid * c_off - sign * s_mid * s_off,
                         s_mid * c_off + sign * c_mid * s_off});
      }
    }
    // slip- 0, stick 1, slip+ 2, flight 3; a smooth law's one phase: its apparent phases' times
    // come from the sampling (below).
    if (pc.phase != Phase::smooth)
      time[static_cast<std::size_t>(static_cast<int>(pc.phase) + 1)] += pc.b - pc.a;
  }
  if (model.friction_phases() == FrictionPhases::smooth)
    time = {result.slip_negative_time, result.stick_time, result.slip_positive_time,
            result.flight_time};
  const Extremes &ddx = peaks[0], &ddz = peaks[1], &delta = peaks[2], &traction = peaks[3],
                 &gap = peaks[4];
  m.ddx_max = ddx.hi, m.ddx_min = ddx.lo;
  m.ddz_max = ddz.hi, m.ddz_min = ddz.lo;
  m.delta_max = delta.hi, m.delta_min = delta.lo;
  m.mu_required = std::max(traction.hi, -traction.lo);

  const int n_compute = std::max(n_max, 3);
  Spectrum hx = spectrum(nodes, &Node::ddx, P, t0, f, p, n_compute);
  Spectrum hz = spectrum(nodes, &Node::ddz, P, t0, f, p, n_compute);
  {
    // The fundamental at a node: A1 sin(nu (t0 + tau) + phase1) = A1 sin(nu tau + theta), theta
    // with nu t0 reduced in cycles, by angle addition from the node's cos and sin of nu tau.
    double cyc = f * t0;
    cyc -= std::round(cyc);
    const double theta = 2.0 * kPi * cyc + hx[1].phase;
    const double a1_cos = hx[1].amplitude * std::cos(theta),
                 a1_sin = hx[1].amplitude * std::sin(theta);
    const double mean = hx[0].amplitude * std::sin(hx[0].phase);
    double sum = 0.0;
    for (const Node& nd : nodes) {
      const double r = nd.ddx - mean - (nd.sin1 * a1_cos + nd.cos1 * a1_sin);
      sum += nd.weight * r * r;
    }
    detail::set_spectral_metrics(m, std::move(hx), std::move(hz), 2.0 * sum / P, n_max,
                                 half_harmonics(nodes, P, f, p));
  }

  // phi: drift removed, the fundamental against M0 sin(nu t).
  const double rate = (pieces.back().f[kPhi](pieces.back().b) - pieces.front().f[kPhi](t0)) / P;
  std::vector<Node> phi_nodes = nodes;
  for (Node& nd : phi_nodes) nd.phi -= rate * nd.tau;
  const Spectrum hphi = spectrum(phi_nodes, &Node::phi, P, t0, f, p, 1);
  detail::set_rotation_metrics(m, hphi[1]);

  double work = 0.0;
  for (const Node& nd : nodes) work += nd.weight * nd.friction_power;
  m.friction_work = work / p;
  detail::set_phase_fractions(m, time[1], time[2], time[0], time[3]);
  detail::no_required_mu_with_flight(m);
  m.liftoffs_per_period = static_cast<double>(rec.lift_offs) / p;
  m.gap_max = std::max(gap.hi, 0.0);
  m.landing_velocity = rec.landing_speed;
  // The Kb-type stiffness: the fundamentals of F_v and z_M integrated over the period.
  m.kb = detail::soil_stiffness(spectrum(nodes, &Node::vertical_force, P, t0, f, p, 1)[1],
                                spectrum(nodes, &Node::z, P, t0, f, p, 2));

  // The Evib-type modulus: the loop F_v(z_M) through kEvibPoints + 1 points of each piece, both
  // ends included (a landing's two one-sided values of F_v at the same z_M).
  m.evib = std::numeric_limits<double>::quiet_NaN();
  const Case& c = model.parameters();
  const double nu_soil = detail::evib_poisson_ratio(c);
  if (c.roller.type == RollerType::vibratory && !std::isnan(nu_soil)) {
    constexpr int kEvibPoints = 32;
    std::vector<double> z, Fv;
    z.reserve(pieces.size() * (kEvibPoints + 1));
    Fv.reserve(z.capacity());
    for (const Piece& pc : pieces)
      for (int k = 0; k <= kEvibPoints; ++k) {
        const double t = k == kEvibPoints ? pc.b : pc.a + (pc.b - pc.a) * k / kEvibPoints;
        z.push_back(pc.f[kZ](t));
        Fv.push_back(pc.f[kVerticalForce](t));
      }
    m.evib = vibration_modulus(z, Fv, c.roller.r, c.roller.b, nu_soil);
  }

  m.area = curve_area(pieces);
  if (std::isnan(m.area)) m.area = extrapolated_area(pieces);
  return m;
}

}  // namespace oscidrum
