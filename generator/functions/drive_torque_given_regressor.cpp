// The drive model F (Swevers eq. 12) on a sample's drive regressor Y (drive_regressor): the
// torques of a residual-only evaluation in a fit, with no Newton-Euler pass. Y is packed
// (drive_regressor_input); the entries drive_regressor never writes are taken as 0 (`reads`).

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_drive_torque_given_regressor(BuildContext& context) {
  const DriveParameters drive = make_drive_parameters(context.graph, context.tree());
  const std::vector<ExprId> Y = drive_regressor_input(context, drive);
  FunctionDefinition definition{
      vector_outputs("tau_M", drive_torques_from_regressor(context.graph, drive, Y))};
  definition.reads = {{"Y", "drive_regressor", "Y"}};
  return definition;
}

}  // namespace modelgen::gen
