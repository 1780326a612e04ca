// The variables of the excitation design (excitation_design.cpp) and what they give: per moving
// joint q0, a_1..a_L, b_1..b_L of the position form q = q0 + sum a_l sin(l wf t) + b_l cos(l wf t)
// (Swevers 2002 eq. 15); the states and the criterion (design_variables.cpp), its gradient
// (design_gradient.cpp), and the limit and effort constraints, random starts and repairs on the
// dense grid (design_limits.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "modelgen/excitation/design_criterion.hpp"
#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::detail {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A number in at most four significant digits, for messages.
std::string shortest_text(double value);

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
  explicit Design(const ExcitationDesignProblem& p);

  int variables() const { return n_; }
  int samples() const { return samples_; }

  // Position-form coefficients of the variables (held joints at their hold position).
  void coefficients(const std::vector<double>& x, Eigen::VectorXd& q0, Eigen::MatrixXd& a,
                    Eigen::MatrixXd& b) const;

  // q, dq, ddq (samples x dof) on the criterion's instants.
  void states(const std::vector<double>& x, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
              Eigen::MatrixXd& ddq) const;

  // q, dq, ddq (instants x dof) on the instants of `basis`.
  void states(const double* x, const FourierBasis& basis, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
              Eigen::MatrixXd& ddq) const;

  // The regressor (dof x base parameters) at one state.
  RowMajor regressor_at(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                        const Eigen::VectorXd& ddq) const;

  // The regressor stacked over the criterion's instants (samples x dof rows).
  Eigen::MatrixXd stacked(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                          const Eigen::MatrixXd& ddq) const;

  // The chosen columns of W.
  Eigen::MatrixXd selected(const Eigen::MatrixXd& W) const;

  // The base parameters the moving axes excite: the independent columns (pivoted QR of the
  // unit-norm columns) of the regressor stacked over the given random trajectories.
  void choose_columns(const std::vector<std::vector<double>>& trajectories);

  const std::vector<int>& columns() const { return columns_; }
  void set_columns(std::vector<int> columns) { columns_ = std::move(columns); }

  // The fixed column scale (design_criterion.hpp): the RMS norm of each selected column over
  // the given trajectories.
  void choose_scale(const std::vector<std::vector<double>>& trajectories);

  const Eigen::VectorXd& scale() const { return scale_; }
  void set_scale(Eigen::VectorXd scale) { scale_ = std::move(scale); }

  // The criterion of the variables x, with its gradient in x when `gradient` is not null.
  CriterionValue criterion(const std::vector<double>& x, std::vector<double>* gradient) const;

  // d value / d x (design_gradient.cpp) from the states, the stacked regressor W and the
  // criterion `value` of its selected columns, evaluated with its gradient.
  void criterion_gradient(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                          const Eigen::MatrixXd& ddq, const Eigen::MatrixXd& W,
                          const CriterionValue& value, std::vector<double>& gradient) const;

  // The number of inequality constraints: limits, then effort limits.
  int constraints() const {
    const int points = static_cast<int>(constraint_basis_.times.size());
    return static_cast<int>(p_.moving.size()) * points * 6 +
           static_cast<int>(torque_joints_.size()) * points * 2;
  }

  bool limits_torque() const { return !torque_joints_.empty(); }

  // The a-priori joint torques (dof) at one state.
  Eigen::VectorXd torque(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                         const Eigen::VectorXd& ddq) const;

  // The largest |tau_i| / (margin effort_i) over the instants of `basis`.
  double torque_use(const double* x, const FourierBasis& basis) const;

  // The largest |tau_i| / (margin effort_i) on the dense grid of limit_use.hpp.
  double dense_torque_use(const std::vector<double>& x) const;

  // Multiplies every moving joint's oscillation (about its q0) by the largest factor in [0, 1]
  // for which `use` (a torque use of the variables) stays within `fill`, found by bisection
  // (16 halvings: the factor is at most 2^-16 below the largest; the lower end is always
  // feasible). Returns the factor, or -1 when even no oscillation (the robot at rest at the
  // offsets) exceeds `fill`; x is then unchanged.
  template <class Use>
  double shrink_for_torque(std::vector<double>& x, double fill, const Use& use) const;

  // c <= 0 at every constraint point, each normalised by its limit: q - high, low - q, +-dq -
  // dq_max, +-ddq - ddq_max; grad (row-major, constraints x variables) when not null.
  void limit_constraints(const double* x, double* c, double* grad) const;

  // +-tau_i / (margin effort_i) - 1 <= 0 at every constraint point for every joint with an
  // effort limit; d tau / d state is the model's state Jacobian at the a-priori values.
  void torque_constraints(const double* x, double* c, double* grad) const;

  // Variable bounds: q0 in [low, high]; a coefficient of harmonic l at most twice what the
  // limits allow that harmonic alone (a Fourier coefficient is at most twice the peak).
  void variable_bounds(std::vector<double>& lower, std::vector<double>& upper) const;

  // The factor by which the oscillation of moving joint m (about its q0) may be multiplied and
  // stay within its bounds at the given extremes.
  static double fitting_factor(const AxisBounds& bound, double q0, double q_min, double q_max,
                               double dq_peak, double ddq_peak);

  // A random trajectory inside the bounds at the constraint points: harmonic amplitudes
  // falling as 1/l, offsets near the middle of the range, then each joint's oscillation
  // scaled to use 98% of its tightest limit.
  std::vector<double> random_start(std::uint64_t& state) const;

  // Scales the oscillation of moving joint m (variables v) to use `fill` of its tightest
  // bound at the constraint points.
  void shrink_to_fit(std::size_t m, double* v, double fill) const;

  // The dense-grid check (limit_use.hpp, 1 kHz or finer): a joint that leaves a bound between
  // the constraint points has its oscillation shrunk to just inside; returns the factors.
  std::vector<double> repair_on_dense_grid(std::vector<double>& x) const;

  // Why no random start met the effort limits: the joint whose a-priori torque at rest, the
  // moving joints in the middle of their ranges and the others where held, uses most of its
  // limit (margin applied), and how much.
  std::string explain_torque_at_rest(int random_starts) const;

  // The effort limits on the dense grid: when the a-priori torques leave them between the
  // constraint points, every oscillation is shrunk by one factor (returned; 1: none needed).
  double repair_torque_on_dense_grid(std::vector<double>& x) const;

  int evaluations = 0;

 private:
  // d value / d (q, dq, ddq) at every sample (samples x 3 dof; the columns of moving joints
  // filled) from the model's state Jacobian, or by differences of the regressor
  // (design_gradient.cpp).
  Eigen::MatrixXd exact_state_gradient(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                       const Eigen::MatrixXd& ddq, const Eigen::MatrixXd& W,
                                       const CriterionValue& value) const;
  Eigen::MatrixXd differenced_state_gradient(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                             const Eigen::MatrixXd& ddq, const Eigen::MatrixXd& W,
                                             const CriterionValue& value) const;

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

}  // namespace modelgen::detail
