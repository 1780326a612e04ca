// The maximum-likelihood criterion of Swevers et al. 2002, eq. 18: motor torque residuals
// (tau_M measured - F_i(theta1, theta2)) / sigma_i of the drive model F (eq. 12) over the
// actuated axes, with the unknown parameters theta1 chosen by name and the rest known (theta2);
// the load enters through its 10 parameters (eq. 3) as part of the payload link. Residuals and
// their analytic Jacobian come from ceres::CostFunction blocks of samples (the ones fit_ml
// hands to Levenberg-Marquardt), the Jacobian by the chain rule from the drive model's.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "modelgen/drive_model.hpp"
#include "modelgen/prepare.hpp"
#include "modelgen/transmission.hpp"

namespace ceres {
class CostFunction;
}  // namespace ceres

namespace modelgen {

/// One experiment for the ML fit, typically the period average of a periodic experiment.
struct MlExperiment {
  std::string source;          ///< for messages
  Eigen::MatrixXd q, dq, ddq;  ///< samples x dof, joint side (rad, rad/s, rad/s^2)
  Eigen::MatrixXd tau_M;       ///< samples x dof measured motor torques, N m, link side (eq. 4)
  Eigen::VectorXd sigma;       ///< dof: standard deviation of the noise on tau_M per motor, N m
};

/// An MlExperiment from a periodic PreparedExperiment (modelgen/prepare.hpp; joint-side torques
/// tau = K^T tau_M and their noise variance per axis): tau_M = K^-T tau, and
/// sigma_i^2 = sum_j (K^-T)_ij^2 var_j (the joint-side noise taken as independent per axis).
/// Throws EstimationError (modelgen/estimate.hpp) naming the source when the experiment has no
/// noise variance (not prepared as periodic) or sizes differ from K.
MlExperiment ml_experiment(const PreparedExperiment& prepared, const DriveChain& drive);

/// The parameters of the ML problem: model.param_names() (inertial and drive parameters), then
/// load_param_names() (modelgen/load_parameters.hpp).
std::vector<std::string> ml_param_names(const DriveModel& model);

/// What is unknown and what is fitted.
struct MlSetup {
  /// theta1: names from ml_param_names(), at least one, no repeats; every other parameter is
  /// known (theta2) at its value.
  std::vector<std::string> unknown;
  /// Number j of the link carrying the load (its parameters XXj .. Mj); 0 when there is no load.
  /// With a load, the link's inertial parameters in F are its own values (the XXj .. Mj
  /// values given, 0 for a link negligible against the load, as Swevers assume) plus the load's
  /// standard parameters (standard_from_load).
  int payload_link = 0;
  /// The axes (0-based motors) whose torques enter eq. 18 (the set the paper calls vartheta);
  /// empty: every motor whose velocity is not zero throughout the data.
  std::vector<int> axes;
  int samples_per_block = 64;  ///< samples per ceres::CostFunction
};

/// The residuals of eq. 18 over stacked experiments: residual index = (sample, axis) with the
/// axis running fastest, sample over all experiments in order. Keeps references to `model`
/// (whose samples it binds) and nothing else; not copyable.
class MlProblem {
 public:
  /// Binds all experiments' samples to `model`. `values` holds every ml_param_names() value
  /// (known values and the starting point of the unknowns).
  /// Throws EstimationError for: an unknown name (listing the valid ones), a repeat, load
  /// parameters without a payload link, a payload link whose XXj .. Mj do not exist, an axis out
  /// of range, no axis moving, sizes that do not match, a non-finite value (naming experiment,
  /// sample and column), a sigma that is not positive on a fitted axis, fewer residuals than
  /// unknowns.
  MlProblem(DriveModel& model, const std::vector<MlExperiment>& data, MlSetup setup,
            const Eigen::VectorXd& values);
  ~MlProblem();
  MlProblem(const MlProblem&) = delete;
  MlProblem& operator=(const MlProblem&) = delete;

  const DriveModel& model() const;
  const std::vector<std::string>& unknown_names() const;
  const std::vector<int>& axes() const;
  int num_unknowns() const;
  Eigen::Index num_residuals() const;
  Eigen::Index num_samples() const;
  /// Indices into ml_param_names() of the unknowns, in unknown_names() order.
  const std::vector<int>& unknown_indices() const;
  /// Every ml_param_names() value: the known ones and the starting point of the unknowns.
  const Eigen::VectorXd& values() const;
  void set_values(const Eigen::VectorXd& values);
  /// theta1 taken from values().
  Eigen::VectorXd initial() const;
  /// values() with theta1 (num_unknowns()) in place of the unknowns.
  Eigen::VectorXd with_unknowns(const Eigen::VectorXd& theta1) const;
  /// The drive model's parameter vector (model().num_params()) from ml_param_names() values:
  /// the payload link's inertial parameters plus the load's standard parameters.
  Eigen::VectorXd drive_parameters(const Eigen::VectorXd& all_values) const;
  /// Index into the drive model's parameters of the payload's XXj .. Mj (10), empty without
  /// a payload link.
  const std::vector<int>& payload_indices() const;

  /// Weighted residuals (num_residuals()) at theta1, and when J is not null their Jacobian
  /// (num_residuals() x num_unknowns()), evaluated block by block through the same cost
  /// functions the fit uses.
  void evaluate(const Eigen::VectorXd& theta1, Eigen::VectorXd& residuals,
                Eigen::MatrixXd* J) const;
  /// Measured minus modelled motor torque, samples x dof (zero on axes not fitted), for
  /// ml_param_names() values `all_values`.
  Eigen::MatrixXd torque_errors(const Eigen::VectorXd& all_values) const;
  /// Measured motor torques and noise standard deviations, per stacked sample, samples x dof.
  const Eigen::MatrixXd& measured() const;
  const Eigen::MatrixXd& sigma() const;

  /// The cost functions (owned by this problem) whose residuals stack to evaluate()'s, each
  /// with one parameter block: theta1, num_unknowns() values.
  std::vector<ceres::CostFunction*> cost_functions() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace modelgen
