// Reads the 'drives' map of an MDH YAML description into the DriveChain: K = motor_from_joint
// with dq_motor = K dq_joint, from the gear ratios alone or from a coupling matrix written as
// Gautier & Briot's motor_from_joint (eq. 25) or Swevers's joint_from_motor (eq. 9).

#include "runtime/model/mdh_drive_chain.hpp"

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace modelgen {

namespace {

// 1-based link number of a moving joint -> 0-based dof index.
int dof_of_link(const YamlReader& in, const RobotModel& model, const YAML::Node& node, long link) {
  if (link < 1 || link > static_cast<long>(model.tree.bodies.size())) {
    in.fail(node, "joint " + std::to_string(link) + " does not exist");
  }
  const Body& body = model.tree.bodies[link - 1];
  if (body.type == JointType::kFixed) {
    in.fail(node,
            "joint " + std::to_string(link) + " ('" + body.name + "') is fixed and has no drive");
  }
  return body.dof_index;
}

Eigen::MatrixXd matrix(const YamlReader& in, const YAML::Node& node, const std::string& field) {
  if (!node.IsSequence() || node.size() == 0) {
    in.fail(node, "'" + field + "' must be a square matrix written as a list of rows");
  }
  const std::size_t rows = node.size();
  Eigen::MatrixXd m(rows, rows);
  for (std::size_t r = 0; r < rows; ++r) {
    const YAML::Node row = node[r];
    if (!row.IsSequence())
      in.fail(row,
              "row " + std::to_string(r + 1) + " of '" + field + "' must be a list of numbers");
    if (row.size() != rows) {
      in.fail(row, "'" + field + "' is not square: it has " + std::to_string(rows) +
                       " rows but row " + std::to_string(r + 1) + " has " +
                       std::to_string(row.size()) + " entries");
    }
    for (std::size_t c = 0; c < rows; ++c) m(r, c) = in.number(row[c], field);
  }
  return m;
}

void read_torque_constants(const YamlReader& in, const YAML::Node& node, int n,
                           DriveChain& drives) {
  const std::vector<double> constants = in.numbers(node, "torque_constant", n);
  drives.torque_constant = Eigen::Map<const Eigen::VectorXd>(constants.data(), n);
  for (int i = 0; i < n; ++i) {
    if (!(drives.torque_constant[i] > 0)) {
      in.fail(node[i], "a torque constant must be positive (N m/A)");
    }
  }
}

void read_joint_offsets(const YamlReader& in, const YAML::Node& offsets, int n,
                        DriveChain& drives) {
  if (!offsets.IsSequence() || static_cast<int>(offsets.size()) != n) {
    in.fail(offsets,
            "'joint_offset' must list " + std::to_string(n) + " values, one per moving joint");
  }
  for (int i = 0; i < n; ++i) drives.joint_offset[i] = in.angle(offsets[i], "joint_offset").value;
}

void read_ratios(const YamlReader& in, const YAML::Node& node, int n, DriveChain& drives) {
  drives.ratio = in.numbers(node, "ratio", n);
  for (std::size_t i = 0; i < drives.ratio.size(); ++i) {
    if (drives.ratio[i] == 0) in.fail(node[i], "a gear ratio cannot be zero");
  }
}

// The dof indices the coupling matrix's rows are for: 'joints' as written, else every moving
// joint.
std::vector<int> coupled_joints(const YamlReader& in, const YAML::Node& coupling,
                                const RobotModel& model) {
  std::vector<int> coupled;
  if (coupling["joints"]) {
    const YAML::Node joints = coupling["joints"];
    if (!joints.IsSequence()) in.fail(joints, "'joints' must be a list of joint numbers");
    for (const auto& j : joints)
      coupled.push_back(dof_of_link(in, model, j, in.integer(j, "joints")));
    if (std::set<int>(coupled.begin(), coupled.end()).size() != coupled.size()) {
      in.fail(joints, "'joints' lists a joint twice");
    }
  } else {
    for (int i = 0; i < model.dof(); ++i) coupled.push_back(i);
  }
  return coupled;
}

void check_coupling_size(const YamlReader& in, const YAML::Node& coupling,
                         const YAML::Node& matrix_node, const Eigen::MatrixXd& block,
                         const DriveChain& drives) {
  if (block.rows() != static_cast<Eigen::Index>(drives.coupled_joints.size())) {
    in.fail(matrix_node, "'" + drives.coupling_form + "' is " + std::to_string(block.rows()) + "x" +
                             std::to_string(block.rows()) + " but must be " +
                             std::to_string(drives.coupled_joints.size()) + "x" +
                             std::to_string(drives.coupled_joints.size()) +
                             (coupling["joints"] ? " (one row per joint in 'joints')"
                                                 : " (one row per moving joint; or list the "
                                                   "coupled joints in 'joints')"));
  }
}

// Gautier & Briot eq. 25: the matrix already carries the gear ratios on its diagonal.
void apply_motor_from_joint(const YamlReader& in, const YAML::Node& matrix_node,
                            const Eigen::MatrixXd& block, DriveChain& drives) {
  const std::vector<int>& idx = drives.coupled_joints;
  const Eigen::Index m = block.rows();
  for (Eigen::Index r = 0; r < m; ++r) {
    const int i = idx[r];
    if (!drives.ratio.empty() &&
        std::abs(block(r, r) - drives.ratio[i]) > 1e-12 * std::abs(block(r, r))) {
      in.fail(matrix_node, "diagonal entry " + std::to_string(r + 1) + " of motor_from_joint (" +
                               std::to_string(block(r, r)) +
                               ") disagrees with the gear ratio of joint " + std::to_string(i + 1) +
                               " (" + std::to_string(drives.ratio[i]) + ")");
    }
    for (Eigen::Index c = 0; c < m; ++c) drives.motor_from_joint(i, idx[c]) = block(r, c);
  }
}

// Swevers eq. 9: q_joint = V (q_motor / ratio), so q_motor = diag(ratio) V^-1 q_joint.
void apply_joint_from_motor(const Eigen::MatrixXd& inverse, const std::vector<double>& ratio,
                            DriveChain& drives) {
  const std::vector<int>& idx = drives.coupled_joints;
  const Eigen::Index m = inverse.rows();
  for (Eigen::Index r = 0; r < m; ++r) {
    for (Eigen::Index c = 0; c < m; ++c) {
      drives.motor_from_joint(idx[r], idx[c]) = ratio[idx[r]] * inverse(r, c);
    }
  }
}

// `ratio`: the gear ratios, 1 where none are given.
void read_coupling(const YamlReader& in, const YAML::Node& coupling,
                   const std::vector<double>& ratio, RobotModel& model) {
  DriveChain& drives = model.drives;
  in.check_keys(coupling, {"joint_from_motor", "motor_from_joint", "joints"}, "coupling");
  const bool swevers = static_cast<bool>(coupling["joint_from_motor"]);
  const bool gautier = static_cast<bool>(coupling["motor_from_joint"]);
  if (swevers == gautier) {
    in.fail(coupling,
            "coupling needs exactly one of 'joint_from_motor' (Swevers eq. 9: "
            "q_joint = V q_motor) and 'motor_from_joint' (Gautier eq. 25)");
  }
  drives.coupling_form = swevers ? "joint_from_motor" : "motor_from_joint";
  const YAML::Node matrix_node = coupling[drives.coupling_form];
  const Eigen::MatrixXd block = matrix(in, matrix_node, drives.coupling_form);
  drives.coupling_as_written = block;
  drives.coupled_joints = coupled_joints(in, coupling, model);
  check_coupling_size(in, coupling, matrix_node, block, drives);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(block);
  lu.setThreshold(1e-9);
  if (!lu.isInvertible()) {
    in.fail(matrix_node, "'" + drives.coupling_form + "' is singular (rank " +
                             std::to_string(lu.rank()) + " of " + std::to_string(block.rows()) +
                             "): motor and joint positions would not determine each other");
  }
  if (gautier) {
    apply_motor_from_joint(in, matrix_node, block, drives);
  } else {
    apply_joint_from_motor(lu.inverse(), ratio, drives);
  }
}

}  // namespace

void read_drive_chain(const YamlReader& in, const YAML::Node& node, RobotModel& model) {
  DriveChain& drives = model.drives;
  const int n = model.dof();
  drives.motor_from_joint = Eigen::MatrixXd::Identity(n, n);
  drives.torque_constant = Eigen::VectorXd::Zero(n);
  drives.joint_offset = Eigen::VectorXd::Zero(n);
  if (!node) return;
  in.check_keys(node, {"ratio", "coupling", "torque_constant", "joint_offset"}, "drives");
  if (node["torque_constant"]) read_torque_constants(in, node["torque_constant"], n, drives);
  if (node["joint_offset"]) read_joint_offsets(in, node["joint_offset"], n, drives);
  if (node["ratio"]) read_ratios(in, node["ratio"], n, drives);
  const std::vector<double> ratio =
      drives.ratio.empty() ? std::vector<double>(n, 1.0) : drives.ratio;
  for (int i = 0; i < n; ++i) drives.motor_from_joint(i, i) = ratio[i];
  if (node["coupling"]) read_coupling(in, node["coupling"], ratio, model);
}

}  // namespace modelgen
