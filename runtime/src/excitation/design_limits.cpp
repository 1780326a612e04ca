// The limit and effort constraints of the excitation design (design_variables.hpp), all linear
// in the variables but the torques: exact closed forms and gradients for the limits, the
// model's state Jacobian d tau / d state for the efforts; the random feasible starts and the
// repairs on the dense grid of limit_use.hpp.

#include "runtime/src/excitation/design_variables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "modelgen/excitation/limit_use.hpp"
#include "modelgen/excitation/torque_use.hpp"

namespace modelgen::detail {

// The a-priori joint torques (dof) at one state.
Eigen::VectorXd Design::torque(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                               const Eigen::VectorXd& ddq) const {
  Eigen::VectorXd tau(dof_);
  model_.inverse_dynamics(q.data(), dq.data(), ddq.data(), p_.a_priori.data(), tau.data());
  return tau;
}

// The largest |tau_i| / (margin effort_i) over the instants of `basis`.
double Design::torque_use(const double* x, const FourierBasis& basis) const {
  Eigen::MatrixXd q, dq, ddq;
  states(x, basis, q, dq, ddq);
  double use = 0;
  for (Eigen::Index k = 0; k < q.rows(); ++k) {
    const Eigen::VectorXd tau =
        torque(q.row(k).transpose(), dq.row(k).transpose(), ddq.row(k).transpose());
    for (std::size_t i = 0; i < torque_joints_.size(); ++i) {
      use = std::max(use, std::abs(tau[torque_joints_[i]]) / torque_limits_[i]);
    }
  }
  return use;
}

// The largest |tau_i| / (margin effort_i) on the dense grid of limit_use.hpp.
double Design::dense_torque_use(const std::vector<double>& x) const {
  Eigen::VectorXd q0;
  Eigen::MatrixXd a, b;
  coefficients(x, q0, a, b);
  const std::vector<TorquePeak> peaks =
      torque_peaks(model_, p_.a_priori, to_trajectory(q0, a, b, p_.period));
  double use = 0;
  for (std::size_t i = 0; i < torque_joints_.size(); ++i) {
    use =
        std::max(use, peaks[static_cast<std::size_t>(torque_joints_[i])].peak / torque_limits_[i]);
  }
  return use;
}

// Multiplies every moving joint's oscillation (about its q0) by the largest factor in [0, 1]
// for which `use` (a torque use of the variables) stays within `fill`, found by bisection
// (16 halvings: the factor is at most 2^-16 below the largest; the lower end is always
// feasible). Returns the factor, or -1 when even no oscillation (the robot at rest at the
// offsets) exceeds `fill`; x is then unchanged.
template <class Use>
double Design::shrink_for_torque(std::vector<double>& x, double fill, const Use& use) const {
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
void Design::limit_constraints(const double* x, double* c, double* grad) const {
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
        const double w = (l + 1) * wf_, s = constraint_basis_.sin(k, l),
                     cs = constraint_basis_.cos(k, l);
        q_dv[1 + l] = s, q_dv[1 + L_ + l] = cs;
        dq_dv[1 + l] = w * cs, dq_dv[1 + L_ + l] = -w * s;
        ddq_dv[1 + l] = -w * w * s, ddq_dv[1 + L_ + l] = -w * w * cs;
      }
      const Eigen::Map<const Eigen::VectorXd> vars(v, per_axis_);
      const double q = q_dv.dot(vars), dq = dq_dv.dot(vars), ddq = ddq_dv.dot(vars);
      const double values[6] = {(q - bound.high) / half, (bound.low - q) / half,
                                dq / bound.dq - 1,       -dq / bound.dq - 1,
                                ddq / bound.ddq - 1,     -ddq / bound.ddq - 1};
      const Eigen::VectorXd rows[6] = {q_dv / half,       -q_dv / half,       dq_dv / bound.dq,
                                       -dq_dv / bound.dq, ddq_dv / bound.ddq, -ddq_dv / bound.ddq};
      for (int i = 0; i < 6; ++i, ++row) {
        c[row] = values[i];
        if (grad != nullptr) {
          double* g = grad + static_cast<std::size_t>(row) * n_ + m * per_axis_;
          for (int e = 0; e < per_axis_; ++e) g[e] = rows[i][e];
        }
      }
    }
  }
  if (limits_torque())
    torque_constraints(x, c + row,
                       grad == nullptr ? nullptr : grad + static_cast<std::size_t>(row) * n_);
}

// +-tau_i / (margin effort_i) - 1 <= 0 at every constraint point for every joint with an
// effort limit; d tau / d state is one state Jacobian at the a-priori values per point (exact
// for generated models, differences of the inverse dynamics for the numeric reference).
void Design::torque_constraints(const double* x, double* c, double* grad) const {
  const int points = static_cast<int>(constraint_basis_.times.size());
  const std::size_t torques = torque_joints_.size();
  if (grad != nullptr)
    std::fill(grad, grad + 2 * torques * points * static_cast<std::size_t>(n_), 0.0);
  Eigen::MatrixXd q, dq, ddq;
  states(x, constraint_basis_, q, dq, ddq);
  RowMajor J(dof_, 3 * dof_);
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
    model_.inverse_dynamics_state_jacobian(qk.data(), dqk.data(), ddqk.data(), p_.a_priori.data(),
                                           J.data());
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const int j = p_.moving[m];
      for (std::size_t i = 0; i < torques; ++i) {
        const int t = torque_joints_[i];
        const double by_q = J(t, j), by_dq = J(t, dof_ + j), by_ddq = J(t, 2 * dof_ + j);
        double* g = grad + (2 * torques * k + 2 * i) * static_cast<std::size_t>(n_) + m * per_axis_;
        double* g_neg = g + n_;
        const double limit = torque_limits_[i];
        g[0] = by_q / limit;
        for (int l = 0; l < L_; ++l) {
          const double w = (l + 1) * wf_, s = constraint_basis_.sin(k, l),
                       cs = constraint_basis_.cos(k, l);
          g[1 + l] = (by_q * s + by_dq * w * cs - by_ddq * w * w * s) / limit;
          g[1 + L_ + l] = (by_q * cs - by_dq * w * s - by_ddq * w * w * cs) / limit;
        }
        for (int e = 0; e < per_axis_; ++e) g_neg[e] = -g[e];
      }
    }
  }
}

// Variable bounds: q0 in [low, high]; a coefficient of harmonic l at most twice what the
// limits allow that harmonic alone (a Fourier coefficient is at most twice the peak).
void Design::variable_bounds(std::vector<double>& lower, std::vector<double>& upper) const {
  lower.resize(static_cast<std::size_t>(n_));
  upper.resize(static_cast<std::size_t>(n_));
  for (std::size_t m = 0; m < p_.moving.size(); ++m) {
    const AxisBounds& bound = bounds_[m];
    const std::size_t base = m * per_axis_;
    lower[base] = bound.low, upper[base] = bound.high;
    for (int l = 0; l < L_; ++l) {
      const double w = (l + 1) * wf_;
      const double most =
          2 * std::min({(bound.high - bound.low) / 2, bound.dq / w, bound.ddq / (w * w)});
      for (std::size_t e : {base + 1 + l, base + 1 + L_ + l}) lower[e] = -most, upper[e] = most;
    }
  }
}

// The factor by which the oscillation of moving joint m (about its q0) may be multiplied and
// stay within its bounds at the given extremes.
double Design::fitting_factor(const AxisBounds& bound, double q0, double q_min, double q_max,
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
std::vector<double> Design::random_start(std::uint64_t& state) const {
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
  if (limits_torque() && shrink_for_torque(x, 0.98, [this](const std::vector<double>& y) {
                           return torque_use(y.data(), constraint_basis_);
                         }) < 0) {
    return {};
  }
  return x;
}

// Scales the oscillation of moving joint m (variables v) to use `fill` of its tightest
// bound at the constraint points.
void Design::shrink_to_fit(std::size_t m, double* v, double fill) const {
  double q_min = v[0], q_max = v[0], dq_peak = 0, ddq_peak = 0;
  for (int k = 0; k < static_cast<int>(constraint_basis_.times.size()); ++k) {
    double q = v[0], dq = 0, ddq = 0;
    for (int l = 0; l < L_; ++l) {
      const double w = (l + 1) * wf_, s = constraint_basis_.sin(k, l),
                   c = constraint_basis_.cos(k, l);
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
std::vector<double> Design::repair_on_dense_grid(std::vector<double>& x) const {
  std::vector<double> factors(static_cast<std::size_t>(dof_), 1.0);
  Eigen::VectorXd q0;
  Eigen::MatrixXd a, b;
  coefficients(x, q0, a, b);
  const std::vector<JointExtremes> extremes =
      trajectory_extremes(to_trajectory(q0, a, b, p_.period));
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
std::string Design::explain_torque_at_rest(int random_starts) const {
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
double Design::repair_torque_on_dense_grid(std::vector<double>& x) const {
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

}  // namespace modelgen::detail
