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

namespace modelgen {

namespace {

// Relative change of the estimate below which the iterations stop whatever the standard
// deviations (a few hundred rounding errors).
constexpr double kSettled = 1e-12;
// Step halvings DIDIM tries before it stops.
constexpr int kMaxHalvings = 8;

// Row j of the base regressor at rows [from, from + count) of (q, dq, ddq): count x b.
Eigen::MatrixXd joint_rows(const IdentificationModel& model, const Eigen::MatrixXd& q,
                           const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq,
                           Eigen::Index from, Eigen::Index count, int j) {
  const int n = model.dof(), b = model.num_base_params();
  Eigen::MatrixXd rows(count, b);
  Eigen::VectorXd qs(n), dqs(n), ddqs(n);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> W(n, b);
  for (Eigen::Index s = 0; s < count; ++s) {
    qs = q.row(from + s).transpose();
    dqs = dq.row(from + s).transpose();
    ddqs = ddq.row(from + s).transpose();
    model.regressor(qs.data(), dqs.data(), ddqs.data(), W.data());
    rows.row(s) = W.row(j);
  }
  return rows;
}

// The equations of one record, decimated (eq. 13-14), per joint.
struct RecordEquations {
  std::vector<Eigen::MatrixXd> W;  // measured states
  std::vector<Eigen::VectorXd> y;  // measured torques
  std::vector<double> weight;      // 1 / sd of the joint's IDIM-WLS residual (eq. 20)
  std::vector<Eigen::Index> kept;  // decimated samples used
};

// Decimated samples where every joint, and every motor (K dq scaled to its joint by K_jj: a
// coupled motor has friction of its own), moves at least at the minimum speed; all of them
// when `min_speed` is empty.
std::vector<Eigen::Index> kept_rows(const Eigen::MatrixXd& dq, const Eigen::MatrixXd& K,
                                    const Eigen::VectorXd& min_speed) {
  std::vector<Eigen::Index> kept;
  const Eigen::MatrixXd motors = dq * K.transpose() * K.diagonal().cwiseInverse().asDiagonal();
  for (Eigen::Index s = 0; s < dq.rows(); ++s) {
    if (min_speed.size() == 0 ||
        ((dq.row(s).cwiseAbs().transpose().array() >= min_speed.array()).all() &&
         (motors.row(s).cwiseAbs().transpose().array() >= min_speed.array()).all())) {
      kept.push_back(s);
    }
  }
  return kept;
}

// Stacks per-joint blocks of every record, each row times its weight.
Eigen::MatrixXd stack(const std::vector<RecordEquations>& equations,
                      const std::vector<std::vector<Eigen::MatrixXd>>& blocks, Eigen::Index rows,
                      Eigen::Index cols) {
  Eigen::MatrixXd out(rows, cols);
  Eigen::Index at = 0;
  for (std::size_t e = 0; e < equations.size(); ++e) {
    for (std::size_t j = 0; j < blocks[e].size(); ++j) {
      const Eigen::MatrixXd& block = blocks[e][j];
      out.middleRows(at, block.rows()) = equations[e].weight[j] * block;
      at += block.rows();
    }
  }
  return out;
}

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

}  // namespace

ClosedLoopIdentification identify_closed_loop(const IdentificationModel& model,
                                              ClosedLoopMethod method, const PidGains& gains,
                                              const std::vector<ClosedLoopRecord>& records,
                                              const ClosedLoopFitOptions& options) {
  gains.check();
  const int n = model.dof(), b = model.num_base_params();
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
  const std::vector<std::string>& names = model.base_param_names();

  // The measured equations, decimated once; the start, IDIM-WLS on them.
  std::vector<RecordEquations> equations(records.size());
  std::vector<std::vector<Eigen::MatrixXd>> measured(records.size()), torques(records.size());
  Eigen::Index rows = 0;
  for (std::size_t e = 0; e < records.size(); ++e) {
    const ClosedLoopRecord& r = records[e];
    const Trajectory& x = r.prepared;
    equations[e].kept = kept_rows(decimate_interior(x.dq, r.decimation), model.drive_chain().motor_from_joint,
                                  options.min_speed);
    if (equations[e].kept.size() * static_cast<std::size_t>(n) <= static_cast<std::size_t>(b)) {
      throw EstimationError(x.source + ": " + std::to_string(equations[e].kept.size()) +
                            " samples are left where every joint moves faster than the "
                            "minimum speed, too few for " + std::to_string(b) + " parameters");
    }
    const auto& kept = equations[e].kept;
    for (int j = 0; j < n; ++j) {
      equations[e].W.push_back(
          decimate_interior(joint_rows(model, x.q, x.dq, x.ddq, 0, x.t.size(), j),
                            r.decimation)(kept, Eigen::all));
      equations[e].y.push_back(decimate_interior(x.tau.col(j), r.decimation)(kept, 0));
      measured[e].push_back(equations[e].W.back());
      torques[e].push_back(equations[e].y.back());
      rows += equations[e].y.back().size();
    }
    equations[e].weight.assign(static_cast<std::size_t>(n), 1.0);
  }
  if (rows <= b) {
    throw EstimationError("closed-loop identification: " + std::to_string(rows) +
                          " equations after decimation for " + std::to_string(b) +
                          " base parameters");
  }
  Eigen::VectorXd beta = fit_ols(stack(equations, measured, rows, b),
                                 stack(equations, torques, rows, 1), names).value;
  // Eq. 20: each joint of each record weighted by its residual's standard deviation.
  std::vector<double> group_sd;
  for (RecordEquations& eq : equations) {
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd residual = eq.y[j] - eq.W[j] * beta;
      const double sd = std::sqrt(residual.squaredNorm() / static_cast<double>(residual.size()));
      eq.weight[j] = sd > 0 ? 1.0 / sd : 1.0;
      group_sd.push_back(sd);
    }
  }
  const Eigen::MatrixXd Wm = stack(equations, measured, rows, b);
  const Eigen::VectorXd y = stack(equations, torques, rows, 1).col(0);
  LeastSquaresResult fit = fit_ols(Wm, y, names);  // IDIM-WLS
  ClosedLoopIdentification out;
  out.start = beta = fit.value;

  // The simulated equations of an estimate: its closed loop on every record's reference.
  struct Simulated {
    std::vector<std::vector<Eigen::MatrixXd>> W, tau;  // regressor and command, decimated
  };
  std::string failure;
  auto simulate_with = [&](const Eigen::VectorXd& estimate, Simulated& sim) {
    const std::vector<double> values(estimate.data(), estimate.data() + b);
    sim.W.assign(records.size(), {});
    sim.tau.assign(records.size(), {});
    for (std::size_t e = 0; e < records.size(); ++e) {
      const ClosedLoopRecord& r = records[e];
      PidController controller(gains);
      ClosedLoopOptions simulation = options.simulation;
      simulation.encoder_resolution.resize(0);
      simulation.q_noise.resize(0);
      simulation.tau_noise.resize(0);
      ClosedLoopRun run;
      try {
        run = simulate_closed_loop(model, values, controller, r.qr, r.q0, r.dq0, simulation,
                                   r.t0);
      } catch (const std::exception& error) {
        failure = error.what();
        return false;
      }
      const Eigen::Index used = r.prepared.t.size();
      const auto& kept = equations[e].kept;
      // The simulated command as the record's torque was prepared: held commands paired half
      // a sample later (PreparationOptions::torque_hold) when the record's were.
      Eigen::MatrixXd command = run.tau_command.middleRows(r.first_row, used);
      if (r.torque_hold) {
        const Eigen::RowVectorXd before =
            r.first_row > 0 ? Eigen::RowVectorXd(run.tau_command.row(r.first_row - 1))
                            : Eigen::RowVectorXd(2 * command.row(0) - command.row(1));
        for (Eigen::Index k = used - 1; k > 0; --k) {
          command.row(k) = 0.5 * (command.row(k) + command.row(k - 1));
        }
        command.row(0) = 0.5 * (command.row(0) + before);
      }
      for (int j = 0; j < n; ++j) {
        sim.W[e].push_back(
            decimate_interior(joint_rows(model, run.q, run.dq, run.ddq, r.first_row, used, j),
                              r.decimation)(kept, Eigen::all));
        sim.tau[e].push_back(decimate_interior(command.col(j), r.decimation)(kept, 0));
      }
    }
    return true;
  };
  auto output_error = [&](const Simulated& sim) {
    return (y - stack(equations, sim.tau, rows, 1).col(0)).squaredNorm();
  };
  Simulated current;
  if (!simulate_with(beta, current)) {
    throw EstimationError("the closed loop could not be simulated with the IDIM-WLS estimate (" +
                          failure + "); try --physical, or check the controller's gains");
  }

  // Iterate: simulate with the last estimate, refit.
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    const Eigen::MatrixXd Ws = stack(equations, current.W, rows, b);
    Eigen::VectorXd next;
    LeastSquaresResult result;
    if (method == ClosedLoopMethod::kDidim) {
      // The Gauss-Newton step of DIDIM on the output error Y - tau_s(beta), with the
      // simulated regressor as its Jacobian: a linear fit. (tau_s = W_s beta where the
      // simulated states obey the model; the simulation's smoothed friction makes them
      // differ near rest, and the simulated torque is the output.) The Jacobian leaves out
      // how the states move with beta: a step that does not lower the output error (or
      // makes a robot that cannot be simulated) is halved.
      const double cost = output_error(current);
      result = fit_ols(Ws, y - stack(equations, current.tau, rows, 1).col(0), names);
      const Eigen::VectorXd step = result.value;
      Simulated trial;
      double alpha = 1;
      bool accepted = false;
      for (int halvings = 0; halvings <= kMaxHalvings && !accepted; ++halvings, alpha /= 2) {
        next = beta + alpha * step;
        accepted = simulate_with(next, trial) && output_error(trial) <= cost;
      }
      if (!accepted) {
        out.iterations = iteration;
        // The step leaves out how the states move with beta; within a standard deviation of
        // the minimum that is what is left of it.
        double full = 0;
        for (int k = 0; k < b; ++k) {
          full = std::max(full, std::abs(step[k]) / std::max(result.std_dev[k], 1e-300));
        }
        // The estimate stays; its statistics are those of this last linearisation.
        result.value = beta;
        fit = result;
        if (full < 1) {
          out.converged = true;
        } else {
          out.stop_reason = "no step along the Gauss-Newton direction lowers the output error";
        }
        break;
      }
      current = std::move(trial);
      result.value = next;
    } else {
      // IV: (Z^T W) beta = Z^T Y, columns scaled to unit norm for the solve.
      const Eigen::VectorXd scale = Wm.colwise().norm().cwiseMax(1e-300).cwiseInverse();
      const Eigen::MatrixXd Zs = Ws * scale.asDiagonal(), Ws_ = Wm * scale.asDiagonal();
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(Zs.transpose() * Ws_);
      if (!lu.isInvertible()) {
        throw EstimationError("IDIM-IV: the instruments are not correlated with every column "
                              "of the regressor (Z^T W is singular)");
      }
      next = scale.asDiagonal() * lu.solve(Zs.transpose() * y);
      const Eigen::VectorXd residual = y - Wm * next;
      const double variance = residual.squaredNorm() / static_cast<double>(rows - b);
      const Eigen::MatrixXd A_inverse = lu.inverse();
      const Eigen::MatrixXd covariance = variance * scale.asDiagonal() * A_inverse *
                                         (Zs.transpose() * Zs) * A_inverse.transpose() *
                                         scale.asDiagonal();
      result = fit;  // the measured W's statistics (condition number, equations)
      result.value = next;
      result.std_dev = covariance.diagonal().cwiseMax(0).cwiseSqrt();
      result.information = covariance.inverse();
      result.residual_std_dev = std::sqrt(variance);
    }
    double move = 0;
    for (int k = 0; k < b; ++k) {
      const double sd = result.std_dev[k] > 0 ? result.std_dev[k] : 1.0;
      move = std::max(move, std::abs(next[k] - beta[k]) / sd);
    }
    // Noise-free data give standard deviations near 0: then the estimate's own change decides.
    const bool settled = (next - beta).norm() <= kSettled * next.norm();
    beta = next;
    fit = result;
    out.iterations = iteration;
    out.moves.push_back(move);
    if (options.on_iteration) options.on_iteration(iteration, move);
    if (move < options.tolerance || settled) {
      out.converged = true;
      break;
    }
    // The next instruments: the closed loop of this estimate (DIDIM simulated it already).
    if (method == ClosedLoopMethod::kIv && iteration < options.max_iterations &&
        !simulate_with(beta, current)) {
      throw EstimationError("iteration " + std::to_string(iteration) +
                            ": the closed loop could not be simulated with the estimate (" +
                            failure + "); try --physical on IDIM-WLS first");
    }
    // Changes that no longer shrink: the iterations circle (the smoothed friction of the
    // simulations moves with the estimate); more of them would not settle.
    const std::size_t m = out.moves.size();
    if (m >= 6 && *std::max_element(out.moves.end() - 3, out.moves.end()) >=
                      *std::max_element(out.moves.end() - 6, out.moves.end() - 3)) {
      out.stop_reason = "the changes no longer shrink";
      break;
    }
  }

  // Statistics on the decimated equations, the residual the method minimises.
  for (int k = 0; k < b; ++k) {
    fit.rel_std_dev[k] = fit.value[k] != 0 ? 100 * fit.std_dev[k] / std::abs(fit.value[k])
                                           : INFINITY;
  }
  fit.group_std_dev = group_sd;
  Eigen::VectorXd error_squares = Eigen::VectorXd::Zero(n), torque_squares = error_squares;
  double error_total = 0, torque_total = 0;
  Eigen::Index samples = 0;
  for (std::size_t e = 0; e < records.size(); ++e) {
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd& tau = torques[e][j];
      error_squares[j] += method == ClosedLoopMethod::kDidim
                              ? (tau - current.tau[e][j]).squaredNorm()
                              : (tau - measured[e][j] * beta).squaredNorm();
      torque_squares[j] += tau.squaredNorm();
    }
    samples += torques[e][0].size();
  }
  error_total = error_squares.sum();
  torque_total = torque_squares.sum();
  fit.relative_error_norm = std::sqrt(error_total / torque_total);
  out.id.fit = fit;
  out.id.names = names;
  out.id.rms_error = (error_squares / static_cast<double>(samples)).cwiseSqrt();
  out.id.rms_torque = (torque_squares / static_cast<double>(samples)).cwiseSqrt();
  out.id.torque_rel_error_norm = fit.relative_error_norm;
  out.id.samples = samples;
  for (std::size_t e = 0; e < records.size(); ++e) {
    const ClosedLoopRecord& r = records[e];
    out.id.slow_samples += decimated_interior(r.prepared.t.size(), r.decimation).count -
                           static_cast<Eigen::Index>(equations[e].kept.size());
  }
  return out;
}

}  // namespace modelgen
