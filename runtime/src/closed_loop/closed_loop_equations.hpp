// The linear equations of the closed-loop methods (closed_loop_identification.cpp): the base
// regressor's rows of one joint, the decimated (eq. 13-14) equations of a record, their weighted
// stack (eq. 20), and the equations of an estimate's simulated closed loop on every record's
// reference.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/closed_loop/closed_loop_identification.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::detail {

// Row j of the base regressor at rows [from, from + count) of (q, dq, ddq): count x b.
Eigen::MatrixXd joint_rows(const IdentificationModel& model, const Eigen::MatrixXd& q,
                           const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, Eigen::Index from,
                           Eigen::Index count, int j);

// The equations of one record, decimated (eq. 13-14), per joint.
struct RecordEquations {
  std::vector<Eigen::MatrixXd> W;  // measured states
  std::vector<Eigen::VectorXd> y;  // measured torques
  std::vector<double> weight;      // 1 / sd of the joint's IDIM-WLS residual (eq. 20)
  std::vector<Eigen::Index> kept;  // decimated samples used
  // Samples x dof before the decimation: 0 where a joint's equation is left out near a
  // reversal (reversal_mask), on measured and simulated sides alike; empty: none.
  Eigen::ArrayXXd mask;
};

// Decimated samples where every joint, and every motor (K dq scaled to its joint by K_jj: a
// coupled motor has friction of its own), moves at least at the minimum speed; all of them
// when `min_speed` is empty.
// Equation j of every sample times mask(s, j) (mask empty: unchanged).
Eigen::MatrixXd masked(Eigen::MatrixXd rows, const Eigen::ArrayXXd& mask, int j);

std::vector<Eigen::Index> kept_rows(const Eigen::MatrixXd& dq, const Eigen::MatrixXd& K,
                                    const Eigen::VectorXd& min_speed);

// Stacks per-joint blocks of every record, each row times its weight.
Eigen::MatrixXd stack(const std::vector<RecordEquations>& equations,
                      const std::vector<std::vector<Eigen::MatrixXd>>& blocks, Eigen::Index rows,
                      Eigen::Index cols);

// The simulated equations of an estimate: its closed loop on every record's reference.
struct Simulated {
  std::vector<std::vector<Eigen::MatrixXd>> W, tau;  // regressor and command, decimated
};

// The closed loop of `estimate` on every record, decimated as the measured equations; false
// (with `failure` set) when it cannot be simulated.
bool simulate_equations(const IdentificationModel& model, const PidGains& gains,
                        const std::vector<ClosedLoopRecord>& records,
                        const ClosedLoopOptions& options,
                        const std::vector<RecordEquations>& equations,
                        const Eigen::VectorXd& estimate, Simulated& sim, std::string& failure);

}  // namespace modelgen::detail
