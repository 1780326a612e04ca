// The drive model F (Swevers eq. 12) with its Jacobian with respect to theta (eq. 14), the
// residual and Jacobian a least-squares solver asks for at once. tau_G = W_std p with W_std from
// a call to idim_regressor_standard: F is then an expression of W_std and theta, d F / d theta
// its symbolic derivative, and tau_M comes from the same intermediates (no second Newton-Euler
// pass; flattened, the drive Jacobians doubled the compile time of the larger models). The sign
// terms (friction, efficiency branch) are piecewise constant: their derivative is taken as zero.

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"
#include "generator/symbolic/derivative.hpp"

namespace modelgen::gen {

FunctionDefinition build_drive_torque_jacobian(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const int n = context.dof(), num_params = context.num_params();
  const DriveParameters drive = make_drive_parameters(graph, context.tree());
  std::vector<ExprId> tau_G;
  for (int i = 0; i < n; ++i) {
    std::vector<ExprId> terms;
    for (std::size_t k = 0; k < drive.standard_index.size(); ++k) {
      terms.push_back(graph.mul(
          input_symbol(graph, "W_std", i * num_params + drive.standard_index[k]), drive.theta[k]));
    }
    tau_G.push_back(graph.add(std::move(terms)));
  }
  const DriveTorques torques = derive_drive_torques(graph, context.model.drives.motor_from_joint,
                                                    context.symbols, drive, tau_G);
  const std::vector<ExprId> J = jacobian(graph, torques.tau_M, drive.theta);
  const int num_drive = static_cast<int>(drive.theta.size());
  FunctionDefinition definition{vector_outputs("tau_M", torques.tau_M)};
  for (FunctionOutput& output : row_major_outputs(
           "J", n, num_drive, [&](int i, int k) { return J[i * num_drive + k]; },
           [&](int k) { return drive.names[k]; })) {
    definition.outputs.push_back(std::move(output));
  }
  definition.reads = {{"W_std", "idim_regressor_standard", "W"}};
  definition.prologue = [](Scalar scalar) {
    return std::vector<std::string>{local_array(scalar, "W_std", "kDof * kStandardParams"),
                                    call("idim_regressor_standard", "q, dq, ddq, W_std")};
  };
  return definition;
}

}  // namespace modelgen::gen
