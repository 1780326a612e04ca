// The modelid commands: each declares its options once, in a table (<command>_options.cpp,
// modelgen/model/option_table.hpp), and runs from the command line parsed by that table (one
// source folder per command). Each run returns the exit code and throws UsageError,
// modelgen::InputError, DataError, EstimationError or std::runtime_error for main to report.
#pragma once

#include "modelgen/model/option_table.hpp"
#include "runtime/cli/common/arguments.hpp"

namespace modelgen::internal {

/// The option tables of the commands.
const CommandSpec& fit_spec();
const CommandSpec& predict_spec();
const CommandSpec& simulate_spec();
const CommandSpec& validate_spec();
const CommandSpec& export_spec();
const CommandSpec& design_spec();
const CommandSpec& check_trajectory_spec();
const CommandSpec& check_spec();

/// modelid fit: base parameters from trajectories (fit/fit_command.cpp).
int run_fit(const CommandLine& args);
/// fit --method ml (fit/ml_fit_command.cpp); `prior_weight` is --physical's.
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

/// A command of modelid: its table and what runs it.
struct Command {
  const CommandSpec& (*spec)();
  int (*run)(const CommandLine& args);
};

/// Every command, in the order of the usage text.
const std::vector<Command>& modelid_commands();

/// The command named `name`, or nullptr.
const Command* find_command(const std::string& name);

/// modelid's usage: a line per command (from its table) and where to find the rest.
std::string modelid_usage();

/// The options every command takes (--robot's --angle-tolerance, --progress), for the tables.
std::vector<OptionSpec> common_options();

/// --robot, required: a description file or the name of a shipped model (`value` and `help`
/// say otherwise where a command needs a description file).
OptionSpec robot_option(std::string value = "ROBOT",
                        std::string help = "the description file or shipped model");

/// The table of modelid COMMAND: `options`, then those every command takes.
CommandSpec modelid_command(std::string name, std::string summary, std::vector<OptionSpec> options);

}  // namespace modelgen::internal
