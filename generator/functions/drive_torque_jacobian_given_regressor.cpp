// drive_torque_jacobian on a sample's drive regressor Y (drive_regressor) instead of the state:
// tau_M and d tau_M / d theta (Swevers eq. 14, 18) with no Newton-Euler pass, what a fit
// evaluates on every iteration. The inertial columns are c_i Y(i, k) (Y unpacked), the motor
// columns Y's own, Rz's from the efficiency factor; the sign terms count as constant
// (drive_model.hpp). Y is packed (drive_regressor_input); the entries drive_regressor never
// writes are taken as 0 (`reads`).

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"
#include "generator/symbolic/derivative.hpp"

namespace modelgen::gen {

FunctionDefinition build_drive_torque_jacobian_given_regressor(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const DriveParameters drive = make_drive_parameters(graph, context.tree());
  const std::vector<ExprId> Y = drive_regressor_input(context, drive);
  const std::vector<ExprId> tau_M = drive_torques_from_regressor(graph, drive, Y);
  const std::vector<ExprId> J = jacobian(graph, tau_M, drive.theta);
  const int columns = static_cast<int>(drive.theta.size());
  FunctionDefinition definition{vector_outputs("tau_M", tau_M)};
  for (FunctionOutput& output : row_major_outputs(
           "J", context.dof(), columns, [&](int i, int k) { return J[i * columns + k]; },
           [&](int k) { return drive.names[k]; })) {
    definition.outputs.push_back(std::move(output));
  }
  definition.reads = {{"Y", "drive_regressor", "Y"}};
  return definition;
}

}  // namespace modelgen::gen
