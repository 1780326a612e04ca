// Identification of a robot recorded under its own controller, by the two methods the field
// trusts on closed-loop data (issue 13): IDIM-IV (Janot, Vandanjon & Gautier, IEEE TCST 2014),
// whose instruments are the regressor of a closed-loop simulation with the current estimate,
// and DIDIM (Gautier, Janot & Vandanjon, IEEE TCST 2013), an output-error method on the
// torques whose simulated regressor makes each Gauss-Newton step a linear least-squares fit.
// Both start from IDIM-WLS and simulate the record's own reference under the same controller.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/closed_loop/closed_loop_simulation.hpp"
#include "modelgen/closed_loop/pid_controller.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen {

enum class ClosedLoopMethod {
  kIv,     ///< IDIM-IV: instruments from the simulated closed loop
  kDidim,  ///< DIDIM: the regressor of the simulated closed loop, fitted to the torques
};

/// One closed-loop record, on the controller's sample grid.
struct ClosedLoopRecord {
  /// The record as prepared for IDIM (joint side, filtered positions and their derivatives,
  /// modelgen/signal/prepare.hpp); its rows are the raw samples first_row, first_row + 1, ...
  Trajectory prepared;
  Eigen::Index first_row = 0;
  /// Parallel decimation factor of Y, W and the instruments (eq. 13-14); the rows the end
  /// samples dominate are left out (decimated_interior, modelgen/signal/decimation.hpp).
  int decimation = 1;
  /// With ClosedLoopFitOptions::min_speed: each joint's equations within this many samples of
  /// its reversals are zeroed before the decimation, measured and simulated alike
  /// (reversal_mask, modelgen/signal/reversal_mask.hpp; PreparedExperiment::reversal_guard).
  Eigen::Index reversal_guard = 0;
  /// The prepared torques pair held commands half a sample later
  /// (PreparationOptions::torque_hold); DIDIM's simulated commands are paired the same way.
  bool torque_hold = false;
  /// The reference of every raw sample (samples x dof), sample k at t0 + k Ts.
  Eigen::MatrixXd qr;
  double t0 = 0;
  Eigen::VectorXd q0, dq0;  ///< state at the first raw sample, where the simulations start
};

struct ClosedLoopFitOptions {
  int max_iterations = 20;
  /// Converged when no parameter moves by more than this fraction of its standard deviation.
  double tolerance = 0.05;
  ClosedLoopOptions simulation;  ///< substeps and friction smoothing (no measurement noise)
  /// Per joint (rad/s, m/s; empty: none): the decimated samples where some joint moves slower
  /// (by its prepared velocity) are left out of every fit. Near rest the Coulomb model
  /// sign(dq) is wrong: a joint that reverses sticks for a moment while its friction is
  /// anything between -Fc and Fc.
  Eigen::VectorXd min_speed;
  /// Called after each iteration: its number (1, 2, ...) and the largest move in standard
  /// deviations.
  std::function<void(int, double)> on_iteration;
};

struct ClosedLoopIdentification {
  /// The estimate, its standard deviations and the torque errors on the decimated
  /// equations: measured torque minus W(measured states) beta for IV, minus W(simulated
  /// states) beta for DIDIM (its output error).
  Identification id;
  Eigen::VectorXd start;  ///< the IDIM-WLS estimate the iterations started from
  int iterations = 0;
  bool converged = false;
  std::string stop_reason;  ///< why the iterations stopped before converging; empty if converged
  std::vector<double> moves;  ///< largest move per iteration, in standard deviations
};

/// Identifies the base parameters of `model` from closed-loop records under `gains` by
/// `method`. Each row of joint j (and record e) is weighted by the inverse of the standard
/// deviation of its residual in the OLS solution (eq. 20), the weights kept fixed over the
/// iterations; the start is IDIM-WLS with these weights.
///   IV: beta = (Z^T W)^-1 Z^T Y, Z the regressor of the closed loop simulated with the last
///       estimate; covariance sigma^2 (Z^T W)^-1 Z^T Z (W^T Z)^-1.
///   DIDIM: Gauss-Newton on the output error Y - tau_s(beta), tau_s the simulated command,
///       with the regressor of the simulated states W_s as its Jacobian: beta += the least-
///       squares solution of W_s d = Y - tau_s(beta); covariance sigma^2 (W_s^T W_s)^-1.
/// Converged when no parameter moves by more than options.tolerance standard deviations (or
/// the estimate no longer changes); stops unconverged after options.max_iterations, when the
/// changes of the last three iterations are no smaller than those of the three before, or
/// (DIDIM) when eight halvings of a step do not lower the output error.
/// Throws EstimationError for records that do not fit the model or the controller, a
/// singular system, and when a simulation with an estimate fails (not a physical robot, an
/// unstable loop), naming the iteration.
ClosedLoopIdentification identify_closed_loop(const IdentificationModel& model,
                                              ClosedLoopMethod method, const PidGains& gains,
                                              const std::vector<ClosedLoopRecord>& records,
                                              const ClosedLoopFitOptions& options = {});

}  // namespace modelgen
