// The methods of modelid fit, one entry each (fit_methods.cpp): the --method value, the name
// printed and written into EST.json, what it is, what it checks before the data are read and
// its estimator. Which options a method takes is said by the options' entries in fit's table
// (fit_options.cpp). Adding a method is an entry here and its estimator.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "modelgen/estimation/identify.hpp"
#include "modelgen/model/identification_model.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// What an estimator of fit works from.
struct FitContext {
  const CommandLine& args;
  const IdentificationModel& model;
  const Experiments& experiments;  ///< the --data files prepared (and as read, if asked)
  const IdentifyOptions& options;  ///< decimation, --min-speed, --essential, progress
  std::ostream& report;            ///< printed after fit's heading
  std::ostream& log;               ///< warnings and progress lines (standard error)
};

/// How fit runs a method: on the base parameters (the estimate, its statistics, --physical,
/// --essential, plots and EST.json are fit's), or the ML route of the nonlinear drive model
/// with its own report (ml_fit_command.cpp).
enum class FitRoute { kBaseParameters, kDriveModel };

struct FitMethod {
  std::string name;     ///< --method value ("wls")
  std::string label;    ///< printed and written ("IDIM-WLS")
  std::string summary;  ///< for --help
  FitRoute route = FitRoute::kBaseParameters;
  /// The records as read are kept for the estimator (Experiments::raw): the closed-loop
  /// methods need the reference qr and the first samples.
  bool keeps_records = false;
  /// Checks before the data are read (UsageError); null for none.
  void (*check)(const CommandLine& args) = nullptr;
  /// The estimate (kBaseParameters); null for the drive-model route.
  Identification (*estimate)(const FitContext& context) = nullptr;
};

/// Every method, in the order --help lists them.
const std::vector<FitMethod>& fit_methods();

/// The entry of a method the command line accepted.
const FitMethod& fit_method(const std::string& name);

}  // namespace modelgen::internal
