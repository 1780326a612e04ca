// The joint controller of a closed-loop experiment: a discrete PID per joint, as industrial
// robot controllers run it at their sample rate (issue 13's controller.yaml, joint side).
#pragma once

#include <Eigen/Core>

namespace modelgen {

/// Gains of a discrete joint PID: per joint kp (N m/rad), ki (N m/(rad s)), kd (N m s/rad),
/// and the controller's sample time Ts (s).
struct PidGains {
  double sample_time = 0;
  Eigen::VectorXd kp, ki, kd;

  int dof() const { return static_cast<int>(kp.size()); }
  /// Throws std::invalid_argument unless Ts > 0, the three lists have one entry per joint (at
  /// least one), every gain is finite and >= 0, and kp > 0 (a loop without a proportional term
  /// does not hold a robot).
  void check() const;
};

/// One PID per joint, run once per sample k on the measured position q_k:
///   e_k = qr_k - q_k,
///   tau_k = kp e_k + ki Ts sum_{i<=k} e_i + kd (e_k - e_{k-1}) / Ts,
/// with e_{-1} = e_0 (no derivative kick at the start). tau_k is held over [t_k, t_k + Ts).
class PidController {
 public:
  /// Checks the gains (PidGains::check).
  explicit PidController(PidGains gains);

  /// The torque command of the next sample; qr and q have dof() values.
  Eigen::VectorXd command(const Eigen::VectorXd& qr, const Eigen::VectorXd& q);

  /// Forgets the integral and the previous error (a new experiment).
  void reset();

  const PidGains& gains() const { return gains_; }
  int dof() const { return gains_.dof(); }

 private:
  PidGains gains_;
  Eigen::VectorXd error_sum_, previous_error_;
  bool started_ = false;
};

}  // namespace modelgen
