// IDIM-IV and DIDIM: iterate closed-loop simulations with the current estimate and linear
// fits on the decimated, weighted equations of every joint and record.

#include "modelgen/closed_loop/closed_loop_identification.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/reversal_mask.hpp"
#include "runtime/src/closed_loop/closed_loop_covariance.hpp"
#include "runtime/src/closed_loop/closed_loop_equations.hpp"

namespace modelgen {

namespace {

using detail::joint_rows;
using detail::kept_rows;
using detail::masked;
using detail::RecordEquations;
using detail::simulate_equations;
using detail::Simulated;
using detail::stack;

// Relative change of the estimate below which the iterations stop whatever the standard
// deviations (a few hundred rounding errors).
constexpr double kSettled = 1e-12;
// Step halvings DIDIM tries before it stops.
constexpr int kMaxHalvings = 8;

void check_record(const IdentificationModel& model, const PidGains& gains,
                  const ClosedLoopRecord& record, std::size_t index) {
  const int n = model.dof();
  const std::string name = record.prepared.source.empty()
                               ? "closed-loop record " + std::to_string(index + 1)
                               : record.prepared.source;
  const Trajectory& x = record.prepared;
  if (record.qr.cols() != n || x.q.cols() != n || record.q0.size() != n ||
      record.dq0.size() != n) {
    throw EstimationError(name + ": the record does not have the " + std::to_string(n) +
                          " joints of " + model.name() + " (reference, positions or start)");
  }
  if (record.first_row < 0 || record.first_row + x.t.size() > record.qr.rows() ||
      x.t.size() < 2) {
    throw EstimationError(name + ": the prepared samples are not within the reference's");
  }
  // The simulation runs on the controller's clock: the record must have been sampled on it.
  const double ts = gains.sample_time;
  for (const Eigen::Index r : {Eigen::Index{0}, x.t.size() - 1}) {
    const double expected = record.t0 + ts * static_cast<double>(record.first_row + r);
    if (std::abs(x.t[r] - expected) > 0.01 * ts) {
      throw EstimationError(name + ": sample at t = " + std::to_string(x.t[r]) +
                            " s is not on the controller's clock (sample time " +
                            std::to_string(ts) + " s): the closed-loop methods simulate the "
                            "controller and need the record sampled at its rate");
    }
  }
  if (record.decimation < 1) throw EstimationError(name + ": decimation factor below 1");
}

// The inputs' checks before anything is computed.
void check_inputs(const IdentificationModel& model, const PidGains& gains,
                  const std::vector<ClosedLoopRecord>& records,
                  const ClosedLoopFitOptions& options) {
  gains.check();
  const int n = model.dof();
  if (options.min_speed.size() != 0 && options.min_speed.size() != n) {
    throw EstimationError(std::to_string(options.min_speed.size()) + " minimum speeds for " +
                          std::to_string(n) + " joints");
  }
  if (gains.dof() != n) {
    throw EstimationError("the controller has " + std::to_string(gains.dof()) +
                          " joints, the robot " + model.name() + " " + std::to_string(n));
  }
  if (records.empty()) throw EstimationError("closed-loop identification needs a record");
  for (std::size_t e = 0; e < records.size(); ++e) check_record(model, gains, records[e], e);
}

// IDIM-IV or DIDIM on checked records: the measured equations and the IDIM-WLS start, then
// closed-loop simulations with the current estimate and linear fits until the estimate settles.
class ClosedLoopFit {
 public:
  ClosedLoopFit(const IdentificationModel& model, ClosedLoopMethod method, const PidGains& gains,
                const std::vector<ClosedLoopRecord>& records, const ClosedLoopFitOptions& options)
      : model_(model),
        method_(method),
        gains_(gains),
        records_(records),
        options_(options),
        n_(model.dof()),
        b_(model.num_base_params()),
        names_(model.base_param_names()) {}

  ClosedLoopIdentification run() {
    measure();
    start();
    iterate();
    statistics();
    return out_;
  }

 private:
  // The measured equations, decimated once.
  void measure() {
    const int n = n_, b = b_;
    equations_.resize(records_.size());
    measured_.resize(records_.size());
    torques_.resize(records_.size());
    for (std::size_t e = 0; e < records_.size(); ++e) {
      const ClosedLoopRecord& r = records_[e];
      const Trajectory& x = r.prepared;
      RecordEquations& equations = equations_[e];
      equations.kept = kept_rows(decimate_interior(x.dq, r.decimation),
                                 model_.drive_chain().motor_from_joint, options_.min_speed);
      if (equations.kept.size() * static_cast<std::size_t>(n) <= static_cast<std::size_t>(b)) {
        throw EstimationError(x.source + ": " + std::to_string(equations.kept.size()) +
                              " samples are left where every joint moves faster than the "
                              "minimum speed, too few for " +
                              std::to_string(b) + " parameters");
      }
      const auto& kept = equations.kept;
      if (options_.min_speed.size() != 0) {
        equations.mask = reversal_mask(x.dq, model_.drive_chain().motor_from_joint,
                                       options_.min_speed, r.reversal_guard);
      }
      const Eigen::ArrayXXd& mask = equations.mask;
      for (int j = 0; j < n; ++j) {
        equations.W.push_back(decimate_interior(
            masked(joint_rows(model_, x.q, x.dq, x.ddq, 0, x.t.size(), j), mask, j), r.decimation)(
            kept, Eigen::all));
        equations.y.push_back(
            decimate_interior(masked(x.tau.col(j), mask, j), r.decimation)(kept, 0));
        measured_[e].push_back(equations.W.back());
        torques_[e].push_back(equations.y.back());
        rows_ += equations.y.back().size();
      }
      equations.weight.assign(static_cast<std::size_t>(n), 1.0);
    }
    if (rows_ <= b) {
      throw EstimationError("closed-loop identification: " + std::to_string(rows_) +
                            " equations after decimation for " + std::to_string(b) +
                            " base parameters");
    }
  }

  // The start: IDIM-WLS on the measured equations, and its closed loop.
  void start() {
    const Eigen::VectorXd beta = fit_ols(stack(equations_, measured_, rows_, b_),
                                         stack(equations_, torques_, rows_, 1), names_)
                                     .value;
    // Eq. 20: each joint of each record weighted by its residual's standard deviation.
    for (RecordEquations& eq : equations_) {
      for (int j = 0; j < n_; ++j) {
        const Eigen::VectorXd residual = eq.y[j] - eq.W[j] * beta;
        const double sd = std::sqrt(residual.squaredNorm() / static_cast<double>(residual.size()));
        eq.weight[j] = sd > 0 ? 1.0 / sd : 1.0;
        group_sd_.push_back(sd);
      }
    }
    Wm_ = stack(equations_, measured_, rows_, b_);
    y_ = stack(equations_, torques_, rows_, 1).col(0);
    fit_ = fit_ols(Wm_, y_, names_);  // IDIM-WLS
    out_.start = beta_ = fit_.value;
    if (!simulate_with(beta_, current_)) {
      throw EstimationError("the closed loop could not be simulated with the IDIM-WLS estimate (" +
                            failure_ + "); try --physical, or check the controller's gains");
    }
  }

  // The closed loop of `estimate` on every record, decimated as the measured equations; false
  // (with failure_ set) when it cannot be simulated.
  bool simulate_with(const Eigen::VectorXd& estimate, Simulated& sim) {
    return simulate_equations(model_, gains_, records_, options_.simulation, equations_, estimate,
                              sim, failure_);
  }

  double output_error(const Simulated& sim) const {
    return (y_ - stack(equations_, sim.tau, rows_, 1).col(0)).squaredNorm();
  }

  // Iterate: simulate with the last estimate, refit.
  void iterate() {
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      const Eigen::MatrixXd Ws = stack(equations_, current_.W, rows_, b_);
      Eigen::VectorXd next;
      LeastSquaresResult result;
      if (method_ == ClosedLoopMethod::kDidim) {
        if (!didim_step(iteration, Ws, next, result)) break;
      } else {
        iv_step(Ws, next, result);
      }
      if (!take_step(iteration, next, result)) break;
    }
  }

  // The Gauss-Newton step of DIDIM on the output error Y - tau_s(beta), with the
  // simulated regressor as its Jacobian: a linear fit. (tau_s = W_s beta where the
  // simulated states obey the model; the simulation's smoothed friction makes them
  // differ near rest, and the simulated torque is the output.) The Jacobian leaves out
  // how the states move with beta: a step that does not lower the output error (or
  // makes a robot that cannot be simulated) is halved. False when no step is accepted: then
  // the iterations end here.
  bool didim_step(int iteration, const Eigen::MatrixXd& Ws, Eigen::VectorXd& next,
                  LeastSquaresResult& result) {
    const double cost = output_error(current_);
    result = fit_ols(Ws, y_ - stack(equations_, current_.tau, rows_, 1).col(0), names_);
    const Eigen::VectorXd step = result.value;
    Simulated trial;
    double alpha = 1;
    bool accepted = false;
    for (int halvings = 0; halvings <= kMaxHalvings && !accepted; ++halvings, alpha /= 2) {
      next = beta_ + alpha * step;
      accepted = simulate_with(next, trial) && output_error(trial) <= cost;
    }
    if (!accepted) {
      out_.iterations = iteration;
      // The step leaves out how the states move with beta; within a standard deviation of
      // the minimum that is what is left of it.
      double full = 0;
      for (int k = 0; k < b_; ++k) {
        full = std::max(full, std::abs(step[k]) / std::max(result.std_dev[k], 1e-300));
      }
      // The estimate stays; its statistics are those of this last linearisation.
      result.value = beta_;
      fit_ = result;
      if (full < 1) {
        out_.converged = true;
      } else {
        out_.stop_reason = "no step along the Gauss-Newton direction lowers the output error";
      }
      return false;
    }
    current_ = std::move(trial);
    result.value = next;
    return true;
  }

  // IV: (Z^T W) beta = Z^T Y, columns scaled to unit norm for the solve.
  void iv_step(const Eigen::MatrixXd& Ws, Eigen::VectorXd& next, LeastSquaresResult& result) const {
    const Eigen::VectorXd scale = Wm_.colwise().norm().cwiseMax(1e-300).cwiseInverse();
    const Eigen::MatrixXd Zs = Ws * scale.asDiagonal(), Ws_ = Wm_ * scale.asDiagonal();
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(Zs.transpose() * Ws_);
    if (!lu.isInvertible()) {
      throw EstimationError(
          "IDIM-IV: the instruments are not correlated with every column "
          "of the regressor (Z^T W is singular)");
    }
    next = scale.asDiagonal() * lu.solve(Zs.transpose() * y_);
    const Eigen::VectorXd residual = y_ - Wm_ * next;
    const double variance = residual.squaredNorm() / static_cast<double>(rows_ - b_);
    const Eigen::MatrixXd A_inverse = lu.inverse();
    const Eigen::MatrixXd covariance = variance * scale.asDiagonal() * A_inverse *
                                       (Zs.transpose() * Zs) * A_inverse.transpose() *
                                       scale.asDiagonal();
    result = fit_;  // the measured W's statistics (condition number, equations)
    result.value = next;
    result.std_dev = covariance.diagonal().cwiseMax(0).cwiseSqrt();
    result.information = covariance.inverse();
    result.residual_std_dev = std::sqrt(variance);
  }

  // Moves the estimate to `next`; false when the iterations end here.
  bool take_step(int iteration, const Eigen::VectorXd& next, const LeastSquaresResult& result) {
    double move = 0;
    for (int k = 0; k < b_; ++k) {
      const double sd = result.std_dev[k] > 0 ? result.std_dev[k] : 1.0;
      move = std::max(move, std::abs(next[k] - beta_[k]) / sd);
    }
    // Noise-free data give standard deviations near 0: then the estimate's own change decides.
    const bool settled = (next - beta_).norm() <= kSettled * next.norm();
    beta_ = next;
    fit_ = result;
    out_.iterations = iteration;
    out_.moves.push_back(move);
    if (options_.on_iteration) options_.on_iteration(iteration, move);
    if (move < options_.tolerance || settled) {
      out_.converged = true;
      return false;
    }
    // The next instruments: the closed loop of this estimate (DIDIM simulated it already).
    if (method_ == ClosedLoopMethod::kIv && iteration < options_.max_iterations &&
        !simulate_with(beta_, current_)) {
      throw EstimationError("iteration " + std::to_string(iteration) +
                            ": the closed loop could not be simulated with the estimate (" +
                            failure_ + "); try --physical on IDIM-WLS first");
    }
    // Changes that no longer shrink: the iterations circle (the smoothed friction of the
    // simulations moves with the estimate); more of them would not settle.
    const std::vector<double>& moves = out_.moves;
    const std::size_t m = moves.size();
    if (m >= 6 && *std::max_element(moves.end() - 3, moves.end()) >=
                      *std::max_element(moves.end() - 6, moves.end() - 3)) {
      out_.stop_reason = "the changes no longer shrink";
      return false;
    }
    return true;
  }

  // Statistics on the decimated equations, the residual the method minimises.
  void statistics() {
    const int n = n_;
    LeastSquaresResult& fit = fit_;
    correlated_statistics();
    for (int k = 0; k < b_; ++k) {
      fit.rel_std_dev[k] =
          fit.value[k] != 0 ? 100 * fit.std_dev[k] / std::abs(fit.value[k]) : INFINITY;
    }
    fit.group_std_dev = group_sd_;
    Eigen::VectorXd error_squares = Eigen::VectorXd::Zero(n), torque_squares = error_squares;
    double error_total = 0, torque_total = 0;
    Eigen::Index samples = 0;
    for (std::size_t e = 0; e < records_.size(); ++e) {
      for (int j = 0; j < n; ++j) {
        const Eigen::VectorXd& tau = torques_[e][j];
        error_squares[j] += method_ == ClosedLoopMethod::kDidim
                                ? (tau - current_.tau[e][j]).squaredNorm()
                                : (tau - measured_[e][j] * beta_).squaredNorm();
        torque_squares[j] += tau.squaredNorm();
      }
      samples += torques_[e][0].size();
    }
    error_total = error_squares.sum();
    torque_total = torque_squares.sum();
    fit.relative_error_norm = std::sqrt(error_total / torque_total);
    out_.id.fit = fit;
    out_.id.names = names_;
    out_.id.rms_error = (error_squares / static_cast<double>(samples)).cwiseSqrt();
    out_.id.rms_torque = (torque_squares / static_cast<double>(samples)).cwiseSqrt();
    out_.id.torque_rel_error_norm = fit.relative_error_norm;
    out_.id.samples = samples;
    for (std::size_t e = 0; e < records_.size(); ++e) {
      const ClosedLoopRecord& r = records_[e];
      out_.id.slow_samples += decimated_interior(r.prepared.t.size(), r.decimation).count -
                              static_cast<Eigen::Index>(equations_[e].kept.size());
    }
  }

  // The sandwich covariance when the decimated residuals are correlated (closed_loop_covariance
  // .hpp): X the last instruments (IV: current_ simulated the estimate before the last step)
  // or the simulated regressor of the estimate (DIDIM).
  void correlated_statistics() {
    const bool didim = method_ == ClosedLoopMethod::kDidim;
    std::vector<std::vector<Eigen::VectorXd>> residual(records_.size());
    for (std::size_t e = 0; e < records_.size(); ++e) {
      for (int j = 0; j < n_; ++j) {
        const Eigen::VectorXd tau = torques_[e][j].col(0);
        residual[e].push_back(didim ? Eigen::VectorXd(tau - current_.tau[e][j].col(0))
                                    : Eigen::VectorXd(tau - measured_[e][j] * beta_));
      }
    }
    if (current_.W.size() != records_.size()) return;
    closed_loop_sandwich(equations_, current_.W, didim ? current_.W : measured_, residual, fit_);
  }

  const IdentificationModel& model_;
  const ClosedLoopMethod method_;
  const PidGains& gains_;
  const std::vector<ClosedLoopRecord>& records_;
  const ClosedLoopFitOptions& options_;
  const int n_, b_;
  const std::vector<std::string>& names_;
  std::vector<RecordEquations> equations_;
  std::vector<std::vector<Eigen::MatrixXd>> measured_, torques_;  // per record and joint
  Eigen::Index rows_ = 0;
  Eigen::MatrixXd Wm_;  // the stacked, weighted measured equations
  Eigen::VectorXd y_;
  std::vector<double> group_sd_;
  LeastSquaresResult fit_;
  Eigen::VectorXd beta_;  // the current estimate
  Simulated current_;     // its closed loop
  std::string failure_;   // why the last simulation failed
  ClosedLoopIdentification out_;
};

}  // namespace

ClosedLoopIdentification identify_closed_loop(const IdentificationModel& model,
                                              ClosedLoopMethod method, const PidGains& gains,
                                              const std::vector<ClosedLoopRecord>& records,
                                              const ClosedLoopFitOptions& options) {
  check_inputs(model, gains, records, options);
  return ClosedLoopFit(model, method, gains, records, options).run();
}

}  // namespace modelgen
