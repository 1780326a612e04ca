// Excitation design by SLSQP (NLopt) over Fourier coefficients; see excitation_design.hpp.
//
// Variables, per moving joint: q0, a_1..a_L, b_1..b_L of the position form
// q = q0 + sum a_l sin(l wf t) + b_l cos(l wf t) (Swevers 2002 eq. 15), so that
//   dq = sum l wf (a_l cos - b_l sin),  ddq = -sum (l wf)^2 (a_l sin + b_l cos),
// all linear in the variables: the limit constraints and their gradients are exact closed
// forms. The criterion's gradient is analytic through the Fourier series and the criterion
// (design_criterion.hpp); only the regressor's derivative in the joint state comes from
// central differences, as the generated code has no state Jacobian: 5 extra regressor
// evaluations per moving joint and sample (a forward step for ddq, in which W is linear).

#include "modelgen/excitation/excitation_design.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <Eigen/QR>
#include <nlopt.h>

#include "modelgen/excitation/limit_use.hpp"
#include "modelgen/excitation/torque_use.hpp"

namespace modelgen {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::string shortest_text(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

// The limits of one moving joint, margin applied: q within [low, high], |dq| <= dq, |ddq| <= ddq.
struct AxisBounds {
  double low, high, dq, ddq;
};

// sin and cos of l wf t for l = 1..L at the given instants.
struct FourierBasis {
  std::vector<double> times;
  Eigen::MatrixXd sin, cos;  // times x L

  FourierBasis(double period, int harmonics, int points) : times(points) {
    const double wf = 2 * std::numbers::pi / period;
    sin.resize(points, harmonics);
    cos.resize(points, harmonics);
    for (int k = 0; k < points; ++k) {
      times[k] = period * k / points;
      for (int l = 0; l < harmonics; ++l) {
        sin(k, l) = std::sin((l + 1) * wf * times[k]);
        cos(k, l) = std::cos((l + 1) * wf * times[k]);
      }
    }
  }
};

class Design {
 public:
  explicit Design(const ExcitationDesignProblem& p)
      : p_(p),
        model_(*p.model),
        dof_(model_.dof()),
        L_(p.harmonics),
        per_axis_(2 * p.harmonics + 1),
        n_(static_cast<int>(p.moving.size()) * per_axis_),
        wf_(2 * std::numbers::pi / p.period),
        samples_(p.samples > 0 ? p.samples : std::max(100, 40 * p.harmonics)),
        criterion_basis_(p.period, p.harmonics, samples_),
        // 16 constraint points per period of the highest harmonic; the dense grid checks after.
        constraint_basis_(p.period, p.harmonics, 16 * p.harmonics) {
    for (int j : p.moving) {
      const JointLimits& limit = p.limits.at(static_cast<std::size_t>(j));
      const double middle = (*limit.q_lower + *limit.q_upper) / 2;
      const double half = (*limit.q_upper - *limit.q_lower) / 2;
      bounds_.push_back({middle - p.margin * half, middle + p.margin * half, p.margin * *limit.dq,
                         p.margin * *limit.ddq});
    }
    if (p.a_priori.size() > 0) {
      for (int j = 0; j < dof_; ++j) {
        const std::optional<double>& effort = p.limits[static_cast<std::size_t>(j)].effort;
        if (effort) torque_joints_.push_back(j), torque_limits_.push_back(p.margin * *effort);
      }
    }
  }

  int variables() const { return n_; }
  int samples() const { return samples_; }

  // Position-form coefficients of the variables (held joints at their hold position).
  void coefficients(const std::vector<double>& x, Eigen::VectorXd& q0, Eigen::MatrixXd& a,
                    Eigen::MatrixXd& b) const {
    q0 = p_.hold;
    a = Eigen::MatrixXd::Zero(dof_, L_);
    b = Eigen::MatrixXd::Zero(dof_, L_);
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const int j = p_.moving[m];
      const double* v = x.data() + m * per_axis_;
      q0[j] = v[0];
      for (int l = 0; l < L_; ++l) a(j, l) = v[1 + l], b(j, l) = v[1 + L_ + l];
    }
  }

  // q, dq, ddq (samples x dof) on the criterion's instants.
  void states(const std::vector<double>& x, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
              Eigen::MatrixXd& ddq) const {
    states(x.data(), criterion_basis_, q, dq, ddq);
  }

  // q, dq, ddq (instants x dof) on the instants of `basis`.
  void states(const double* x, const FourierBasis& basis, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
              Eigen::MatrixXd& ddq) const {
    const int points = static_cast<int>(basis.times.size());
    q = p_.hold.transpose().replicate(points, 1);
    dq = Eigen::MatrixXd::Zero(points, dof_);
    ddq = Eigen::MatrixXd::Zero(points, dof_);
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const int j = p_.moving[m];
      const double* v = x + m * per_axis_;
      for (int k = 0; k < points; ++k) {
        double qk = v[0], dqk = 0, ddqk = 0;
        for (int l = 0; l < L_; ++l) {
          const double w = (l + 1) * wf_, s = basis.sin(k, l), c = basis.cos(k, l);
          const double a = v[1 + l], b = v[1 + L_ + l];
          qk += a * s + b * c;
          dqk += w * (a * c - b * s);
          ddqk -= w * w * (a * s + b * c);
        }
        q(k, j) = qk, dq(k, j) = dqk, ddq(k, j) = ddqk;
      }
    }
  }

  RowMajor regressor_at(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                        const Eigen::VectorXd& ddq) const {
    RowMajor W(dof_, model_.num_base_params());
    model_.regressor(q.data(), dq.data(), ddq.data(), W.data());
    return W;
  }

  Eigen::MatrixXd stacked(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                          const Eigen::MatrixXd& ddq) const {
    Eigen::MatrixXd W(samples_ * dof_, model_.num_base_params());
    for (int k = 0; k < samples_; ++k) {
      W.middleRows(k * dof_, dof_) =
          regressor_at(q.row(k).transpose(), dq.row(k).transpose(), ddq.row(k).transpose());
    }
    return W;
  }

  Eigen::MatrixXd selected(const Eigen::MatrixXd& W) const {
    Eigen::MatrixXd out(W.rows(), static_cast<Eigen::Index>(columns_.size()));
    for (std::size_t c = 0; c < columns_.size(); ++c) out.col(static_cast<Eigen::Index>(c)) = W.col(columns_[c]);
    return out;
  }

  // The base parameters the moving axes excite: the independent columns (pivoted QR of the
  // unit-norm columns) of the regressor stacked over the given random trajectories.
  void choose_columns(const std::vector<std::vector<double>>& trajectories) {
    Eigen::MatrixXd W(0, model_.num_base_params());
    for (const auto& x : trajectories) {
      Eigen::MatrixXd q, dq, ddq;
      states(x, q, dq, ddq);
      const Eigen::MatrixXd part = stacked(q, dq, ddq);
      Eigen::MatrixXd grown(W.rows() + part.rows(), W.cols());
      grown << W, part;
      W.swap(grown);
    }
    const Eigen::VectorXd norms = W.colwise().norm().transpose();
    std::vector<int> nonzero;
    for (Eigen::Index c = 0; c < W.cols(); ++c) {
      if (norms[c] > 1e-12 * norms.maxCoeff()) nonzero.push_back(static_cast<int>(c));
    }
    Eigen::MatrixXd scaled(W.rows(), static_cast<Eigen::Index>(nonzero.size()));
    for (std::size_t c = 0; c < nonzero.size(); ++c) {
      scaled.col(static_cast<Eigen::Index>(c)) = W.col(nonzero[c]) / norms[nonzero[c]];
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
    qr.setThreshold(1e-8);
    columns_.clear();
    for (Eigen::Index r = 0; r < qr.rank(); ++r) {
      columns_.push_back(nonzero[static_cast<std::size_t>(qr.colsPermutation().indices()[r])]);
    }
    std::sort(columns_.begin(), columns_.end());
  }
  const std::vector<int>& columns() const { return columns_; }
  void set_columns(std::vector<int> columns) { columns_ = std::move(columns); }

  // The fixed column scale (design_criterion.hpp): the RMS norm of each selected column over
  // the given trajectories.
  void choose_scale(const std::vector<std::vector<double>>& trajectories) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(columns_.size()));
    for (const auto& x : trajectories) {
      Eigen::MatrixXd q, dq, ddq;
      states(x, q, dq, ddq);
      sum += selected(stacked(q, dq, ddq)).colwise().squaredNorm().transpose();
    }
    scale_ = (sum / static_cast<double>(trajectories.size())).cwiseSqrt();
    // A column no trajectory excites keeps scale 1 (it is rank-deficient anyway).
    for (Eigen::Index c = 0; c < scale_.size(); ++c) {
      if (!(scale_[c] > 0)) scale_[c] = 1;
    }
  }
  const Eigen::VectorXd& scale() const { return scale_; }
  void set_scale(Eigen::VectorXd scale) { scale_ = std::move(scale); }

  CriterionValue criterion(const std::vector<double>& x, std::vector<double>* gradient) const {
    Eigen::MatrixXd q, dq, ddq;
    states(x, q, dq, ddq);
    const Eigen::MatrixXd W = stacked(q, dq, ddq);
    CriterionValue value = evaluate_criterion(selected(W), scale_, p_.criterion, gradient != nullptr);
    if (gradient == nullptr) return value;
    gradient->assign(static_cast<std::size_t>(n_), 0.0);
    if (!std::isfinite(value.value)) return value;
    // d value / d x_i = sum over samples k of <G_k, dW_k/dstate_j> dstate_j/dx_i: the state
    // derivatives of W by differences, contracted with G at once.
    constexpr double h = 1e-6;
    for (int k = 0; k < samples_; ++k) {
      const Eigen::MatrixXd G = value.gradient.middleRows(k * dof_, dof_);
      const auto contract = [&](const RowMajor& dW) {
        double sum = 0;
        for (std::size_t c = 0; c < columns_.size(); ++c) {
          sum += G.col(static_cast<Eigen::Index>(c)).dot(dW.col(columns_[c]));
        }
        return sum;
      };
      const Eigen::VectorXd qk = q.row(k).transpose(), dqk = dq.row(k).transpose(),
                            ddqk = ddq.row(k).transpose();
      const RowMajor Wk = W.middleRows(k * dof_, dof_);
      for (std::size_t m = 0; m < p_.moving.size(); ++m) {
        const int j = p_.moving[m];
        Eigen::VectorXd up = qk, down = qk;
        up[j] += h, down[j] -= h;
        const double by_q = contract(regressor_at(up, dqk, ddqk) - regressor_at(down, dqk, ddqk)) / (2 * h);
        up = dqk, down = dqk;
        up[j] += h, down[j] -= h;
        const double by_dq = contract(regressor_at(qk, up, ddqk) - regressor_at(qk, down, ddqk)) / (2 * h);
        up = ddqk;
        up[j] += 1;  // W is linear in ddq: the unit step is exact
        const double by_ddq = contract(regressor_at(qk, dqk, up) - Wk);
        double* g = gradient->data() + m * per_axis_;
        g[0] += by_q;
        for (int l = 0; l < L_; ++l) {
          const double w = (l + 1) * wf_, s = criterion_basis_.sin(k, l), c = criterion_basis_.cos(k, l);
          g[1 + l] += by_q * s + by_dq * w * c - by_ddq * w * w * s;
          g[1 + L_ + l] += by_q * c - by_dq * w * s - by_ddq * w * w * c;
        }
      }
    }
    return value;
  }

  int constraints() const {
    const int points = static_cast<int>(constraint_basis_.times.size());
    return static_cast<int>(p_.moving.size()) * points * 6 +
           static_cast<int>(torque_joints_.size()) * points * 2;
  }

  bool limits_torque() const { return !torque_joints_.empty(); }

  // The a-priori joint torques (dof) at one state.
  Eigen::VectorXd torque(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                         const Eigen::VectorXd& ddq) const {
    Eigen::VectorXd tau(dof_);
    model_.inverse_dynamics(q.data(), dq.data(), ddq.data(), p_.a_priori.data(), tau.data());
    return tau;
  }

  // The largest |tau_i| / (margin effort_i) over the instants of `basis`.
  double torque_use(const double* x, const FourierBasis& basis) const {
    Eigen::MatrixXd q, dq, ddq;
    states(x, basis, q, dq, ddq);
    double use = 0;
    for (Eigen::Index k = 0; k < q.rows(); ++k) {
      const Eigen::VectorXd tau = torque(q.row(k).transpose(), dq.row(k).transpose(), ddq.row(k).transpose());
      for (std::size_t i = 0; i < torque_joints_.size(); ++i) {
        use = std::max(use, std::abs(tau[torque_joints_[i]]) / torque_limits_[i]);
      }
    }
    return use;
  }

  // The largest |tau_i| / (margin effort_i) on the dense grid of limit_use.hpp.
  double dense_torque_use(const std::vector<double>& x) const {
    Eigen::VectorXd q0;
    Eigen::MatrixXd a, b;
    coefficients(x, q0, a, b);
    const std::vector<TorquePeak> peaks =
        torque_peaks(model_, p_.a_priori, to_trajectory(q0, a, b, p_.period));
    double use = 0;
    for (std::size_t i = 0; i < torque_joints_.size(); ++i) {
      use = std::max(use, peaks[static_cast<std::size_t>(torque_joints_[i])].peak / torque_limits_[i]);
    }
    return use;
  }

  // Multiplies every moving joint's oscillation (about its q0) by the largest factor in [0, 1]
  // for which `use` (a torque use of the variables) stays within `fill`, found by bisection
  // (16 halvings: the factor is at most 2^-16 below the largest; the lower end is always
  // feasible). Returns the factor, or -1 when even no oscillation (the robot at rest at the
  // offsets) exceeds `fill`; x is then unchanged.
  template <class Use>
  double shrink_for_torque(std::vector<double>& x, double fill, const Use& use) const {
    if (use(x) <= fill) return 1;
    const auto scaled = [&](double factor) {
      std::vector<double> y = x;
      for (std::size_t m = 0; m < p_.moving.size(); ++m) {
        for (int e = 1; e < per_axis_; ++e) y[m * per_axis_ + e] *= factor;
      }
      return y;
    };
    if (use(scaled(0)) > fill) return -1;
    double low = 0, high = 1;
    for (int i = 0; i < 16; ++i) {
      const double middle = (low + high) / 2;
      (use(scaled(middle)) <= fill ? low : high) = middle;
    }
    x = scaled(low);
    return low;
  }

  // c <= 0 at every constraint point, each normalised by its limit: q - high, low - q, +-dq -
  // dq_max, +-ddq - ddq_max; grad (row-major, constraints x variables) when not null.
  void limit_constraints(const double* x, double* c, double* grad) const {
    const int points = static_cast<int>(constraint_basis_.times.size());
    if (grad != nullptr) std::fill(grad, grad + static_cast<std::size_t>(constraints()) * n_, 0.0);
    int row = 0;
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const AxisBounds& bound = bounds_[m];
      const double* v = x + m * per_axis_;
      const double half = (bound.high - bound.low) / 2;
      for (int k = 0; k < points; ++k) {
        // d(q, dq, ddq)/d(variables of this joint)
        Eigen::VectorXd dq_dv = Eigen::VectorXd::Zero(per_axis_), ddq_dv = dq_dv, q_dv = dq_dv;
        q_dv[0] = 1;
        for (int l = 0; l < L_; ++l) {
          const double w = (l + 1) * wf_, s = constraint_basis_.sin(k, l), cs = constraint_basis_.cos(k, l);
          q_dv[1 + l] = s, q_dv[1 + L_ + l] = cs;
          dq_dv[1 + l] = w * cs, dq_dv[1 + L_ + l] = -w * s;
          ddq_dv[1 + l] = -w * w * s, ddq_dv[1 + L_ + l] = -w * w * cs;
        }
        const Eigen::Map<const Eigen::VectorXd> vars(v, per_axis_);
        const double q = q_dv.dot(vars), dq = dq_dv.dot(vars), ddq = ddq_dv.dot(vars);
        const double values[6] = {(q - bound.high) / half, (bound.low - q) / half,
                                  dq / bound.dq - 1,       -dq / bound.dq - 1,
                                  ddq / bound.ddq - 1,     -ddq / bound.ddq - 1};
        const Eigen::VectorXd rows[6] = {q_dv / half,       -q_dv / half,
                                         dq_dv / bound.dq,  -dq_dv / bound.dq,
                                         ddq_dv / bound.ddq, -ddq_dv / bound.ddq};
        for (int i = 0; i < 6; ++i, ++row) {
          c[row] = values[i];
          if (grad != nullptr) {
            double* g = grad + static_cast<std::size_t>(row) * n_ + m * per_axis_;
            for (int e = 0; e < per_axis_; ++e) g[e] = rows[i][e];
          }
        }
      }
    }
    if (limits_torque()) torque_constraints(x, c + row, grad == nullptr ? nullptr : grad + static_cast<std::size_t>(row) * n_);
  }

  // +-tau_i / (margin effort_i) - 1 <= 0 at every constraint point for every joint with an
  // effort limit. d tau / d state by differences as in criterion() (the model gives no state
  // Jacobian): central in q and dq, a unit step in ddq, in which tau is linear.
  void torque_constraints(const double* x, double* c, double* grad) const {
    const int points = static_cast<int>(constraint_basis_.times.size());
    const std::size_t torques = torque_joints_.size();
    if (grad != nullptr) std::fill(grad, grad + 2 * torques * points * static_cast<std::size_t>(n_), 0.0);
    Eigen::MatrixXd q, dq, ddq;
    states(x, constraint_basis_, q, dq, ddq);
    constexpr double h = 1e-6;
    for (int k = 0; k < points; ++k) {
      const Eigen::VectorXd qk = q.row(k).transpose(), dqk = dq.row(k).transpose(),
                            ddqk = ddq.row(k).transpose();
      const Eigen::VectorXd tau = torque(qk, dqk, ddqk);
      double* ck = c + 2 * torques * k;
      for (std::size_t i = 0; i < torques; ++i) {
        const double scaled = tau[torque_joints_[i]] / torque_limits_[i];
        ck[2 * i] = scaled - 1, ck[2 * i + 1] = -scaled - 1;
      }
      if (grad == nullptr) continue;
      for (std::size_t m = 0; m < p_.moving.size(); ++m) {
        const int j = p_.moving[m];
        Eigen::VectorXd up = qk, down = qk;
        up[j] += h, down[j] -= h;
        const Eigen::VectorXd by_q = (torque(up, dqk, ddqk) - torque(down, dqk, ddqk)) / (2 * h);
        up = dqk, down = dqk;
        up[j] += h, down[j] -= h;
        const Eigen::VectorXd by_dq = (torque(qk, up, ddqk) - torque(qk, down, ddqk)) / (2 * h);
        up = ddqk;
        up[j] += 1;
        const Eigen::VectorXd by_ddq = torque(qk, dqk, up) - tau;
        for (std::size_t i = 0; i < torques; ++i) {
          const int t = torque_joints_[i];
          double* g = grad + (2 * torques * k + 2 * i) * static_cast<std::size_t>(n_) + m * per_axis_;
          double* g_neg = g + n_;
          const double limit = torque_limits_[i];
          g[0] = by_q[t] / limit;
          for (int l = 0; l < L_; ++l) {
            const double w = (l + 1) * wf_, s = constraint_basis_.sin(k, l), cs = constraint_basis_.cos(k, l);
            g[1 + l] = (by_q[t] * s + by_dq[t] * w * cs - by_ddq[t] * w * w * s) / limit;
            g[1 + L_ + l] = (by_q[t] * cs - by_dq[t] * w * s - by_ddq[t] * w * w * cs) / limit;
          }
          for (int e = 0; e < per_axis_; ++e) g_neg[e] = -g[e];
        }
      }
    }
  }

  // Variable bounds: q0 in [low, high]; a coefficient of harmonic l at most twice what the
  // limits allow that harmonic alone (a Fourier coefficient is at most twice the peak).
  void variable_bounds(std::vector<double>& lower, std::vector<double>& upper) const {
    lower.resize(static_cast<std::size_t>(n_));
    upper.resize(static_cast<std::size_t>(n_));
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const AxisBounds& bound = bounds_[m];
      const std::size_t base = m * per_axis_;
      lower[base] = bound.low, upper[base] = bound.high;
      for (int l = 0; l < L_; ++l) {
        const double w = (l + 1) * wf_;
        const double most = 2 * std::min({(bound.high - bound.low) / 2, bound.dq / w, bound.ddq / (w * w)});
        for (std::size_t e : {base + 1 + l, base + 1 + L_ + l}) lower[e] = -most, upper[e] = most;
      }
    }
  }

  // The factor by which the oscillation of moving joint m (about its q0) may be multiplied and
  // stay within its bounds at the given extremes.
  static double fitting_factor(const AxisBounds& bound, double q0, double q_min, double q_max,
                               double dq_peak, double ddq_peak) {
    double factor = std::numeric_limits<double>::infinity();
    if (q_max > q0) factor = std::min(factor, (bound.high - q0) / (q_max - q0));
    if (q_min < q0) factor = std::min(factor, (q0 - bound.low) / (q0 - q_min));
    if (dq_peak > 0) factor = std::min(factor, bound.dq / dq_peak);
    if (ddq_peak > 0) factor = std::min(factor, bound.ddq / ddq_peak);
    return factor;
  }

  // A random trajectory inside the bounds at the constraint points: harmonic amplitudes
  // falling as 1/l, offsets near the middle of the range, then each joint's oscillation
  // scaled to use 98% of its tightest limit.
  std::vector<double> random_start(std::uint64_t& state) const {
    const auto uniform = [&state] {  // splitmix64: the same numbers on every platform
      std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    };
    std::vector<double> x(static_cast<std::size_t>(n_));
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const AxisBounds& bound = bounds_[m];
      double* v = x.data() + m * per_axis_;
      v[0] = (bound.low + bound.high) / 2 + (uniform() - 0.5) * 0.4 * (bound.high - bound.low) / 2;
      for (int l = 0; l < L_; ++l) {
        v[1 + l] = (2 * uniform() - 1) / (l + 1);
        v[1 + L_ + l] = (2 * uniform() - 1) / (l + 1);
      }
      shrink_to_fit(m, v, 0.98);
    }
    // The effort limits at the constraint points, by one factor for all joints (torques
    // couple them); a start whose torque at rest already exceeds them is marked empty.
    if (limits_torque() &&
        shrink_for_torque(x, 0.98, [this](const std::vector<double>& y) {
          return torque_use(y.data(), constraint_basis_);
        }) < 0) {
      return {};
    }
    return x;
  }

  // Scales the oscillation of moving joint m (variables v) to use `fill` of its tightest
  // bound at the constraint points.
  void shrink_to_fit(std::size_t m, double* v, double fill) const {
    double q_min = v[0], q_max = v[0], dq_peak = 0, ddq_peak = 0;
    for (int k = 0; k < static_cast<int>(constraint_basis_.times.size()); ++k) {
      double q = v[0], dq = 0, ddq = 0;
      for (int l = 0; l < L_; ++l) {
        const double w = (l + 1) * wf_, s = constraint_basis_.sin(k, l), c = constraint_basis_.cos(k, l);
        q += v[1 + l] * s + v[1 + L_ + l] * c;
        dq += w * (v[1 + l] * c - v[1 + L_ + l] * s);
        ddq -= w * w * (v[1 + l] * s + v[1 + L_ + l] * c);
      }
      q_min = std::min(q_min, q), q_max = std::max(q_max, q);
      dq_peak = std::max(dq_peak, std::abs(dq)), ddq_peak = std::max(ddq_peak, std::abs(ddq));
    }
    const double factor = fill * fitting_factor(bounds_[m], v[0], q_min, q_max, dq_peak, ddq_peak);
    for (int e = 1; e < per_axis_; ++e) v[e] *= factor;
  }

  // The dense-grid check (limit_use.hpp, 1 kHz or finer): a joint that leaves a bound between
  // the constraint points has its oscillation shrunk to just inside; returns the factors.
  std::vector<double> repair_on_dense_grid(std::vector<double>& x) const {
    std::vector<double> factors(static_cast<std::size_t>(dof_), 1.0);
    Eigen::VectorXd q0;
    Eigen::MatrixXd a, b;
    coefficients(x, q0, a, b);
    const std::vector<JointExtremes> extremes = trajectory_extremes(to_trajectory(q0, a, b, p_.period));
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const JointExtremes& e = extremes[static_cast<std::size_t>(p_.moving[m])];
      double* v = x.data() + m * per_axis_;
      const double factor = fitting_factor(bounds_[m], v[0], e.q_min, e.q_max, e.dq_peak, e.ddq_peak);
      if (factor < 1) {
        const double applied = factor * (1 - 1e-9);
        for (int e2 = 1; e2 < per_axis_; ++e2) v[e2] *= applied;
        factors[static_cast<std::size_t>(p_.moving[m])] = applied;
      }
    }
    return factors;
  }

  // Why no random start met the effort limits: the joint whose a-priori torque at rest, the
  // moving joints in the middle of their ranges and the others where held, uses most of its
  // limit (margin applied), and how much.
  std::string explain_torque_at_rest(int random_starts) const {
    Eigen::VectorXd q = p_.hold;
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      q[p_.moving[m]] = (bounds_[m].low + bounds_[m].high) / 2;
    }
    const Eigen::VectorXd tau = torque(q, Eigen::VectorXd::Zero(dof_), Eigen::VectorXd::Zero(dof_));
    std::size_t worst = 0;
    for (std::size_t i = 1; i < torque_joints_.size(); ++i) {
      if (std::abs(tau[torque_joints_[i]]) / torque_limits_[i] >
          std::abs(tau[torque_joints_[worst]]) / torque_limits_[worst]) {
        worst = i;
      }
    }
    return "none of " + std::to_string(random_starts) + " random starts keeps the a-priori " +
           "torques within the effort limits times the margin, even shrunk to rest at its " +
           "offsets; at rest in the middle of the moving joints' ranges, joint " +
           std::to_string(torque_joints_[worst] + 1) + "'s torque is " +
           shortest_text(tau[torque_joints_[worst]]) + " against " +
           shortest_text(torque_limits_[worst]) + " (effort times margin): check the " +
           "description's effort limits and a-priori values, or hold the joints elsewhere";
  }

  // The effort limits on the dense grid: when the a-priori torques leave them between the
  // constraint points, every oscillation is shrunk by one factor (returned; 1: none needed).
  double repair_torque_on_dense_grid(std::vector<double>& x) const {
    if (!limits_torque()) return 1;
    const double factor = shrink_for_torque(
        x, 1.0, [this](const std::vector<double>& y) { return dense_torque_use(y); });
    if (factor < 0) {
      throw std::runtime_error(
          "the design leaves an effort limit on the dense grid and cannot be shrunk into it: "
          "the a-priori torque at rest at its offsets already exceeds the limit times the margin");
    }
    return factor;
  }

  int evaluations = 0;

 private:
  const ExcitationDesignProblem& p_;
  const IdentificationModel& model_;
  int dof_, L_, per_axis_, n_;
  double wf_;
  int samples_;
  FourierBasis criterion_basis_, constraint_basis_;
  std::vector<AxisBounds> bounds_;
  std::vector<int> columns_;
  Eigen::VectorXd scale_;
  std::vector<int> torque_joints_;     // joints with an effort limit, when a_priori is given
  std::vector<double> torque_limits_;  // their margin * effort
};

double objective(unsigned n, const double* x, double* grad, void* data) {
  Design& design = *static_cast<Design*>(data);
  ++design.evaluations;
  std::vector<double> point(x, x + n), gradient;
  const CriterionValue value = design.criterion(point, grad != nullptr ? &gradient : nullptr);
  if (grad != nullptr) std::copy(gradient.begin(), gradient.end(), grad);
  // SLSQP cannot step from +inf; a rank-deficient point is just very bad.
  return std::isfinite(value.value) ? value.value : 1e30;
}

void constraint(unsigned /*m*/, double* result, unsigned /*n*/, const double* x, double* grad,
                void* data) {
  static_cast<Design*>(data)->limit_constraints(x, result, grad);
}

}  // namespace

FourierTrajectory to_trajectory(const Eigen::VectorXd& q0, const Eigen::MatrixXd& a,
                                const Eigen::MatrixXd& b, double period) {
  // Position amplitudes to FourierTrajectory's velocity amplitudes (its eq. 15 form).
  FourierTrajectory x;
  x.period = period;
  x.q0 = q0;
  x.a.resize(a.rows(), a.cols());
  x.b.resize(b.rows(), b.cols());
  const double wf = 2 * std::numbers::pi / period;
  for (Eigen::Index l = 0; l < a.cols(); ++l) {
    x.a.col(l) = a.col(l) * ((l + 1) * wf);
    x.b.col(l) = -b.col(l) * ((l + 1) * wf);
  }
  return x;
}

Eigen::MatrixXd stacked_regressor(const IdentificationModel& model,
                                  const FourierTrajectory& trajectory, int samples) {
  const int dof = model.dof();
  Eigen::MatrixXd W(static_cast<Eigen::Index>(samples) * dof, model.num_base_params());
  RowMajor block(dof, model.num_base_params());
  Eigen::VectorXd q, dq, ddq;
  for (int k = 0; k < samples; ++k) {
    trajectory.evaluate(trajectory.period * k / samples, q, dq, ddq);
    model.regressor(q.data(), dq.data(), ddq.data(), block.data());
    W.middleRows(static_cast<Eigen::Index>(k) * dof, dof) = block;
  }
  return W;
}

double design_objective(const ExcitationDesignProblem& problem, const std::vector<int>& columns,
                        const Eigen::VectorXd& scale, const std::vector<double>& x,
                        std::vector<double>* gradient) {
  Design design(problem);
  design.set_columns(columns);
  design.set_scale(scale);
  return design.criterion(x, gradient).value;
}

std::vector<double> design_constraints(const ExcitationDesignProblem& problem,
                                       const std::vector<double>& x, std::vector<double>* jacobian) {
  Design design(problem);
  std::vector<double> c(static_cast<std::size_t>(design.constraints()));
  if (jacobian != nullptr) jacobian->assign(c.size() * x.size(), 0.0);
  design.limit_constraints(x.data(), c.data(), jacobian != nullptr ? jacobian->data() : nullptr);
  return c;
}

ExcitationDesign design_excitation(const ExcitationDesignProblem& problem) {
  if (problem.model == nullptr || problem.moving.empty() || problem.harmonics < 1 ||
      !(problem.period > 0) || problem.hold.size() != problem.model->dof() ||
      problem.limits.size() != static_cast<std::size_t>(problem.model->dof()) ||
      problem.random_starts < 1 || problem.starts < 1 ||
      (problem.a_priori.size() != 0 && problem.a_priori.size() != problem.model->num_base_params())) {
    throw std::invalid_argument("design_excitation: inconsistent problem");
  }
  const auto say = [&problem](const std::string& line) {
    if (problem.progress) problem.progress(line);
  };
  Design design(problem);
  std::uint64_t state = problem.seed;

  // Random feasible starts; the first three also decide which base parameters the moving axes
  // excite at all (a held axis leaves some unidentifiable: Swevers 2002 section 4.2).
  std::vector<std::vector<double>> starts;
  for (int s = 0; s < problem.random_starts; ++s) {
    std::vector<double> start = design.random_start(state);
    if (!start.empty()) starts.push_back(std::move(start));
  }
  if (starts.empty()) throw std::runtime_error(design.explain_torque_at_rest(problem.random_starts));
  design.choose_columns({starts.begin(), starts.begin() + std::min<std::size_t>(3, starts.size())});
  design.choose_scale(starts);
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t s = 0; s < starts.size(); ++s) {
    ranked.emplace_back(design.criterion(starts[s], nullptr).value, s);
  }
  std::sort(ranked.begin(), ranked.end());
  say(std::to_string(starts.size()) + " random feasible starts, best criterion " +
      shortest_text(ranked.front().first));

  ExcitationDesign result;
  result.period = problem.period;
  result.samples = design.samples();
  result.columns = design.columns();
  result.scale = design.scale();
  result.before = design.criterion(starts[ranked.front().second], nullptr);

  std::vector<double> lower, upper, best, best_shrink;
  design.variable_bounds(lower, upper);
  double best_value = std::numeric_limits<double>::infinity();
  const int optimised = std::min(problem.starts, static_cast<int>(starts.size()));
  for (int s = 0; s < optimised; ++s) {
    std::vector<double> x = starts[ranked[static_cast<std::size_t>(s)].second];
    nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, static_cast<unsigned>(x.size()));
    nlopt_set_min_objective(opt, objective, &design);
    const std::vector<double> tolerances(static_cast<std::size_t>(design.constraints()), 1e-9);
    nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(design.constraints()), constraint,
                                     &design, tolerances.data());
    nlopt_set_lower_bounds(opt, lower.data());
    nlopt_set_upper_bounds(opt, upper.data());
    nlopt_set_maxeval(opt, problem.max_evaluations);
    nlopt_set_ftol_rel(opt, 1e-7);
    double value = 0;
    const int before = design.evaluations;
    const nlopt_result code = nlopt_optimize(opt, x.data(), &value);
    nlopt_destroy(opt);
    const std::vector<double> shrink = design.repair_on_dense_grid(x);
    const double torque_shrink = design.repair_torque_on_dense_grid(x);
    const double repaired = design.criterion(x, nullptr).value;
    say("start " + std::to_string(s + 1) + "/" + std::to_string(optimised) + ": " +
        shortest_text(ranked[static_cast<std::size_t>(s)].first) + " -> " + shortest_text(repaired) +
        " (" + std::to_string(design.evaluations - before) + " evaluations, NLopt code " +
        std::to_string(static_cast<int>(code)) + ")");
    if (repaired < best_value) {
      best_value = repaired, best = x, best_shrink = shrink, result.torque_shrink = torque_shrink;
    }
  }
  // The kept design, checked once more on the dense grid (a no-op unless it was repaired).
  design.repair_on_dense_grid(best);
  design.repair_torque_on_dense_grid(best);
  result.shrink = best_shrink;
  design.coefficients(best, result.q0, result.a, result.b);
  result.after = design.criterion(best, nullptr);
  result.evaluations = design.evaluations;
  result.regressor = stacked_regressor(*problem.model,
                                       to_trajectory(result.q0, result.a, result.b, problem.period),
                                       design.samples());
  return result;
}

}  // namespace modelgen
