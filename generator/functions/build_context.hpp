// What every builder of a generated function works from: the robot, its base parameters and
// the shared expression DAG with the symbolic inputs, plus the small helpers several builders
// share (the base-parameter substitution, the state vector, row-major output lists).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "generator/dynamics/drive_model.hpp"
#include "generator/dynamics/newton_euler.hpp"
#include "generator/functions/function_entry.hpp"
#include "generator/symbolic/expr.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::gen {

struct BuildContext {
  const RobotModel& model;
  const BaseParameterSet& base;
  ExprGraph& graph;
  SymbolicInputs symbols;       ///< q, dq, ddq, sin/cos, signs and the standard parameters p
  std::vector<Scalar> scalars;  ///< the scalar types of the entry points, in file order

  const RigidBodyTree& tree() const { return model.tree; }
  int dof() const { return model.tree.dof; }
  int num_params() const { return static_cast<int>(model.tree.params.size()); }
  int num_base() const { return static_cast<int>(base.params.size()); }
};

/// "W[14]": one element of an array, as generated code reads or writes it.
std::string element(const std::string& array, int index);

/// The input leaf `array[index]`.
ExprId input_symbol(ExprGraph& graph, const std::string& array, int index);

/// The symbolic inputs with each base parameter beta[b] in place of the standard parameter it is
/// built on and the absorbed parameters at zero: Newton-Euler on them gives
/// tau = W_std p = W_base beta (Gautier & Briot eq. 4).
SymbolicInputs base_parameter_inputs(BuildContext& context);

/// M(q) on the base parameters, dof x dof row-major and symmetric (mass_matrix.cpp): the
/// rigid bodies by composite rigid bodies plus the drive inertias.
std::vector<ExprId> base_mass_matrix(BuildContext& context);

/// The state x = [q, dq, ddq] (3 dof symbols), and the name of its entry k: "dq[2]".
std::vector<ExprId> state_symbols(const SymbolicInputs& symbols);
std::string state_name(int k, int dof);

/// Outputs `array[i * cols + k] = value(i, k)` in row-major order; the first row names its
/// columns with `column_name(k)` when given.
std::vector<FunctionOutput> row_major_outputs(
    const std::string& array, int rows, int cols, const std::function<ExprId(int, int)>& value,
    const std::function<std::string(int)>& column_name = {});

/// Outputs `array[i] = values[i]`, without comments.
std::vector<FunctionOutput> vector_outputs(const std::string& array,
                                           const std::vector<ExprId>& values);

/// The drive regressor Y (derive_drive_regressor) on the standard regressor read from the input
/// array W_std: an entry of W_std that is zero in the symbolic regressor is zero here too, so
/// Y's structurally zero entries are known. Dense, row-major dof x theta.
std::vector<ExprId> drive_regressor_on_standard_inputs(BuildContext& context,
                                                       const DriveParameters& drive);

/// The entries of the dense drive regressor (drive_regressor_on_standard_inputs) that are not
/// structurally zero, in increasing order: the packed layout drive_regressor writes, entry p of
/// the packed array being dense entry result[p]. Depends on the robot only. A few may still be
/// zero for every input once simplified; drive_regressor leaves those unwritten (its
/// "unwritten" entries in the manifest) and its readers take them as zero.
std::vector<int> drive_regressor_entries(BuildContext& context);
/// The same from the dense drive regressor already derived.
std::vector<int> drive_regressor_entries(const std::vector<ExprId>& dense_Y,
                                         const ExprGraph& graph);

/// The input array Y of the functions given the drive regressor, dense row-major dof x theta:
/// the packed input symbol Y[p] at the p-th entry of drive_regressor_entries, zero elsewhere.
std::vector<ExprId> drive_regressor_input(BuildContext& context, const DriveParameters& drive);

/// A zero-initialized local array and a call to another entry point, as prologue statements.
std::string local_array(Scalar scalar, const std::string& name, const std::string& size);
std::string call(const std::string& function, const std::string& arguments);

}  // namespace modelgen::gen
