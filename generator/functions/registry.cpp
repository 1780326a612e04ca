// The table of generated functions. Builders run in table order on one shared DAG whose node
// ids follow creation order; appending an entry leaves the bodies of the others unchanged.

#include "generator/functions/registry.hpp"

namespace modelgen::gen {

// The builders, one per file generator/functions/<name>.cpp; the table is their only caller.
FunctionDefinition build_idim_regressor_standard(BuildContext& context);
FunctionDefinition build_inverse_dynamics_standard(BuildContext& context);
FunctionDefinition build_joint_sincos(BuildContext& context);
FunctionDefinition build_base_from_standard(BuildContext& context);
FunctionDefinition build_idim_regressor(BuildContext& context);
FunctionDefinition build_inverse_dynamics(BuildContext& context);
FunctionDefinition build_inverse_dynamics_state_jacobian(BuildContext& context);
FunctionDefinition build_drive_torque(BuildContext& context);
FunctionDefinition build_drive_torque_jacobian(BuildContext& context);
FunctionDefinition build_drive_torque_state_jacobian(BuildContext& context);
FunctionDefinition build_energy_regressor(BuildContext& context);
FunctionDefinition build_power_regressor(BuildContext& context);
FunctionDefinition build_mass_matrix(BuildContext& context);
FunctionDefinition build_inverse_dynamics_identified(BuildContext& context);
FunctionDefinition build_drive_regressor(BuildContext& context);
FunctionDefinition build_drive_torque_given_regressor(BuildContext& context);
FunctionDefinition build_drive_torque_jacobian_given_regressor(BuildContext& context);
FunctionDefinition build_mass_matrix_and_bias(BuildContext& context);

namespace {

using E = Extent;
using S = Section;

// The arrays most functions share.
const ArraySpec kQ{"q", E::kDof}, kDq{"dq", E::kDof}, kDdq{"ddq", E::kDof};
// The drive regressor of one sample, packed (its entries that are not structurally zero), as
// drive_regressor writes it.
const ArraySpec kY{"Y", E::kDriveRegressorEntries};

// Not every function has a _sincos variant: the state Jacobian's body is several times that of
// the inverse dynamics, so sharing the sines and cosines would save under 1 % of its work for
// twice the code to compile; the drive model is called once per sample in an estimation loop.
// clang-format off
const std::vector<FunctionEntry> kRegistry = {
    {"idim_regressor_standard", S::kStandard, Variants::kSincos, InModelStruct::kNo,
     {kQ, kDq, kDdq}, {{"W", E::kDof, E::kStandardParams}}, build_idim_regressor_standard},
    {"inverse_dynamics_standard", S::kStandard, Variants::kSincos, InModelStruct::kNo,
     {kQ, kDq, kDdq, {"p", E::kStandardParams}}, {{"tau", E::kDof}},
     build_inverse_dynamics_standard},
    {"joint_sincos", S::kStandard, Variants::kPlain, InModelStruct::kYes,
     {kQ}, {{"sin_q", E::kDof}, {"cos_q", E::kDof}}, build_joint_sincos},
    {"base_from_standard", S::kRegrouping, Variants::kPlain, InModelStruct::kYes,
     {{"p_standard", E::kStandardParams}}, {{"beta", E::kBaseParams}}, build_base_from_standard},
    {"idim_regressor", S::kBase, Variants::kSincos, InModelStruct::kYes,
     {kQ, kDq, kDdq}, {{"W", E::kDof, E::kBaseParams}}, build_idim_regressor},
    {"inverse_dynamics", S::kBase, Variants::kSincos, InModelStruct::kYes,
     {kQ, kDq, kDdq, {"beta", E::kBaseParams}}, {{"tau", E::kDof}}, build_inverse_dynamics},
    {"inverse_dynamics_state_jacobian", S::kBaseJacobian, Variants::kPlain, InModelStruct::kYes,
     {kQ, kDq, kDdq, {"beta", E::kBaseParams}}, {{"J", E::kDof, E::kState}},
     build_inverse_dynamics_state_jacobian},
    {"drive_torque", S::kDriveModel, Variants::kPlain, InModelStruct::kYes,
     {kQ, kDq, kDdq, {"theta", E::kDriveParams}}, {{"tau_M", E::kDof}}, build_drive_torque},
    {"drive_torque_jacobian", S::kDriveModel, Variants::kPlain, InModelStruct::kYes,
     {kQ, kDq, kDdq, {"theta", E::kDriveParams}},
     {{"tau_M", E::kDof}, {"J", E::kDof, E::kDriveParams}}, build_drive_torque_jacobian,
     Emitted::kAlways, {"idim_regressor_standard"}},
    {"drive_torque_state_jacobian", S::kDriveModel, Variants::kPlain, InModelStruct::kYes,
     {kQ, kDq, kDdq, {"theta", E::kDriveParams}}, {{"J", E::kDof, E::kState}},
     build_drive_torque_state_jacobian, Emitted::kAlways,
     {"base_from_standard", "inverse_dynamics", "inverse_dynamics_state_jacobian"}},
    {"energy_regressor", S::kPowerModel, Variants::kSincos, InModelStruct::kNo,
     {kQ, kDq}, {{"h", E::kBaseParams}}, build_energy_regressor},
    {"power_regressor", S::kPowerModel, Variants::kSincos, InModelStruct::kYes,
     {kQ, kDq, kDdq}, {{"dh", E::kBaseParams}}, build_power_regressor},
    {"mass_matrix", S::kBase, Variants::kSincos, InModelStruct::kYes,
     {kQ, {"beta", E::kBaseParams}}, {{"M", E::kDof, E::kDof}}, build_mass_matrix},
    {"inverse_dynamics_identified", S::kIdentified, Variants::kPlain, InModelStruct::kNo,
     {kQ, kDq, kDdq}, {{"tau", E::kDof}}, build_inverse_dynamics_identified,
     Emitted::kWithEstimate, {"inverse_dynamics"}},
    {"drive_regressor", S::kDriveModel, Variants::kPlain, InModelStruct::kYes,
     {kQ, kDq, kDdq}, {kY}, build_drive_regressor,
     Emitted::kAlways, {"idim_regressor_standard"}},
    {"drive_torque_given_regressor", S::kDriveModel, Variants::kPlain, InModelStruct::kYes,
     {kY, {"theta", E::kDriveParams}}, {{"tau_M", E::kDof}}, build_drive_torque_given_regressor},
    {"drive_torque_jacobian_given_regressor", S::kDriveModel, Variants::kPlain,
     InModelStruct::kYes, {kY, {"theta", E::kDriveParams}},
     {{"tau_M", E::kDof}, {"J", E::kDof, E::kDriveParams}},
     build_drive_torque_jacobian_given_regressor},
    {"mass_matrix_and_bias", S::kBase, Variants::kPlain, InModelStruct::kYes,
     {kQ, kDq, {"beta", E::kBaseParams}}, {{"M", E::kDof, E::kDof}, {"h", E::kDof}},
     build_mass_matrix_and_bias},
};
// clang-format on

}  // namespace

const std::vector<FunctionEntry>& function_registry() { return kRegistry; }

}  // namespace modelgen::gen
