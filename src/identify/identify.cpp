// Identification of the soil from measured accelerations (identify.hpp, docs/identify.md):
// Levenberg-Marquardt on the complex harmonics, the record's time origin projected out, standard
// uncertainties from the Jacobian, 95 % intervals from the profile of the objective.
#include "oscidrum/identify.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "oscidrum/error.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/simulate.hpp"
#include "oscidrum/soil.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr long kMaxStepsPerRun = 400000;  // integration steps of one model run (about 0.5 s)
std::string num(double v) { return detail::shortest(v); }

// ---- the forward model, reduced to what the fit compares --------------------------------------

struct Simulated {
  bool ok = false;
  std::string message;
  std::vector<std::complex<double>> x, z;  // C_n, n = 1 ... N
  double ddx_max = 0, ddx_min = 0, ddz_max = 0, ddz_min = 0, area = 0;
  Metrics metrics;
  double friction_ratio = kNaN;  // largest |T| / N of the steady state
  bool rolling = false;          // the steady state sticks throughout (no slip)
};

std::complex<double> coefficient(const Harmonic& h) { return std::polar(h.amplitude, h.phase); }

// Extremes and area of the periodic signal made of harmonics 0 ... n (as for a record).
void signal_shape(const std::vector<Harmonic>& hx, const std::vector<Harmonic>& hz, int n,
                  double& xmax, double& xmin, double& zmax, double& zmin, double& area) {
  constexpr int kSamples = 512;
  std::vector<double> x(kSamples), z(kSamples);
  for (int j = 0; j < kSamples; ++j) {
    const double w = 2.0 * M_PI * j / kSamples;
    double sx = 0, sz = 0;
    for (int k = 0; k <= n && k < static_cast<int>(hx.size()); ++k) {
      sx += hx[k].amplitude * std::sin(k * w + hx[k].phase);
      sz += hz[k].amplitude * std::sin(k * w + hz[k].phase);
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

// ---- parameters --------------------------------------------------------------------------------

enum class Kind { G, ksh, ksv, mu, MMd };

struct Parameter {
  Kind kind;
  double lo, hi;  // bounds of the internal coordinate
};

// Internal coordinates: ln G, ln ksh, ln ksv, ln mu, MMd / M0.
double to_internal(Kind k, double v, double M0) { return k == Kind::MMd ? v / M0 : std::log(v); }
double to_physical(Kind k, double p, double M0) { return k == Kind::MMd ? p * M0 : std::exp(p); }
const char* name_of(Kind k) {
  switch (k) {
    case Kind::G:
      return "G";
    case Kind::ksh:
      return "ksh";
    case Kind::ksv:
      return "ksv";
    case Kind::mu:
      return "mu";
    case Kind::MMd:
      return "MMd";
  }
  return "";
}
const char* unit_of(Kind k) {
  switch (k) {
    case Kind::G:
      return "Pa";
    case Kind::ksh:
    case Kind::ksv:
      return "N/m";
    case Kind::mu:
      return "-";
    case Kind::MMd:
      return "N m";
  }
  return "";
}

// ---- the problem -------------------------------------------------------------------------------

class Problem {
 public:
  Problem(const Case& base, const MeasuredResponse& data, const IdentifyOptions& o)
      : data_(data), o_(o) {
    case_ = base;
    const double scale = data.f / base.roller.f;
    case_.roller.f = data.f;
    case_.roller.M0 = base.roller.M0 * scale * scale;  // M0 grows with f^2 (5)
    n_sim_ = std::max(o.harmonics, data.n_signal);
    case_.numerics.samples_per_period = std::max(64, 4 * n_sim_ + 8);
    case_.numerics.output_periods = 1;
    // Every model run is bounded, so that no trial the optimiser visits can take long: one that
    // has not settled in 1500 periods, needs more than 2000 steps in one period (a diverging slip
    // phase, a stiff corner of the parameter space) or more than kMaxStepsPerRun steps in all is
    // a failed trial (Simulated::ok false, with the run's message), not waited for. The paper's
    // cases need 40-130 steps per period at rtol 1e-6 and at most ~140 000 in all (G = 2e9 Pa,
    // pure rolling, about 1100 periods).
    case_.numerics.max_periods = std::min(base.numerics.max_periods, 1500);
    case_.numerics.max_steps_per_period = std::min(base.numerics.max_steps_per_period, 2000);
    if (o.shooting) case_.numerics.method = SteadyMethod::shooting;
    // The model to 1e-6 (its harmonics change by about that much; the measured ones are known to
    // about 1e-3), three times faster than the default 1e-8.
    case_.numerics.rtol = std::max(base.numerics.rtol, o.model_tolerance);
    case_.numerics.steady_tol = std::max(base.numerics.steady_tol, o.model_tolerance);
    if (o.modulus) {
      case_.soil.input = SoilInput::modulus;
      params_.push_back({Kind::G, std::log(1e5), std::log(2e9)});
    } else {
      case_.soil.input = SoilInput::coefficients;
      params_.push_back({Kind::ksh, std::log(1e5), std::log(1e11)});
      params_.push_back({Kind::ksv, std::log(1e5), std::log(1e11)});
    }
    if (o.fit_mu) {
      case_.contact.pure_rolling = false;
      params_.push_back({Kind::mu, std::log(0.05), std::log(5.0)});
    }
    if (o.fit_MMd) params_.push_back({Kind::MMd, -0.5, 0.5});
    rows_ = 4 * o.harmonics + (o.use_peaks ? 4 : 0) + (o.use_area ? 1 : 0);
  }

  const std::vector<Parameter>& params() const { return params_; }
  int rows() const { return rows_; }
  int simulations() const { return simulations_; }
  double M0() const { return case_.roller.M0; }
  const Case& base() const { return case_; }

  Case case_at(const Eigen::VectorXd& p) const {
    Case c = case_;
    for (std::size_t j = 0; j < params_.size(); ++j) {
      const double v = to_physical(params_[j].kind, p[static_cast<Eigen::Index>(j)], M0());
      switch (params_[j].kind) {
        case Kind::G:
          c.soil.G = v;
          break;
        case Kind::ksh:
          c.soil.ksh = v;
          break;
        case Kind::ksv:
          c.soil.ksv = v;
          break;
        case Kind::mu:
          c.contact.mu = v;
          break;
        case Kind::MMd:
          c.MMd = v;
          break;
      }
    }
    return c;
  }

  Eigen::VectorXd internal_of(const Case& c) const {
    Eigen::VectorXd p(static_cast<Eigen::Index>(params_.size()));
    for (std::size_t j = 0; j < params_.size(); ++j) {
      double v = 0;
      switch (params_[j].kind) {
        case Kind::G:
          v = c.soil.G;
          break;
        case Kind::ksh:
          v = c.soil.ksh;
          break;
        case Kind::ksv:
          v = c.soil.ksv;
          break;
        case Kind::mu:
          v = c.contact.mu;
          break;
        case Kind::MMd:
          v = c.MMd;
          break;
      }
      p[static_cast<Eigen::Index>(j)] =
          std::clamp(to_internal(params_[j].kind, v, M0()), params_[j].lo, params_[j].hi);
    }
    return p;
  }

  const Simulated& simulate_at(const Eigen::VectorXd& p) {
    std::vector<double> key(p.data(), p.data() + p.size());
    const auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    Simulated s;
    try {
      const Case c = case_at(p);
      ModelResponse r = run(c);
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
        signal_shape(r.metrics.ddx_harmonics, r.metrics.ddz_harmonics, data_.n_signal, s.ddx_max,
                     s.ddx_min, s.ddz_max, s.ddz_min, s.area);
        s.metrics = r.metrics;
      }
    } catch (const std::exception& e) {  // an invalid trial case, or the integrator gave up
      s.ok = false;
      s.message = e.what();
    }
    if (cache_.size() > 4096) cache_.clear();
    return cache_.emplace(std::move(key), std::move(s)).first->second;
  }

  // One bounded model run (the constructor's numerics, kMaxStepsPerRun).
  ModelResponse run(const Case& c) {
    ++simulations_;
    return simulate_metrics(c, n_sim_, kMaxStepsPerRun);
  }

  // The run from rest of `c` (with slip) failed, which happens for large mu: the transient from
  // rest slips, and a slip phase at such mu can end inconsistently (chattering) or diverge
  // (docs/model.md section 6). The pure-rolling steady state at the same soil and torque is also
  // a steady state of `c` when it never needs more friction than the cone of `c` offers
  // (|T| <= mu N throughout): then it is the response at this mu, and every larger mu gives the
  // same response (mu is not identifiable there). Otherwise the trial fails with both reasons.
  ModelResponse rolling_instead(const Case& c, const Eigen::VectorXd& p, const ModelResponse& r) {
    std::vector<double> key(p.data(), p.data() + p.size());
    for (std::size_t j = 0; j < params_.size(); ++j)
      if (params_[j].kind == Kind::mu) key[j] = 0;  // the rolling response does not depend on mu
    auto it = rolling_cache_.find(key);
    if (it == rolling_cache_.end()) {
      Case roll = c;
      roll.contact.pure_rolling = true;
      if (rolling_cache_.size() > 1024) rolling_cache_.clear();
      it = rolling_cache_.emplace(std::move(key), run(roll)).first;
    }
    const ModelResponse& roll = it->second;
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
  double best_phase(const Simulated& s) const {
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
    return best;
  }

  // Weighted residuals at p (empty if the model failed there); phi receives the time shift.
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r, double* phi_out = nullptr) {
    const Simulated& s = simulate_at(p);
    if (!s.ok) return false;
    const double phi = best_phase(s);
    if (phi_out) *phi_out = phi;
    r.resize(rows_);
    Eigen::Index i = 0;
    for (int n = 1; n <= o_.harmonics; ++n) {
      const std::complex<double> e = std::polar(1.0, n * phi);
      const std::complex<double> dx = (data_.ddx[n - 1] - s.x[n - 1] * e) / data_.sigma_x;
      const std::complex<double> dz = (data_.ddz[n - 1] - s.z[n - 1] * e) / data_.sigma_z;
      r[i++] = dx.real();
      r[i++] = dx.imag();
      r[i++] = dz.real();
      r[i++] = dz.imag();
    }
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

 private:
  MeasuredResponse data_;
  IdentifyOptions o_;
  Case case_;
  std::vector<Parameter> params_;
  int n_sim_ = 10, rows_ = 0, simulations_ = 0;
  std::map<std::vector<double>, Simulated> cache_;
  std::map<std::vector<double>, ModelResponse> rolling_cache_;
};

// ---- Levenberg-Marquardt with a mask of fixed parameters --------------------------------------

struct Fit {
  Eigen::VectorXd p, r;
  Eigen::MatrixXd J;       // the last Jacobian, at a point at most last_step from p
  double last_step = 1.0;  // size of the last accepted step (internal coordinates)
  double S = std::numeric_limits<double>::infinity();
  int iterations = 0;
  bool converged = false;
  std::string message;
};

constexpr double kStep = 1e-3;  // finite-difference step of the internal coordinates

bool jacobian(Problem& pr, const Eigen::VectorXd& p, const Eigen::VectorXd& r,
              const std::vector<bool>& free, Eigen::MatrixXd& J) {
  J.setZero(pr.rows(), p.size());
  for (Eigen::Index j = 0; j < p.size(); ++j) {
    if (!free[static_cast<std::size_t>(j)]) continue;
    const Parameter& par = pr.params()[static_cast<std::size_t>(j)];
    Eigen::VectorXd q = p;
    double h = kStep;
    if (q[j] + h > par.hi) h = -h;  // step inwards at the upper bound
    q[j] += h;
    Eigen::VectorXd rq;
    if (!pr.residual(q, rq)) {
      q[j] = p[j] - h;  // the other side
      if (!pr.residual(q, rq)) return false;
      h = -h;
    }
    J.col(j) = (rq - r) / h;
  }
  return true;
}

Fit levenberg_marquardt(Problem& pr, Eigen::VectorXd p, const std::vector<bool>& free,
                        int max_iterations) {
  Fit fit;
  fit.p = p;
  if (!pr.residual(p, fit.r)) {
    fit.message = "the model fails at the start";
    return fit;
  }
  fit.S = fit.r.squaredNorm();
  double lambda = 1e-3;
  Eigen::MatrixXd J;
  for (int it = 0; it < max_iterations; ++it) {
    fit.iterations = it + 1;
    if (!jacobian(pr, fit.p, fit.r, free, J)) {
      fit.message = "the model fails next to the estimate";
      return fit;
    }
    fit.J = J;
    fit.last_step = 1.0;
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * fit.r;
    bool accepted = false;
    double step_norm = 0, gain = 0;
    while (lambda < 1e12) {
      Eigen::MatrixXd M = A;
      for (Eigen::Index j = 0; j < A.rows(); ++j)
        M(j, j) = free[static_cast<std::size_t>(j)] ? A(j, j) * (1 + lambda) + 1e-12 : 1.0;
      Eigen::VectorXd dp = -M.ldlt().solve(g);
      for (Eigen::Index j = 0; j < dp.size(); ++j)
        if (!free[static_cast<std::size_t>(j)]) dp[j] = 0;
      // Trust region: internal coordinates move at most 0.7 (a factor 2 in G) per step.
      const double big = dp.cwiseAbs().maxCoeff();
      if (big > 0.7) dp *= 0.7 / big;
      if (big < 1e-7) break;  // the steps have shrunk to nothing: at the minimum
      Eigen::VectorXd q = fit.p + dp;
      for (Eigen::Index j = 0; j < q.size(); ++j)
        q[j] = std::clamp(q[j], pr.params()[static_cast<std::size_t>(j)].lo,
                          pr.params()[static_cast<std::size_t>(j)].hi);
      Eigen::VectorXd rq;
      if (pr.residual(q, rq) && rq.squaredNorm() < fit.S) {
        gain = fit.S - rq.squaredNorm();
        step_norm = (q - fit.p).cwiseAbs().maxCoeff();
        fit.p = q;
        fit.r = rq;
        fit.S = rq.squaredNorm();
        fit.last_step = step_norm;
        lambda = std::max(lambda / 5, 1e-9);
        accepted = true;
        break;
      }
      lambda *= 8;
    }
    if (!accepted) {
      fit.converged = true;  // no step lowers the objective: a minimum (to the FD precision)
      fit.message = "no step lowers the objective";
      return fit;
    }
    // 1e-4 in ln G is 0.01 % of G, far below any uncertainty the data allow.
    if (step_norm < 1e-4 || gain < 1e-8 * fit.S) {
      fit.converged = true;
      fit.message = "converged";
      return fit;
    }
  }
  fit.message = "iteration limit reached";
  return fit;
}

double t_quantile(double dof) {
  const boost::math::students_t t(std::max(1.0, dof));
  return boost::math::quantile(t, 0.975);
}

}  // namespace

// ---- public functions --------------------------------------------------------------------------

ModelResponse simulate_metrics(const Case& c, int n_max, long max_steps) {
  const Model model(c);
  // The budget counts the flow's polls of `cancelled`: one per accepted integration step.
  long steps = 0;
  std::function<bool()> over_budget;
  if (max_steps > 0) over_budget = [&steps, max_steps] { return ++steps > max_steps; };
  const Result r = simulate(model, {}, over_budget);
  ModelResponse out;
  out.status = r.status;
  out.message = r.message;
  out.friction_ratio = kNaN;
  if (r.status == Status::cancelled && max_steps > 0 && steps > max_steps) {
    out.status = Status::budget_exceeded;
    out.message = "no steady state within " + std::to_string(max_steps) +
                  " integration steps (the budget of one model run; " + r.message + ")";
    return out;
  }
  if (!r.samples.t.empty()) out.metrics = compute_metrics(r, n_max);
  if (r.status == Status::steady_state) {
    double ratio = 0;
    for (std::size_t j = 0; j < r.samples.size(); ++j)
      ratio = std::max(ratio, std::abs(r.samples.T[j]) / r.samples.N[j]);
    out.friction_ratio = ratio;
    out.switches_per_period = r.diagnostics.switches_per_period;
  }
  return out;
}

MeasuredResponse measured_response(const RecordMetrics& m, double f, std::size_t samples) {
  if (m.ddx_harmonics.size() < 2 || samples == 0)
    throw Error("identify: the record's metrics hold no harmonics");
  MeasuredResponse d;
  d.f = f;
  d.n_signal = static_cast<int>(m.ddx_harmonics.size()) - 1;
  double px = 0, pz = 0;  // mean square of the fitted signals
  for (std::size_t n = 0; n < m.ddx_harmonics.size(); ++n) {
    const double k = n == 0 ? 1.0 : 0.5;
    px += k * m.ddx_harmonics[n].amplitude * m.ddx_harmonics[n].amplitude;
    pz += k * m.ddz_harmonics[n].amplitude * m.ddz_harmonics[n].amplitude;
    if (n > 0) {
      d.ddx.push_back(coefficient(m.ddx_harmonics[n]));
      d.ddz.push_back(coefficient(m.ddz_harmonics[n]));
    }
  }
  // residual = s / rms with rms^2 = fitted^2 + s^2, so s^2 = fitted^2 r^2 / (1 - r^2).
  auto noise = [](double fitted, double r) {
    const double rr = std::min(r * r, 0.99);
    return std::sqrt(fitted * rr / (1.0 - rr));
  };
  const double k = std::sqrt(2.0 / static_cast<double>(samples));
  // A floor (1e-6 of the signal) keeps the weights finite for noise-free records.
  d.sigma_x = std::max(noise(px, m.residual_x) * k, 1e-6 * std::sqrt(px) + 1e-300);
  d.sigma_z = std::max(noise(pz, m.residual_z) * k, 1e-6 * std::sqrt(pz) + 1e-300);
  d.ddx_max = m.ddx_max;
  d.ddx_min = m.ddx_min;
  d.ddz_max = m.ddz_max;
  d.ddz_min = m.ddz_min;
  d.area = m.area;
  return d;
}

Identification identify(const Case& base, const MeasuredResponse& data, const IdentifyOptions& o,
                        const Identification* start) {
  if (!(std::isfinite(data.f) && data.f > 0))
    throw Error("identify: f must be > 0 [Hz]; got " + num(data.f));
  if (o.harmonics < 1 || static_cast<int>(data.ddx.size()) < o.harmonics ||
      static_cast<int>(data.ddz.size()) < o.harmonics)
    throw Error("identify: harmonics must be in [1, " + std::to_string(data.ddx.size()) +
                "] (the measured ones); got " + std::to_string(o.harmonics));
  if (!(data.sigma_x > 0 && data.sigma_z > 0))
    throw Error("identify: the uncertainties of the measured harmonics must be > 0");
  Problem pr(base, data, o);
  const std::size_t q = pr.params().size();
  const int dof = pr.rows() - static_cast<int>(q) - 1;  // - 1: the time shift
  if (dof < 1)
    throw Error("identify: " + std::to_string(pr.rows()) + " measured values are too few for " +
                std::to_string(q) + " unknowns and the time shift; use more --harmonics");
  const std::vector<bool> all(q, true);

  // Start: the previous window's estimate, else the best of a coarse scan of the soil.
  Eigen::VectorXd p0 = pr.internal_of(start ? start->fitted : pr.base());
  if (start && o.fit_mu && start->fitted.contact.pure_rolling) p0 = pr.internal_of(pr.base());
  if (!start) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::VectorXd best_p = p0;
    const Roller roller = pr.base().roller;
    // With mu unknown, the scan is made at the case's mu and at the largest mu (a drum that
    // does not slip): a record of a rolling drum is far from any slipping response.
    std::vector<Eigen::VectorXd> starts{p0};
    for (std::size_t j = 0; j < q; ++j) {
      if (pr.params()[j].kind != Kind::mu) continue;
      Eigen::VectorXd p = p0;
      p[static_cast<Eigen::Index>(j)] = pr.params()[j].hi;
      starts.push_back(p);
    }
    for (const Eigen::VectorXd& p_start : starts)
      for (const double G : {4e6, 8e6, 16e6, 32e6, 64e6, 128e6}) {
        Eigen::VectorXd p = p_start;
        if (o.modulus) {
          p[0] = std::log(G);
        } else {
          const SoilCoefficients s =
              soil_coefficients(G, pr.base().soil.nu, pr.base().soil.rho, roller);
          p[0] = std::log(s.ksh);
          p[1] = std::log(s.ksv);
        }
        Eigen::VectorXd r;
        if (pr.residual(p, r) && r.squaredNorm() < best) {
          best = r.squaredNorm();
          best_p = p;
        }
      }
    if (!std::isfinite(best))
      throw Error("identify: the model fails for every start (G = 4 ... 128 MN/m^2)");
    p0 = best_p;
  }
  Fit fit = levenberg_marquardt(pr, p0, all, o.max_iterations);
  if (!std::isfinite(fit.S)) throw Error("identify: " + fit.message);

  Identification id;
  id.f = data.f;
  id.converged = fit.converged;
  id.message = fit.message;
  id.iterations = fit.iterations;
  double phi = 0;
  Eigen::VectorXd r;
  pr.residual(fit.p, r, &phi);
  id.time_shift = phi / (2.0 * M_PI * data.f);
  const double s2 = fit.S / dof;
  id.reduced_chi2 = s2;
  id.fitted = pr.case_at(fit.p);
  id.simulated = pr.simulate_at(fit.p).metrics;
  {
    const Simulated& s = pr.simulate_at(fit.p);
    double num2 = 0, den2 = 0;
    for (int n = 1; n <= o.harmonics; ++n) {
      const std::complex<double> e = std::polar(1.0, n * phi);
      num2 +=
          std::norm(data.ddx[n - 1] - s.x[n - 1] * e) + std::norm(data.ddz[n - 1] - s.z[n - 1] * e);
      den2 += std::norm(data.ddx[n - 1]) + std::norm(data.ddz[n - 1]);
    }
    id.rms_residual = std::sqrt(num2 / (2.0 * o.harmonics));
    id.relative_residual = den2 > 0 ? std::sqrt(num2 / den2) : kNaN;
  }
  // The uncertainties grow with the residual (s^2 below), but a bias does not show in them.
  if (s2 > o.max_reduced_chi2)
    id.warnings.push_back(
        "poor fit: reduced chi^2 " + num(std::round(s2 * 10) / 10) + " > " +
        num(o.max_reduced_chi2) + " (relative residual " +
        num(std::round(id.relative_residual * 1000) / 1000) +
        "): the model does not reproduce the measured harmonics to their noise, and the "
        "estimates are biased by what it lacks (an unknown not fitted, such as mu or MMd, or "
        "a case that does not describe the roller)");

  // Covariance s^2 (J^T J)^-1, condition number and correlations of the column-scaled Jacobian.
  Eigen::MatrixXd J;
  Eigen::VectorXd se = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(q), kNaN);
  bool have_J = fit.J.rows() == r.size() && fit.last_step < 1e-3;  // close enough: reuse
  if (have_J) J = fit.J;
  if (have_J || jacobian(pr, fit.p, r, all, J)) {
    Eigen::VectorXd norms = J.colwise().norm();
    Eigen::MatrixXd Js = J;
    for (Eigen::Index j = 0; j < Js.cols(); ++j) {
      if (norms[j] > 0) Js.col(j) /= norms[j];
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js);
    const auto sv = svd.singularValues();
    id.condition =
        sv[sv.size() - 1] > 0 ? sv[0] / sv[sv.size() - 1] : std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < J.cols(); ++j)
      if (!(norms[j] > 0))
        id.warnings.push_back(std::string(name_of(pr.params()[static_cast<std::size_t>(j)].kind)) +
                              " has no effect on the fit: it cannot be identified from these data");
    if (id.condition > o.max_condition)
      id.warnings.push_back("near-singular Jacobian (condition number " +
                            num(std::round(id.condition)) +
                            "): the parameters cannot be told apart");
    const Eigen::MatrixXd Ai =
        (Js.transpose() * Js).completeOrthogonalDecomposition().pseudoInverse();
    for (Eigen::Index j = 0; j < J.cols(); ++j) {
      se[j] = norms[j] > 0 ? std::sqrt(s2 * Ai(j, j)) / norms[j] : kNaN;
      for (Eigen::Index k = j + 1; k < J.cols(); ++k) {
        const double c = Ai(j, k) / std::sqrt(Ai(j, j) * Ai(k, k));
        if (std::abs(c) > o.max_correlation)
          id.warnings.push_back(
              std::string(name_of(pr.params()[static_cast<std::size_t>(j)].kind)) + " and " +
              name_of(pr.params()[static_cast<std::size_t>(k)].kind) +
              " cannot be told apart (correlation " + num(std::round(c * 1000) / 1000) + ")");
      }
    }
  } else {
    id.warnings.push_back("the model fails next to the estimate: no uncertainties");
  }

  // Profile intervals: S_profile(p_j) = S_min + s^2 t^2 (two-sided 95 %, dof degrees of freedom).
  const double c = t_quantile(dof);
  for (std::size_t j = 0; j < q; ++j) {
    const Parameter& par = pr.params()[j];
    const Eigen::Index J_ = static_cast<Eigen::Index>(j);
    Estimate e;
    e.name = name_of(par.kind);
    e.unit = unit_of(par.kind);
    const double pj = fit.p[J_];
    e.value = to_physical(par.kind, pj, pr.M0());
    e.standard_uncertainty =
        par.kind == Kind::MMd ? se[J_] * pr.M0() : e.value * se[J_];  // d exp(p) = exp(p) dp
    e.lower = e.upper = kNaN;
    if (o.profile && !std::isfinite(se[J_])) {
      // No effect on the fit: nothing to profile; the parameter is not identifiable.
      e.lower_open = e.upper_open = true;
    } else if (o.profile) {
      std::vector<bool> others(q, true);
      others[j] = false;
      for (const int side : {-1, 1}) {
        const double bound = side < 0 ? par.lo : par.hi;
        double step = std::isfinite(se[J_]) && se[J_] > 0 ? c * se[J_] : 0.05;
        step = std::min(step, std::abs(bound - pj));
        double lo_step = 0, lo_delta = 0, hi_step = kNaN, hi_delta = kNaN;
        Eigen::VectorXd warm = fit.p;
        bool found = false, open = false;
        std::string failure;  // why the model failed at hi_step (when hi_delta is infinite)
        for (int k = 0; k < 7 && step > 0; ++k) {
          Eigen::VectorXd p = warm;
          p[J_] = pj + side * step;
          double S = kNaN;
          if (q > 1) {
            const Fit inner = levenberg_marquardt(pr, p, others, 5);
            if (std::isfinite(inner.S)) {
              S = inner.S;
              warm = inner.p;
            }
          } else {
            Eigen::VectorXd rr;
            if (pr.residual(p, rr)) S = rr.squaredNorm();
          }
          if (!std::isfinite(S)) {  // the model fails out there: stop at the last good point
            failure = pr.simulate_at(p).message;
            hi_step = step;
            hi_delta = std::numeric_limits<double>::infinity();
            step = 0.5 * (lo_step + step);
            continue;
          }
          const double delta = std::sqrt(std::max(0.0, S - fit.S) / s2);
          if (std::abs(delta - c) < 0.03 * c) {
            found = true;
            lo_step = step;
            break;
          }
          if (delta < c) {
            lo_step = step;
            lo_delta = delta;
            if (std::abs(pj + side * step - bound) < 1e-12) {
              open = true;
              break;
            }
          } else {
            hi_step = step;
            hi_delta = delta;
          }
          if (std::isfinite(hi_step)) {  // regula falsi on delta, linear in the step
            step = std::isfinite(hi_delta)
                       ? lo_step + (c - lo_delta) * (hi_step - lo_step) / (hi_delta - lo_delta)
                       : 0.5 * (lo_step + hi_step);
          } else {
            step = lo_delta > 0.05 * c ? step * std::min(4.0, 1.1 * c / lo_delta) : step * 4;
            step = std::min(step, std::abs(bound - pj));
          }
        }
        const double at = to_physical(par.kind, pj + side * lo_step, pr.M0());
        if (found || open) {
          (side < 0 ? e.lower : e.upper) = at;
        } else if (std::isfinite(hi_step) && !std::isfinite(hi_delta)) {
          // Where the model fails, the data have not excluded anything: that is no limit.
          id.warnings.push_back("no 95 % " + std::string(side < 0 ? "lower" : "upper") +
                                " limit of " + e.name + ": the profile stays below it up to " +
                                e.name + " = " + num(at) + " and the model fails beyond (" +
                                (failure.empty() ? std::string("no steady state") : failure) + ")");
        } else if (std::isfinite(hi_step)) {
          (side < 0 ? e.lower : e.upper) =
              to_physical(par.kind, pj + side * 0.5 * (lo_step + hi_step), pr.M0());
        }
        if (open || (!found && !std::isfinite(hi_step))) {
          (side < 0 ? e.lower_open : e.upper_open) = true;
          id.warnings.push_back("flat profile: " + e.name +
                                (side < 0 ? " has no lower" : " has no upper") +
                                " 95 % limit within its range; it is not identifiable from "
                                "these data");
        }
      }
    }
    id.estimates.push_back(e);
  }
  // mu of a drum that does not slip: every mu above the friction the steady state needs gives
  // the same response, whatever the Jacobian or the profile (within the budget) saw.
  const Simulated& at_estimate = pr.simulate_at(fit.p);
  for (Estimate& e : id.estimates) {
    if (e.name != "mu" || !at_estimate.rolling) continue;
    e.upper = kNaN;
    e.upper_open = true;
    id.warnings.push_back(
        "mu is not identifiable: the drum does not slip in the fitted steady "
        "state, which needs mu >= " +
        num(std::round(at_estimate.friction_ratio * 1000) / 1000) +
        "; every larger mu gives the same response");
  }
  id.simulations = pr.simulations();
  return id;
}

std::vector<PassEstimate> identify_pass(const Case& base, std::span<const double> t,
                                        std::span<const double> ddx, std::span<const double> ddz,
                                        std::span<const double> position,
                                        const WindowOptions& windows, const IdentifyOptions& o,
                                        const PassProgress& progress) {
  const std::vector<RecordWindow> ws = analyze_windows(t, ddx, ddz, position, windows);
  std::vector<PassEstimate> out;
  const Identification* previous = nullptr;
  for (std::size_t k = 0; k < ws.size(); ++k) {
    PassEstimate pe;
    pe.window = ws[k];
    pe.identification.f = ws[k].f;
    if (!ws[k].valid) {
      pe.reason = ws[k].reason;
    } else {
      try {
        const MeasuredResponse d = measured_response(ws[k].metrics, ws[k].f, ws[k].count);
        pe.identification = identify(base, d, o, previous);
        pe.valid = true;
      } catch (const Error& e) {
        pe.reason = e.what();
      }
    }
    out.push_back(std::move(pe));
    if (out.back().valid) previous = &out.back().identification;
    if (progress && !progress(k, ws.size())) break;
  }
  return out;
}

RecordSamples synthetic_record(const std::vector<Case>& segments, const SyntheticRecord& o) {
  if (segments.empty()) throw Error("synthetic_record: no case given");
  if (!(o.duration > 0 && o.sample_rate > 0))
    throw Error("synthetic_record: duration and sample_rate must be > 0");
  const std::size_t n = static_cast<std::size_t>(std::floor(o.duration * o.sample_rate)) + 1;
  RecordSamples rec;
  rec.t.resize(n);
  rec.ddx_M.resize(n);
  rec.ddz_M.resize(n);
  rec.position.resize(n);
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> uni(-0.5, 0.5);
  for (std::size_t i = 0; i < n; ++i)
    rec.t[i] =
        (static_cast<double>(i) + (i > 0 && i + 1 < n ? o.jitter * uni(rng) : 0.0)) / o.sample_rate;
  const double seg = o.duration / static_cast<double>(segments.size());
  double peak_x = 0, peak_z = 0;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    Case c = segments[s];
    c.numerics.samples_per_period = 1024;
    c.numerics.output_periods = 1;
    const Result r = simulate(c);
    if (!ok(r.status))
      throw Error("synthetic_record: segment " + std::to_string(s) + " did not reach its steady " +
                  "state: " + r.message);
    const std::size_t m = r.samples.size();
    const double T = static_cast<double>(m) / (c.roller.f * r.samples_per_period);  // its period
    const double t0 = r.samples.t.front();
    for (std::size_t i = 0; i < n; ++i) {
      const double ti = rec.t[i];
      if (ti < seg * static_cast<double>(s) - 1e-12 ||
          (s + 1 < segments.size() && ti >= seg * static_cast<double>(s + 1)))
        continue;
      double u = std::fmod(ti - t0, T);
      if (u < 0) u += T;
      const double x = u / T * static_cast<double>(m);
      const std::size_t j = static_cast<std::size_t>(std::floor(x)) % m;
      const double w = x - std::floor(x);
      const std::size_t j1 = (j + 1) % m;
      rec.ddx_M[i] = (1 - w) * r.samples.ddx_M[j] + w * r.samples.ddx_M[j1];
      rec.ddz_M[i] = (1 - w) * r.samples.ddz_M[j] + w * r.samples.ddz_M[j1];
    }
    for (std::size_t j = 0; j < m; ++j) {
      peak_x = std::max(peak_x, std::abs(r.samples.ddx_M[j]));
      peak_z = std::max(peak_z, std::abs(r.samples.ddz_M[j]));
    }
  }
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double slow = std::sin(2.0 * M_PI * rec.t[i] / o.duration + 0.3);
    rec.ddx_M[i] += peak_x * (o.noise * gauss(rng) + o.drift * slow);
    rec.ddz_M[i] += peak_z * (o.noise * gauss(rng) + o.drift * slow);
    rec.position[i] = o.speed * rec.t[i];
  }
  return rec;
}

}  // namespace oscidrum
