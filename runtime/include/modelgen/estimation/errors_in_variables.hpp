// Errors-in-variables maximum likelihood (Bona & Curatella section 2.2.1, eq. 13-16, after
// Olsen 2003) on periodic data: positions (and so velocities and accelerations) are measured
// with noise as well as torques, and the weight of each sample's torque equations depends on
// the parameters through the sensitivity of the model to its state.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/signal/periodic_noise.hpp"

namespace modelgen {

/// Per sample i of the experiments, the observation x_i = (q, dq, ddq, tau) and the model
/// G(theta, x) = tau - W(q, dq, ddq) theta (base parameters, one equation per joint). Eq. 15:
///   cost(theta) = 1/2 sum_i b_i' S_i^-2 b_i,   b_i = -G(theta, x_i),
///   S_i^2 = B_i Sigma_x B_i' (eq. 16),   B_i = d G / d x = [-dtau/dq, -dtau/ddq... , I]
/// with dtau/d(q, dq, ddq) the model's inverse_dynamics_state_jacobian at theta (linear in
/// theta) and Sigma_x the noise covariance of one observation (PeriodicNoise: per axis
/// q, dq, ddq, tau variances and the q-ddq covariance; axes independent).
/// The residuals r_i = L_i^-1 b_i, L_i the lower Cholesky factor of S_i^2, give
/// cost = 1/2 |r|^2.
/// When the prepared torques were kept only up to harmonic H_tau (PeriodicNoise::tau_lines
/// not empty), every column of W over the period is projected on the same harmonics before
/// it meets them (the parallel filtering of Gautier & Briot eq. 13-14, here the periodic
/// low-pass): a torque model with content above H_tau (the dynamics are nonlinear in q)
/// against measured torques without it biased the estimate by several standard deviations
/// (XX2R by 4.9 on the simulated TX-40 of the test). B_i stays the per-sample state Jacobian.
class ErrorsInVariablesObjective {
 public:
  /// `data[e]` with dq and ddq, `noise[e]` its PeriodicNoise (dof values each); both copied.
  /// Throws
  /// EstimationError for sizes that differ, a noise variance that is negative or not finite,
  /// or a noise covariance of an axis that is not positive semi-definite.
  ErrorsInVariablesObjective(const IdentificationModel& model, const std::vector<Trajectory>& data,
                             const std::vector<PeriodicNoise>& noise);

  int num_params() const { return model_.num_base_params(); }
  Eigen::Index num_residuals() const { return samples_ * model_.dof(); }
  Eigen::Index samples() const { return samples_; }

  /// r (num_residuals(), sample-major: sample i's dof values together) and, when J is given,
  /// d r / d theta (num_residuals() x num_params()), analytic: for
  /// r_i = L_i^-1 b_i, d r_i = L_i^-1 (W_i d theta) - Phi(L_i^-1 dS_i^2 L_i^-T) r_i, Phi the lower
  /// triangle with the diagonal halved (the derivative of the Cholesky factor), and
  /// dS_i^2 / d theta_p = dB_p Sigma B' + B Sigma dB_p' with dB_p the state Jacobian at
  /// beta = e_p. Returns false when some S_i^2 is not positive definite at theta (a sample
  /// whose equations carry no noise).
  bool evaluate(const Eigen::VectorXd& theta, Eigen::VectorXd& r, Eigen::MatrixXd* J) const;

  /// 1/2 |r|^2 at theta; +inf when evaluate() fails.
  double cost(const Eigen::VectorXd& theta) const;

 private:
  const IdentificationModel& model_;
  std::vector<Trajectory> data_;  // copies: the objective outlives no argument
  std::vector<Eigen::Index> first_;  // first sample index of each experiment
  std::vector<PeriodicNoise> noise_;
  // Per experiment: samples x (dof * params) projected regressor rows (row k: W_k row-major),
  // or empty when the torques are whole.
  std::vector<Eigen::MatrixXd> projected_;
  Eigen::Index samples_ = 0;
  friend struct ErrorsInVariablesAccess;
};

struct ErrorsInVariablesOptions {
  int max_iterations = 50;
  int threads = 2;
};

struct ErrorsInVariablesResult {
  /// The EIV estimate in the form fit prints: fit.value; fit.std_dev and fit.rel_std_dev from
  /// the covariance (J'J)^-1 Cov(J'r) (J'J)^-1 at the optimum, Cov(J'r) from the noise lines
  /// of the averaged period (the prepared samples' noise is correlated: the Fourier series of
  /// q, the torques kept up to a harmonic; white_std_dev below ignores it and is too small by
  /// about sqrt(N / (2 H + 1))), not scaled by the residuals; when the noise has no lines,
  /// white_std_dev. fit.residual_std_dev = s, s^2 = |r|^2 / (m - b) (m residuals,
  /// b parameters): about 1 when the noise model is right. fit.condition_number of J;
  /// rms_error, rms_torque, torque_rel_error_norm of the torques.
  Identification id;
  /// sqrt of the diagonal of s^2 (J'J)^-1: eq. 15-16 read with white, independent samples.
  Eigen::VectorXd white_std_dev;
  bool correlated_noise = false;  ///< id.fit.std_dev from the noise lines (see id)
  Identification initial;  ///< the IDIM-WLS estimate the search starts from
  double initial_cost = 0, final_cost = 0;  ///< eq. 15 at the start and at the optimum
  int iterations = 0;
  bool converged = false;
  std::string solver_report;  ///< Ceres' one-line summary
  double solve_seconds = 0;
};

/// Minimises eq. 15 with Levenberg-Marquardt (Ceres) from the IDIM-WLS estimate of the same
/// data. Throws EstimationError as identify() does, for bad noise (see the objective) and
/// when the solver fails.
ErrorsInVariablesResult fit_errors_in_variables(const IdentificationModel& model,
                                                const std::vector<Trajectory>& data,
                                                const std::vector<PeriodicNoise>& noise,
                                                const ErrorsInVariablesOptions& options = {});

}  // namespace modelgen
