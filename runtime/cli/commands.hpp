// The modelid commands, one source file each; main dispatches to them. Each returns the exit
// code and throws UsageError, modelgen::InputError, DataError, EstimationError or
// std::runtime_error for main to report.
#pragma once

#include "runtime/cli/arguments.hpp"

namespace modelgen::internal {

/// The options each command accepts, for parse_arguments.
extern const std::map<std::string, OptionKind> kFitOptions, kPredictOptions, kSimulateOptions,
    kExportOptions, kCheckTrajectoryOptions, kDesignOptions, kValidateOptions;

/// modelid fit: base parameters from trajectories (fit_command.cpp).
int run_fit(const CommandLine& args);
/// fit --method ml (ml_fit_command.cpp); `prior_weight` is --physical's.
int run_fit_ml(const CommandLine& args, double prior_weight);
/// modelid predict: torques of an estimate on trajectories and their errors.
int run_predict(const CommandLine& args);
/// modelid simulate: synthetic data from a Fourier excitation and true parameters.
int run_simulate(const CommandLine& args);
/// modelid export: the identified values of an estimate written into the description.
int run_export(const CommandLine& args);
/// modelid check-trajectory: the use of every joint limit by a Fourier excitation.
int run_check_trajectory(const CommandLine& args);
/// modelid design: an optimal Fourier excitation within the joint limits.
int run_design(const CommandLine& args);
/// modelid validate: an estimate simulated under the controller along a closed-loop record.
int run_validate(const CommandLine& args);
/// modelid check ROBOT: loads a model and prints its sizes.
int run_check(const CommandLine& args);

}  // namespace modelgen::internal
