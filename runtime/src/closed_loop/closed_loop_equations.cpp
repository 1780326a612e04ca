// The closed-loop methods' equations of closed_loop_equations.hpp: regressor rows evaluated
// sample by sample, decimated with the records' factors, and the simulated commands paired as the
// records' torques were prepared.

#include "runtime/src/closed_loop/closed_loop_equations.hpp"

#include <exception>

#include "modelgen/signal/decimation.hpp"

namespace modelgen::detail {
namespace {

// The simulated command as the record's torque was prepared: held commands paired half
// a sample later (PreparationOptions::torque_hold) when the record's were.
Eigen::MatrixXd prepared_command(const ClosedLoopRecord& r, const ClosedLoopRun& run,
                                 Eigen::Index used) {
  Eigen::MatrixXd command = run.tau_command.middleRows(r.first_row, used);
  if (r.torque_hold) {
    const Eigen::RowVectorXd before = r.first_row > 0
                                          ? Eigen::RowVectorXd(run.tau_command.row(r.first_row - 1))
                                          : Eigen::RowVectorXd(2 * command.row(0) - command.row(1));
    for (Eigen::Index k = used - 1; k > 0; --k) {
      command.row(k) = 0.5 * (command.row(k) + command.row(k - 1));
    }
    command.row(0) = 0.5 * (command.row(0) + before);
  }
  return command;
}

}  // namespace

Eigen::MatrixXd joint_rows(const IdentificationModel& model, const Eigen::MatrixXd& q,
                           const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, Eigen::Index from,
                           Eigen::Index count, int j) {
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

Eigen::MatrixXd masked(Eigen::MatrixXd rows, const Eigen::ArrayXXd& mask, int j) {
  if (mask.size() != 0) rows = mask.col(j).matrix().asDiagonal() * rows;
  return rows;
}

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

bool simulate_equations(const IdentificationModel& model, const PidGains& gains,
                        const std::vector<ClosedLoopRecord>& records,
                        const ClosedLoopOptions& options,
                        const std::vector<RecordEquations>& equations,
                        const Eigen::VectorXd& estimate, Simulated& sim, std::string& failure) {
  const int n = model.dof(), b = model.num_base_params();
  const std::vector<double> values(estimate.data(), estimate.data() + b);
  sim.W.assign(records.size(), {});
  sim.tau.assign(records.size(), {});
  for (std::size_t e = 0; e < records.size(); ++e) {
    const ClosedLoopRecord& r = records[e];
    PidController controller(gains);
    ClosedLoopOptions simulation = options;
    simulation.encoder_resolution.resize(0);
    simulation.q_noise.resize(0);
    simulation.tau_noise.resize(0);
    ClosedLoopRun run;
    try {
      run = simulate_closed_loop(model, values, controller, r.qr, r.q0, r.dq0, simulation, r.t0);
    } catch (const std::exception& error) {
      failure = error.what();
      return false;
    }
    const Eigen::Index used = r.prepared.t.size();
    const auto& kept = equations[e].kept;
    const Eigen::MatrixXd command = prepared_command(r, run, used);
    for (int j = 0; j < n; ++j) {
      const Eigen::ArrayXXd& mask = equations[e].mask;
      sim.W[e].push_back(decimate_interior(
          masked(joint_rows(model, run.q, run.dq, run.ddq, r.first_row, used, j), mask, j),
          r.decimation)(kept, Eigen::all));
      sim.tau[e].push_back(
          decimate_interior(masked(command.col(j), mask, j), r.decimation)(kept, 0));
    }
  }
  return true;
}

}  // namespace modelgen::detail
