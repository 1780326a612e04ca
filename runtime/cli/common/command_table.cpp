// The table of modelid's commands and the usage text derived from their option tables.

#include "runtime/cli/common/commands.hpp"

namespace modelgen::internal {

const std::vector<Command>& modelid_commands() {
  static const std::vector<Command> commands = {
      {fit_spec, run_fit},
      {predict_spec, run_predict},
      {simulate_spec, run_simulate},
      {validate_spec, run_validate},
      {export_spec, run_export},
      {design_spec, run_design},
      {check_trajectory_spec, run_check_trajectory},
      {check_spec, run_check},
  };
  return commands;
}

const Command* find_command(const std::string& name) {
  for (const Command& command : modelid_commands()) {
    if (command.spec().name == name) return &command;
  }
  return nullptr;
}

std::string modelid_usage() {
  std::string text = "usage:";
  for (const Command& command : modelid_commands()) {
    text += (text == "usage:" ? " " : "       ") + usage_line(command.spec()) + "\n";
  }
  text += "       modelid --version | --help\n\n";
  for (const Command& command : modelid_commands()) {
    const CommandSpec& spec = command.spec();
    const std::string head = "  " + spec.name;
    text += head + std::string(head.size() < 20 ? 20 - head.size() : 1, ' ') +
            wrapped(spec.summary, 20, 20) + "\n";
  }
  text +=
      "\n'modelid COMMAND --help' lists a command's options. ROBOT is a description (.yaml/.urdf,\n"
      "its model compiled and cached on first use; docs/compiled-models.md) or the name of a\n"
      "compiled-in generated model (tx40, kr150, ur5, iiwa14, panda, kuka_kr150_2, panda_arm,\n"
      "comau_smart_six). Exit codes: 0 success,\n"
      "1 bad input or data, 2 bad usage, 3 internal error. docs/commands/ has a page per\n"
      "command.\n";
  return text;
}

std::vector<OptionSpec> common_options() {
  OptionSpec tolerance{.name = "--angle-tolerance",
                       .type = ValueType::kNonNegative,
                       .value = "RAD",
                       .help =
                           "read a description as modelgen does: angles within RAD of a "
                           "multiple of pi/2 and axis components within RAD of 0 are taken "
                           "as exact, with a note; 0 takes every value as written",
                       .unit = "rad",
                       .default_value = "1e-4",
                       .group = "Every command"};
  OptionSpec name{.name = "--name",
                  .value = "NAME",
                  .help =
                      "the robot's name, for a description file whose own name is no C++ "
                      "identifier (made one, with a note, without --name)",
                  .default_value = "from the file",
                  .group = "Every command"};
  OptionSpec base{.name = "--base",
                  .value = "LINK",
                  .help = "URDF description: the link to use as the fixed base",
                  .default_value = "the URDF root",
                  .group = "Every command"};
  OptionSpec tip{.name = "--tip",
                 .value = "LINK",
                 .help = "URDF description: keep only the chain from the base to this link",
                 .group = "Every command"};
  OptionSpec mimic{.name = "--mimic-as-joint",
                   .type = ValueType::kFlag,
                   .help =
                       "URDF description: keep a <mimic> follower as an independent joint "
                       "(refused without: modelgen has no mimic constraint)",
                   .group = "Every command"};
  OptionSpec progress{.name = "--progress",
                      .type = ValueType::kFlag,
                      .help = "progress lines on stderr also when it is not a terminal (a log)",
                      .group = "Every command"};
  OptionSpec no_compile{.name = "--no-compile",
                        .type = ValueType::kFlag,
                        .help =
                            "evaluate a description file's model with the numeric reference "
                            "instead of generating, compiling and caching it "
                            "(docs/compiled-models.md)",
                        .group = "Every command"};
  return {tolerance, name, base, tip, mimic, no_compile, progress};
}

OptionSpec robot_option(std::string value, std::string help) {
  return {.name = "--robot", .value = std::move(value), .help = std::move(help), .required = true};
}

CommandSpec modelid_command(std::string name, std::string summary,
                            std::vector<OptionSpec> options) {
  CommandSpec spec{.program = "modelid", .name = std::move(name), .summary = std::move(summary)};
  spec.options = std::move(options);
  const std::vector<OptionSpec> common = common_options();
  spec.options.insert(spec.options.end(), common.begin(), common.end());
  return spec;
}

}  // namespace modelgen::internal
