// The Swevers drive model F (eq. 12) flattened: the rigid-body torques of theta's inertial
// parameters through coupling, transmission efficiency, motor inertia and friction.

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_drive_torque(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const DriveParameters drive = make_drive_parameters(graph, context.tree());
  SymbolicInputs rigid = context.symbols;
  rigid.p = rigid_body_parameters(graph, context.tree(), drive);
  const DriveTorques torques =
      derive_drive_torques(graph, context.model.drives.motor_from_joint, context.symbols, drive,
                           derive_inverse_dynamics(graph, context.tree(), rigid));
  return {vector_outputs("tau_M", torques.tau_M)};
}

}  // namespace modelgen::gen
