// The identification's least-squares problem (problem.hpp): unknowns, forward model, time shift,
// residuals.
#include "identify/problem.hpp"

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

#include "oscidrum/error.hpp"
#include "oscidrum/simulate.hpp"
#include "oscidrum/soil.hpp"
#include "util/format.hpp"
#include "util/one_value.hpp"
#include "util/small_angle.hpp"

namespace oscidrum::detail {
namespace {

std::string num(double v) { return shortest(v); }

std::complex<double> coefficient(const Harmonic& h) { return std::polar(h.amplitude, h.phase); }

// Extremes and area of the periodic signal made of harmonics 1 ... n (as for a record).
void signal_shape(const std::vector<Harmonic>& hx, const std::vector<Harmonic>& hz, int n,
                  double& xmax, double& xmin, double& zmax, double& zmin, double& area) {
  constexpr int kSamples = 512;
  // n >= 1: the mean is an offset in a record, and left out of both. A sin(k w + theta) =
  // A cos(theta) sin(k w) + A sin(theta) cos(k w), the harmonics of w = 2 pi j / 512 by
  // harmonics_turns (a sine per sample and harmonic was a twentieth of an identification window).
  const int N = std::min(n, static_cast<int>(hx.size()) - 1);
  std::vector<double> x(kSamples), z(kSamples), ax(N + 1), bx(N + 1), az(N + 1), bz(N + 1),
      ck(N + 1), sk(N + 1);
  for (int k = 1; k <= N; ++k) {
    ax[k] = hx[k].amplitude * std::cos(hx[k].phase);
    bx[k] = hx[k].amplitude * std::sin(hx[k].phase);
    az[k] = hz[k].amplitude * std::cos(hz[k].phase);
    bz[k] = hz[k].amplitude * std::sin(hz[k].phase);
  }
  for (int j = 0; j < kSamples; ++j) {
    harmonics_turns(static_cast<double>(j) / kSamples, std::max(N, 0), ck.data(), sk.data());
    double sx = 0, sz = 0;
    for (int k = 1; k <= N; ++k) {
      sx += ax[k] * sk[k] + bx[k] * ck[k];
      sz += az[k] * sk[k] + bz[k] * ck[k];
    }
    x[j] = sx;
    z[j] = sz;
  }
  xmax = *std::max_element(x.begin(), x.end());
  xmin = *std::min_element(x.begin(), x.end());
  zmax = *std::max_element(z.begin(), z.end());
  zmin = *std::min_element(z.begin(), z.end());
  area = enclosed_area(x, z);
}

}  // namespace

const char* name_of(Unknown k) {
  switch (k) {
    case Unknown::G:
      return "G";
    case Unknown::ksh:
      return "ksh";
    case Unknown::ksv:
      return "ksv";
    case Unknown::mu:
      return "mu";
    case Unknown::MMd:
      return "MMd";
  }
  return "";
}

const char* unit_of(Unknown k) {
  switch (k) {
    case Unknown::G:
      return "Pa";
    case Unknown::ksh:
    case Unknown::ksv:
      return "N/m";
    case Unknown::mu:
      return "-";
    case Unknown::MMd:
      return "N m";
  }
  return "";
}

double to_internal(Unknown k, double v, double M0) {
  return k == Unknown::MMd ? v / M0 : std::log(v);
}
double to_physical(Unknown k, double p, double M0) {
  return k == Unknown::MMd ? p * M0 : std::exp(p);
}

HarmonicMisfit harmonic_misfit(const std::vector<std::complex<double>>& x,
                               const std::vector<std::complex<double>>& z,
                               const MeasuredResponse& data, int harmonics) {
  double num2 = 0, den2 = 0;
  for (int n = 1; n <= harmonics; ++n) {
    num2 += std::norm(data.ddx[n - 1] - x[n - 1]) + std::norm(data.ddz[n - 1] - z[n - 1]);
    den2 += std::norm(data.ddx[n - 1]) + std::norm(data.ddz[n - 1]);
  }
  return {std::sqrt(num2 / (2.0 * harmonics)),
          den2 > 0 ? std::sqrt(num2 / den2) : std::numeric_limits<double>::quiet_NaN()};
}

Problem::Problem(const Case& base, const MeasuredResponse& data, const IdentifyOptions& o,
                 Comparison comparison)
    : data_(data), o_(o), comparison_(comparison) {
  if (comparison == Comparison::sampled && !has_sampling_map(data, o.harmonics))
    throw Error("identify: the model sampled at the window's times needs the window's fit of " +
                std::to_string(o.harmonics) + " harmonics (measure_window, alias_t)");
  case_ = base;
  const double scale = data.f / base.roller.f;
  case_.roller.f = data.f;
  case_.roller.M0 = base.roller.M0 * scale * scale;  // M0 grows with f^2 (5)
  // The harmonics compared, and those of the signal whose peaks and area are compared.
  n_sim_ = std::max({3, o.harmonics, o.use_peaks || o.use_area ? data.n_signal : 0});
  case_.numerics.samples_per_period = std::max(64, 4 * n_sim_ + 8);
  case_.numerics.output_periods = 1;
  // Every model run is bounded, so that no trial the optimiser visits can take long: one that
  // has not settled in 1500 periods, needs more than 800 steps in one period (a diverging slip
  // phase, a stiff corner of the parameter space) or more than kMaxStepsPerRun steps in all is
  // a failed trial (Simulated::ok false, with the run's message), not waited for. The paper's
  // roller needs 20-150 steps per period at rtol 1e-6 (G = 5 to 2000 MN/m^2).
  case_.numerics.max_periods = std::min(base.numerics.max_periods, 1500);
  case_.numerics.max_steps_per_period = std::min(base.numerics.max_steps_per_period, 800);
  if (o.shooting) case_.numerics.method = SteadyMethod::shooting;
  // The model to 1e-6 (its harmonics change by about that much; the measured ones are known to
  // about 1e-3), three times faster than the default 1e-8.
  case_.numerics.rtol = std::max(base.numerics.rtol, o.model_tolerance);
  case_.numerics.steady_tol = std::max(base.numerics.steady_tol, o.model_tolerance);
  if (o.modulus && o.soil_scale == SoilScale::table2) {
    // Table 2's coefficients at G (case_at), given to the model as coefficients.
    case_.soil.input = SoilInput::coefficients;
    unknowns_.push_back(Unknown::G);
    bounds_.push_back({std::log(kTable2InterpolatedMin), std::log(kTable2InterpolatedMax)});
  } else if (o.modulus) {
    case_.soil.input = SoilInput::modulus;
    unknowns_.push_back(Unknown::G);
    bounds_.push_back({std::log(1e5), std::log(2e9)});
  } else {
    case_.soil.input = SoilInput::coefficients;
    unknowns_.push_back(Unknown::ksh);
    bounds_.push_back({std::log(1e5), std::log(1e11)});
    unknowns_.push_back(Unknown::ksv);
    bounds_.push_back({std::log(1e5), std::log(1e11)});
  }
  if (o.fit_mu) {
    case_.contact.pure_rolling = false;
    unknowns_.push_back(Unknown::mu);
    warm_starts_ = false;  // see run()
    bounds_.push_back({std::log(0.05), std::log(5.0)});
  }
  if (o.fit_MMd) {
    unknowns_.push_back(Unknown::MMd);
    bounds_.push_back({-0.5, 0.5});
  }
  rows_ = 4 * o.harmonics + (o.use_peaks ? 4 : 0) + (o.use_area ? 1 : 0);
  // The weights: the inverse Cholesky factor of each signal's covariance (measure_window), or
  // 1 / sigma without one.
  const int m = 2 * o.harmonics;
  auto whitening = [m](const std::vector<double>& cov, double sigma) {
    const std::size_t k2 = static_cast<std::size_t>(std::sqrt(static_cast<double>(cov.size())));
    if (k2 < static_cast<std::size_t>(m) || k2 * k2 != cov.size())
      return Eigen::MatrixXd(Eigen::MatrixXd::Identity(m, m) / sigma);
    Eigen::MatrixXd C(m, m);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) C(a, b) = cov[static_cast<std::size_t>(a) * k2 + b];
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    if (llt.info() != Eigen::Success)
      return Eigen::MatrixXd(Eigen::MatrixXd::Identity(m, m) / sigma);
    return Eigen::MatrixXd(llt.matrixL().solve(Eigen::MatrixXd(Eigen::MatrixXd::Identity(m, m))));
  };
  wx_ = whitening(data.cov_x, data.sigma_x);
  wz_ = whitening(data.cov_z, data.sigma_z);
}

Case Problem::case_at(const Eigen::VectorXd& p) const {
  Case c = case_;
  for (std::size_t j = 0; j < unknowns_.size(); ++j) {
    const double v = to_physical(unknowns_[j], p[static_cast<Eigen::Index>(j)], M0());
    switch (unknowns_[j]) {
      case Unknown::G:
        c.soil.G = v;
        if (c.soil.input == SoilInput::coefficients) {  // the Table 2 scale
          const SoilCoefficients s = table2_coefficients(v);
          c.soil.ksh = s.ksh;
          c.soil.ksv = s.ksv;
          c.soil.csh = s.csh;
          c.soil.csv = s.csv;
        }
        break;
      case Unknown::ksh:
        c.soil.ksh = v;
        break;
      case Unknown::ksv:
        c.soil.ksv = v;
        break;
      case Unknown::mu:
        c.contact.mu = v;
        break;
      case Unknown::MMd:
        c.MMd = v;
        break;
    }
  }
  return c;
}

Eigen::VectorXd Problem::internal_of(const Case& c) const {
  Eigen::VectorXd p(static_cast<Eigen::Index>(unknowns_.size()));
  for (std::size_t j = 0; j < unknowns_.size(); ++j) {
    double v = 0;
    switch (unknowns_[j]) {
      case Unknown::G:
        v = c.soil.G;
        break;
      case Unknown::ksh:
        v = c.soil.ksh;
        break;
      case Unknown::ksv:
        v = c.soil.ksv;
        break;
      case Unknown::mu:
        v = c.contact.mu;
        break;
      case Unknown::MMd:
        v = c.MMd;
        break;
    }
    p[static_cast<Eigen::Index>(j)] =
        std::clamp(to_internal(unknowns_[j], v, M0()), bounds_[j].lo, bounds_[j].hi);
  }
  return p;
}

const Simulated& Problem::simulate_at(const Eigen::VectorXd& p) {
  std::vector<double> key(p.data(), p.data() + p.size());
  const auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;
  Simulated s;
  try {
    const Case c = case_at(p);
    ModelResponse r = run(c, p);
    if (!ok(r.status) && !c.contact.pure_rolling) r = rolling_instead(c, p, r);
    s.ok = ok(r.status);
    s.message = r.message;
    s.friction_ratio = r.friction_ratio;
    s.rolling = s.ok && r.switches_per_period == 0 && !(r.metrics.slip_fraction > 0);
    if (s.ok) {
      for (int n = 1; n <= o_.harmonics; ++n) {
        s.x.push_back(coefficient(r.metrics.ddx_harmonics[n]));
        s.z.push_back(coefficient(r.metrics.ddz_harmonics[n]));
      }
      // The signal's shape only where the residual reads it (a sweep-line area per model run
      // was some 4 % of an identification window that compares harmonics alone).
      if (o_.use_peaks || o_.use_area)
        signal_shape(r.metrics.ddx_harmonics, r.metrics.ddz_harmonics, data_.n_signal, s.ddx_max,
                     s.ddx_min, s.ddz_max, s.ddz_min, s.area);
      s.metrics = r.metrics;
      if (comparison_ == Comparison::sampled) {
        s.signal = std::move(signal_);
        if (s.signal.empty()) {  // (a steady state always has its period)
          s.ok = false;
          s.message = "no steady period recorded";
        }
      }
    }
  } catch (const std::exception& e) {  // an invalid trial case, or the integrator gave up
    s.ok = false;
    s.message = e.what();
  }
  if (cache_.size() > 4096) cache_.clear();
  return cache_.emplace(std::move(key), std::move(s)).first->second;
}

// One bounded model run (the constructor's numerics, kMaxStepsPerRun), within what is left of
// the identification's kMaxStepsPerWindow.
ModelResponse Problem::run(const Case& c, const Eigen::VectorXd& p) {
  long& steps = *steps_used_;
  if (steps >= kMaxStepsPerWindow) {
    ModelResponse out;
    out.status = Status::budget_exceeded;
    out.message = "the model runs of this identification took more than " +
                  std::to_string(kMaxStepsPerWindow) +
                  " integration steps in all without a fit (the model hardly settles for this "
                  "roller: check its parameters)";
    return out;
  }
  ++simulations_;
  // Shooting starts from a steady state found at a neighbour of p no farther than a
  // finite-difference step of the Jacobian (kWarmRadius) with the same friction model: there the
  // two orbits lie on one branch. The nearest of the last kOrbits (the latest of equally near
  // ones): a Jacobian's column at the start point continues the start point's orbit even when
  // the start scan ran another point last. A farther trial (a step of the fit, a profile) starts
  // from rest: from a distant orbit Newton could reach another steady state that coexists with
  // the one from rest, and the model's response would depend on the fit's path. With mu among
  // the unknowns not even a neighbour's orbit is safe: a trial mu can admit both a rolling orbit
  // (the neighbour's, or the pure-rolling one that stands in for a failed run) and the
  // stick-slip orbit the run from rest reaches (seen: a pure-rolling record's G off by 6 %).
  const WarmStart* near = nullptr;
  double nearest = kWarmRadius;
  if (warm_starts_)
    for (auto o = orbits_.rbegin(); o != orbits_.rend(); ++o) {
      if (o->p.size() != p.size() || o->pure_rolling != c.contact.pure_rolling) continue;
      const double d = (p - o->p).cwiseAbs().maxCoeff();
      if (near ? d < nearest : d <= nearest) {
        near = &o->orbit;
        nearest = d;
      }
    }
  std::optional<WarmStart> orbit;
  ModelResponse r =
      simulate_metrics_from(c, n_sim_, std::min(kMaxStepsPerRun, kMaxStepsPerWindow - steps), near,
                            &orbit, comparison_ == Comparison::sampled ? &signal_ : nullptr);
  if (orbit) {
    if (orbits_.size() == kOrbits) orbits_.erase(orbits_.begin());
    orbits_.push_back({p, c.contact.pure_rolling, std::move(*orbit)});
  }
  steps += std::max(r.steps, 1L);
  if (r.status == Status::budget_exceeded && steps >= kMaxStepsPerWindow)
    r.message = "the model runs of this identification took more than " +
                std::to_string(kMaxStepsPerWindow) + " integration steps in all (" + r.message +
                ")";
  return r;
}

// The run from rest of `c` (with slip) failed, which happens for large mu: the transient from
// rest slips, and a slip phase at such mu can end inconsistently (chattering) or diverge
// (docs/model.md section 6). The pure-rolling steady state at the same soil and torque is also
// a steady state of `c` when it never needs more friction than the cone of `c` offers
// (|T| <= mu N throughout): then it is the response at this mu, and every larger mu gives the
// same response (mu is not identifiable there). Otherwise the trial fails with both reasons.
ModelResponse Problem::rolling_instead(const Case& c, const Eigen::VectorXd& p,
                                       const ModelResponse& r) {
  std::vector<double> key(p.data(), p.data() + p.size());
  for (std::size_t j = 0; j < unknowns_.size(); ++j)
    if (unknowns_[j] == Unknown::mu) key[j] = 0;  // the rolling response does not depend on mu
  auto it = rolling_cache_.find(key);
  if (it == rolling_cache_.end()) {
    Case roll = c;
    roll.contact.pure_rolling = true;
    if (rolling_cache_.size() > 1024) rolling_cache_.clear();
    ModelResponse response = run(roll, p);
    it = rolling_cache_.emplace(std::move(key), std::pair{std::move(response), signal_}).first;
  }
  const ModelResponse& roll = it->second.first;
  signal_ = it->second.second;  // the rolling steady state's (Comparison::sampled)
  const double cone = c.contact.mu_static >= 0 ? c.contact.mu_static : c.contact.mu;
  if (ok(roll.status) && roll.friction_ratio <= cone) {
    ModelResponse out = roll;
    out.message =
        "the run from rest failed (" + r.message +
        "); the pure-rolling steady state, which needs mu >= " + num(roll.friction_ratio) +
        ", is the steady state at mu = " + num(cone);
    return out;
  }
  ModelResponse out = r;
  if (ok(roll.status))
    out.message += "; the pure-rolling steady state needs mu >= " + num(roll.friction_ratio);
  return out;
}

// The time shift (as the phase phi = nu tau) that best aligns the model's harmonics with the
// measured ones: maximise sum_n Re(conj(D_n) S_n e^{i n phi}) / sigma^2.
double Problem::best_phase(const Simulated& s) const {
  auto g = [&](double phi, double* d1, double* d2) {
    double v = 0, a = 0, b = 0;
    for (int n = 1; n <= o_.harmonics; ++n) {
      const std::complex<double> e = std::polar(1.0, n * phi);
      const std::complex<double> qx =
          std::conj(data_.ddx[n - 1]) * s.x[n - 1] / (data_.sigma_x * data_.sigma_x);
      const std::complex<double> qz =
          std::conj(data_.ddz[n - 1]) * s.z[n - 1] / (data_.sigma_z * data_.sigma_z);
      const std::complex<double> q = (qx + qz) * e;
      v += q.real();
      a += -n * q.imag();
      b += -n * n * q.real();
    }
    if (d1) *d1 = a;
    if (d2) *d2 = b;
    return v;
  };
  double best = 0, best_v = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 96; ++k) {
    const double phi = 2.0 * M_PI * k / 96;
    const double v = g(phi, nullptr, nullptr);
    if (v > best_v) {
      best_v = v;
      best = phi;
    }
  }
  for (int it = 0; it < 20; ++it) {
    double d1 = 0, d2 = 0;
    g(best, &d1, &d2);
    if (!(d2 < 0)) break;
    const double step = std::clamp(-d1 / d2, -0.05, 0.05);
    best += step;
    if (std::abs(step) < 1e-13) break;
  }
  // The above weighs each signal's harmonics alike; with the full covariance the minimum moves
  // a little: Brent's method on the weighted objective itself, within one grid step.
  Eigen::VectorXd r(4 * o_.harmonics);
  auto objective = [&](double phi) {
    harmonic_residual(s, phi, r);
    return r.squaredNorm();
  };
  std::uintmax_t iterations = 60;
  const double h = 2.0 * M_PI / 96;
  return boost::math::tools::brent_find_minima(objective, best - h, best + h, 40, iterations).first;
}

void Problem::compared(const Simulated& s, double phi, std::vector<std::complex<double>>& x,
                       std::vector<std::complex<double>>& z) const {
  const int H = o_.harmonics;
  x.assign(static_cast<std::size_t>(H), 0.0);
  z.assign(static_cast<std::size_t>(H), 0.0);
  if (!s.ok || (comparison_ == Comparison::sampled && s.signal.empty())) {  // a failed trial
    const double nan = std::numeric_limits<double>::quiet_NaN();
    x.assign(static_cast<std::size_t>(H), {nan, nan});
    z.assign(static_cast<std::size_t>(H), {nan, nan});
    return;
  }
  if (comparison_ == Comparison::harmonics) {
    for (int n = 1; n <= H; ++n) {
      const std::complex<double> e = std::polar(1.0, n * phi);
      x[static_cast<std::size_t>(n - 1)] = s.x[static_cast<std::size_t>(n - 1)] * e;
      z[static_cast<std::size_t>(n - 1)] = s.z[static_cast<std::size_t>(n - 1)] * e;
    }
    return;
  }
  // The window's fit (a linear map of its samples) of the model at the window's times: record
  // time t_ref + s is model time s + phi / (2 pi f) (identify.cpp, the time shift). The harmonics
  // the fit resolves come out as C_n e^{i n phi}; those above alias as the record's own do.
  const std::size_t K2 = data_.alias_w.size() / data_.alias_t.size();
  const double shift = phi / (2.0 * M_PI * data_.f);
  for (std::size_t i = 0; i < data_.alias_t.size(); ++i) {
    const auto [yx, yz] = s.signal.at(data_.alias_t[i] + shift);
    const double* w = &data_.alias_w[i * K2];
    for (int n = 0; n < H; ++n) {
      const auto k = static_cast<std::size_t>(n);
      x[k] += std::complex<double>(w[2 * k] * yx, w[2 * k + 1] * yx);
      z[k] += std::complex<double>(w[2 * k] * yz, w[2 * k + 1] * yz);
    }
  }
}

void Problem::harmonic_residual(const Simulated& s, double phi, Eigen::VectorXd& r) const {
  const int m = 2 * o_.harmonics;
  Eigen::VectorXd vx(m), vz(m);
  std::vector<std::complex<double>> cx, cz;
  compared(s, phi, cx, cz);
  for (int n = 1; n <= o_.harmonics; ++n) {
    const std::complex<double> dx = data_.ddx[n - 1] - cx[static_cast<std::size_t>(n - 1)];
    const std::complex<double> dz = data_.ddz[n - 1] - cz[static_cast<std::size_t>(n - 1)];
    vx[2 * n - 2] = dx.real();
    vx[2 * n - 1] = dx.imag();
    vz[2 * n - 2] = dz.real();
    vz[2 * n - 1] = dz.imag();
  }
  r.head(m) = wx_ * vx;
  r.segment(m, m) = wz_ * vz;
}

bool Problem::residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) {
  double phi = 0;
  return residual(p, r, phi);
}

bool Problem::residual(const Eigen::VectorXd& p, Eigen::VectorXd& r, double& phi) {
  const Simulated& s = simulate_at(p);
  if (!s.ok) return false;
  phi = best_phase(s);
  r.resize(rows_);
  harmonic_residual(s, phi, r);
  Eigen::Index i = 4 * o_.harmonics;
  const double sq = std::sqrt(data_.n_signal + 0.5);
  if (o_.use_peaks) {
    r[i++] = (data_.ddx_max - s.ddx_max) / (data_.sigma_x * sq);
    r[i++] = (data_.ddx_min - s.ddx_min) / (data_.sigma_x * sq);
    r[i++] = (data_.ddz_max - s.ddz_max) / (data_.sigma_z * sq);
    r[i++] = (data_.ddz_min - s.ddz_min) / (data_.sigma_z * sq);
  }
  if (o_.use_area) {
    const double sa = sq * (data_.sigma_z * (data_.ddx_max - data_.ddx_min) +
                            data_.sigma_x * (data_.ddz_max - data_.ddz_min));
    r[i++] = (data_.area - s.area) / sa;
  }
  return true;
}

MeasuredResponse flipped(MeasuredResponse d, bool x, bool z) {
  if (x) {
    for (auto& c : d.ddx) c = -c;
    for (double& c : d.trend_x) c = -c;
    d.ddx_max = -std::exchange(d.ddx_min, -d.ddx_max);
  }
  if (z) {
    for (auto& c : d.ddz) c = -c;
    for (double& c : d.trend_z) c = -c;
    d.ddz_max = -std::exchange(d.ddz_min, -d.ddz_max);
  }
  return d;
}

std::string dead_channel(bool x, const std::string& where) {
  return std::string(x ? "x_M''" : "z_M''") + " is one value in every sample of " + where +
         " (a dead or disconnected channel, or a column that is not the drum's " +
         (x ? "horizontal" : "vertical") +
         " acceleration): the model is fitted to x_M'' and z_M'' together; give the logger's " +
         (x ? "horizontal channel with --x-col" : "vertical channel with --z-col");
}

void require_live_channels(std::span<const double> ddx, std::span<const double> ddz,
                           const std::string& where) {
  for (const bool x : {true, false}) {
    const std::span<const double> y = x ? ddx : ddz;
    if (one_value(y)) throw Error(dead_channel(x, where));
  }
}

MeasuredResponse swapped(MeasuredResponse d) {
  std::swap(d.ddx, d.ddz);
  std::swap(d.cov_x, d.cov_z);
  std::swap(d.sigma_x, d.sigma_z);
  std::swap(d.noise_x, d.noise_z);
  std::swap(d.trend_x, d.trend_z);
  std::swap(d.ddx_max, d.ddz_max);
  std::swap(d.ddx_min, d.ddz_min);
  return d;
}

MeasuredResponse scaled(MeasuredResponse d, double s) {
  return scaled_channels(std::move(d), s, s);
}

MeasuredResponse scaled_channels(MeasuredResponse d, double sx, double sz) {
  for (auto& c : d.ddx) c *= sx;
  for (auto& c : d.ddz) c *= sz;
  for (double& c : d.cov_x) c *= sx * sx;
  for (double& c : d.cov_z) c *= sz * sz;
  for (double& c : d.trend_x) c *= sx;
  for (double& c : d.trend_z) c *= sz;
  d.sigma_x *= sx;
  d.sigma_z *= sz;
  d.noise_x *= sx;
  d.noise_z *= sz;
  d.ddx_max *= sx;
  d.ddx_min *= sx;
  d.ddz_max *= sz;
  d.ddz_min *= sz;
  d.area *= sx * sz;
  return d;
}

void check_gain_uncertainty(double gain_uncertainty) {
  if (!(gain_uncertainty >= 0.0 && gain_uncertainty <= 0.5))
    throw Error(
        "identify: gain_uncertainty (--gain-uncertainty) must be in [0, 0.5] (a relative "
        "standard uncertainty of each channel's gain); got " +
        shortest(gain_uncertainty));
}

std::string open_reading_warning(bool z_negated, bool in_g, double chi2, double s2,
                                 const std::string& where) {
  const bool both = z_negated && in_g;
  const std::string what = both   ? "the accelerations fitted in g (x 9.80665) and z_M'' negated"
                           : in_g ? "the accelerations fitted in g (x 9.80665)"
                                  : "z_M'' fitted negated";
  const std::string why = both   ? "the record's columns have no unit and are in g, and its z "
                                   "axis points up"
                          : in_g ? "the record's columns have no unit and are in g"
                                 : "the record's z axis points up";
  const std::string as_read = both   ? "as read in m/s^2, pointing down"
                              : in_g ? "as read in m/s^2"
                                     : "as read pointing down";
  const std::string give =
      both   ? "give --units g --z-positive up to read it so, or --units m/s2 --z-positive down "
               "to fit it as read (Python: the arrays in m/s^2 and z_positive)"
      : in_g ? "give --units g to read it so, or --units m/s2 to fit it as read (Python: the "
               "arrays in m/s^2)"
             : "give --z-positive up to read it so, or --z-positive down to fit it as read "
               "(Python: z_positive)";
  return what + (where.empty() ? "" : " in " + where) + ": " + why + " (reduced chi^2 " +
         num(std::round(chi2 * 100) / 100) + " so, " + num(std::round(s2)) + " " + as_read +
         "; nothing in the columns tells): " + give;
}

}  // namespace oscidrum::detail
