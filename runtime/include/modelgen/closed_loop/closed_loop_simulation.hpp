// A robot under its joint controller: the controller runs once per sample on the measured
// positions, its torque is held over the sample, and the plant (the model's forward dynamics)
// is integrated in between. What `modelid simulate --controller` writes, and what IDIM-IV and
// DIDIM simulate with the current estimate (issue 13).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "modelgen/closed_loop/pid_controller.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen {

struct ClosedLoopOptions {
  /// Fourth-order Runge-Kutta steps per controller sample.
  int substeps = 4;
  /// Coulomb friction as tanh(v / eps) inside the integrator, not sign(v): eps per term is
  /// max(min_smoothing, 2 h F (a^T M(q0)^-1 a)), which keeps h times the friction's stiffness
  /// at 0.5, inside RK4's stability region (h the substep, F the friction, a its torque
  /// direction). False: sign(v), for a test that wants the discontinuity.
  bool smooth_coulomb = true;
  double min_smoothing = 1e-3;  ///< rad/s (m/s)
  /// Measurement model of the recorded run (empty: none). Positions: quantised to the encoder
  /// resolution (rad per count, per joint), then Gaussian noise of q_noise; the controller sees
  /// these measured positions. Torques: the command plus Gaussian noise of tau_noise (the
  /// plant gets the command itself).
  Eigen::VectorXd encoder_resolution, q_noise, tau_noise;
  std::uint64_t seed = 1;
};

/// One closed-loop run, sample k at t_k = t0 + k Ts.
struct ClosedLoopRun {
  Eigen::VectorXd t;
  Eigen::MatrixXd qr;            ///< reference positions
  Eigen::MatrixXd q_measured;    ///< what the controller saw (samples x dof)
  Eigen::MatrixXd tau_command;   ///< the controller's torques, held over [t_k, t_k + Ts)
  Eigen::MatrixXd tau_recorded;  ///< the command plus measurement noise
  /// The plant's true state at t_k, and its acceleration at t_k under tau_k.
  Eigen::MatrixXd q, dq, ddq;
};

/// Simulates `model` with base parameters `beta` under `controller` along the reference `qr`
/// (samples x dof, sample k at t0 + k Ts, Ts the controller's sample time), from state
/// (q0, dq0). The controller is reset first.
/// Throws std::invalid_argument for sizes that disagree or substeps < 1, std::domain_error when
/// the plant leaves what it can integrate (a mass matrix that is not positive definite, a
/// non-finite state: an unstable loop), naming the time.
ClosedLoopRun simulate_closed_loop(const IdentificationModel& model, const std::vector<double>& beta,
                                   PidController& controller, const Eigen::MatrixXd& qr,
                                   const Eigen::VectorXd& q0, const Eigen::VectorXd& dq0,
                                   const ClosedLoopOptions& options, double t0 = 0);

}  // namespace modelgen
