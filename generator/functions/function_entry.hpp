// What the registry says about one generated function (name, arrays, variants, place in the
// files and in the Model struct, builder), and what its builder returns: the outputs as
// expressions of the shared DAG, plus any calls to other entry points.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "generator/emit/statement_writer.hpp"

namespace modelgen::gen {

struct BuildContext;

/// Where a function appears in the generated files: the sections in this order, each with its
/// functions in registry order followed by their _sincos variants.
enum class Section {
  kStandard,      ///< on the standard parameters, and the shared sines and cosines
  kRegrouping,    ///< base parameters from standard ones
  kBase,          ///< on the base parameters
  kBaseJacobian,  ///< derivatives of the base inverse dynamics
  kPowerModel,    ///< Gautier & Briot eq. 8-10
  kDriveModel,    ///< Swevers et al. 2002 eq. 12 and its Jacobians
  kIdentified,    ///< on the identified base parameters of --params (firmware constants)
};

/// A dimension of an array, in the counts of the generated header.
/// kDriveRegressorEntries: the drive regressor's entries that are not structurally zero (the
/// packed layout, build_context.hpp's drive_regressor_entries).
enum class Extent {
  kOne,
  kDof,
  kState,
  kStandardParams,
  kBaseParams,
  kDriveParams,
  kDriveRegressorEntries
};

/// An input or output array of a generated function: rows x cols values, row-major.
struct ArraySpec {
  const char* name;
  Extent rows;
  Extent cols = Extent::kOne;
};

/// Whether a function also has a `<name>_sincos` entry point that takes sin_q, cos_q (after q)
/// from joint_sincos instead of computing them.
enum class Variants { kPlain, kSincos };

/// Whether the Model struct of the generated header forwards to the (double) function.
enum class InModelStruct { kNo, kYes };

/// Whether a function is generated for every model or only with an estimate (--params), whose
/// base parameters it uses as constants.
enum class Emitted { kAlways, kWithEstimate };

/// What a builder derives.
struct FunctionDefinition {
  /// The output entries in the order they are written; their count is the sum of the sizes of
  /// the entry's outputs.
  std::vector<FunctionOutput> outputs;
  /// Statements before the body: local arrays filled by calls to other entry points.
  std::function<std::vector<std::string>(Scalar)> prologue{};
  /// The prologue's call writes the outputs (a function that wraps another entry point), so
  /// `outputs` stays empty.
  bool outputs_written_by_call = false;
  /// Arrays this function reads (`array[k]` leaves: a local array a prologue call fills, or an
  /// input the caller fills with another entry point) that hold another function's output:
  /// the entries that function never writes are zero, and the emitter substitutes 0 for them.
  struct ReadsOutput {
    std::string array;     ///< as this function names it: "W_std", "Y"
    std::string function;  ///< the registry name of the function that writes it
    std::string output;    ///< that function's output array: "W"
  };
  std::vector<ReadsOutput> reads{};
};

using Builder = FunctionDefinition (*)(BuildContext& context);

/// One generated function. Its documentation is templates/functions/<name>.tmpl.
struct FunctionEntry {
  const char* name;
  Section section;
  Variants variants;
  InModelStruct in_model_struct;
  std::vector<ArraySpec> inputs;
  std::vector<ArraySpec> outputs;
  Builder build;
  Emitted emitted = Emitted::kAlways;
  /// The entry points the builder's prologue calls; their operation counts add to this
  /// function's, and --functions generates them with it.
  std::vector<std::string> calls = {};
};

/// The sizes an Extent stands for in one model.
struct ModelSizes {
  int dof = 0;
  int standard_params = 0;
  int base_params = 0;
  int drive_params = 0;
  int drive_regressor_entries = 0;
};

/// Number of values of `extent` (kState: q, dq and ddq together, 3 dof).
int extent_size(Extent extent, const ModelSizes& sizes);

/// Number of values of `array`: rows times cols.
int array_size(const ArraySpec& array, const ModelSizes& sizes);

}  // namespace modelgen::gen
