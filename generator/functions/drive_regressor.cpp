// The part of the drive model F (Swevers eq. 12) that does not depend on theta, per sample: the
// regressor Y of the model with unit efficiencies (section 3.2's linear model), V^T W_std in
// the inertial columns (eq. 10) and the motor motion in those of JM, Rv, Rc (eq. 5-7, 9). A fit
// evaluates it once per sample and hands it to the _given_regressor functions on every
// iteration, packed: its structurally zero entries are neither stored nor read. W_std comes from
// a call to idim_regressor_standard; its structurally zero entries are not read.

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_drive_regressor(BuildContext& context) {
  const DriveParameters drive = make_drive_parameters(context.graph, context.tree());
  const std::vector<ExprId> Y = drive_regressor_on_standard_inputs(context, drive);
  const int columns = static_cast<int>(drive.theta.size());
  // Packed: only the entries that are not structurally zero, each named by its place.
  FunctionDefinition definition;
  const std::vector<int> entries = drive_regressor_entries(Y, context.graph);
  for (std::size_t p = 0; p < entries.size(); ++p) {
    const int k = entries[p];
    definition.outputs.push_back({element("Y", static_cast<int>(p)), Y[static_cast<std::size_t>(k)],
                                  "row " + std::to_string(k / columns) + ", " +
                                      drive.names[static_cast<std::size_t>(k % columns)]});
  }
  definition.reads = {{"W_std", "idim_regressor_standard", "W"}};
  definition.prologue = [](Scalar scalar) {
    return std::vector<std::string>{local_array(scalar, "W_std", "kDof * kStandardParams"),
                                    call("idim_regressor_standard", "q, dq, ddq, W_std")};
  };
  return definition;
}

}  // namespace modelgen::gen
