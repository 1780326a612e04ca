// Jacobian of the drive model F (Swevers eq. 12) with respect to the state (Bona & Curatella
// eq. 13-16): d tau_M / d x = c V^T d tau_G / d x + Rv K (dq block) + JM K (ddq block), with
// tau_G and d tau_G / d x from calls to the base inverse dynamics and its state Jacobian at
// beta = base_from_standard(p) (tau = W_std p = W_base beta for every p). The sign terms are
// piecewise constant: their derivative is taken as zero.

#include "generator/dynamics/drive_model.hpp"
#include "generator/emit/statement_writer.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

namespace {

std::vector<std::string> prologue(const DriveParameters& drive, Scalar scalar) {
  std::vector<std::string> lines = {local_array(scalar, "p_std", "kStandardParams")};
  for (std::size_t k = 0; k < drive.standard_index.size(); ++k) {
    lines.push_back(render_statement("statements/output",
                                     {{"target", element("p_std", drive.standard_index[k])},
                                      {"value", element("theta", static_cast<int>(k))}}));
  }
  lines.push_back(local_array(scalar, "beta", "kBaseParams"));
  lines.push_back(call("base_from_standard", "p_std, beta"));
  lines.push_back(local_array(scalar, "tau_G", "kDof"));
  lines.push_back(call("inverse_dynamics", "q, dq, ddq, beta, tau_G"));
  lines.push_back(local_array(scalar, "dtau_G", "kDof * 3 * kDof"));
  lines.push_back(call("inverse_dynamics_state_jacobian", "q, dq, ddq, beta, dtau_G"));
  return lines;
}

}  // namespace

FunctionDefinition build_drive_torque_state_jacobian(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const int n = context.dof();
  const Eigen::MatrixXd& K = context.model.drives.motor_from_joint;
  const Eigen::MatrixXd V = joint_from_motor(K, n);
  const DriveParameters drive = make_drive_parameters(graph, context.tree());
  std::vector<ExprId> tau_G;
  for (int i = 0; i < n; ++i) tau_G.push_back(input_symbol(graph, "tau_G", i));
  const DriveTorques torques = derive_drive_torques(graph, K, context.symbols, drive, tau_G);
  auto entry = [&](int i, int k) {
    std::vector<ExprId> chain;
    for (int j = 0; j < n; ++j) {
      chain.push_back(
          graph.mul(graph.constant(V(j, i)), input_symbol(graph, "dtau_G", j * 3 * n + k)));
    }
    std::vector<ExprId> terms = {graph.mul(torques.efficiency[i], graph.add(chain))};
    // Eq. 7 and 9: d (Rv dq_M) / d dq = Rv K, d (JM ddq_M) / d ddq = JM K.
    if (k >= n && k < 2 * n) {
      terms.push_back(graph.mul(graph.constant(K(i, k - n)), drive.Rv[i]));
    } else if (k >= 2 * n) {
      terms.push_back(graph.mul(graph.constant(K(i, k - 2 * n)), drive.JM[i]));
    }
    return graph.add(terms);
  };
  FunctionDefinition definition{
      row_major_outputs("J", n, 3 * n, entry, [&](int k) { return state_name(k, n); })};
  definition.reads = {{"dtau_G", "inverse_dynamics_state_jacobian", "J"}};
  definition.prologue = [drive](Scalar scalar) { return prologue(drive, scalar); };
  return definition;
}

}  // namespace modelgen::gen
