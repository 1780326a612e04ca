// modelgen's commands (generate, describe, base), their options declared once in tables
// (modelgen/model/option_table.hpp), and the parsed command line main runs.
#pragma once

#include <string>
#include <vector>

#include "generator/generate.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/option_table.hpp"

namespace modelgen::gen {

struct Arguments {
  std::string command;  ///< "describe", "base" or "generate"
  std::string robot;
  std::string output_dir;
  GenerationOptions generation;  ///< --scalar, --params, --functions, --loadable
  LoadOptions load;
};

/// The table of `modelgen ROBOT -o DIR`, `modelgen describe ROBOT` and `modelgen base ROBOT`.
const CommandSpec& generate_spec();
const CommandSpec& describe_spec();
const CommandSpec& base_spec();

/// modelgen's usage: a line per command, derived from the tables.
std::string modelgen_usage();

/// The table argv[1..argc) is read by: describe's or base's when argv[1] names them, else
/// generation's.
const CommandSpec& spec_for(int argc, char** argv);

/// argv[1..argc) parsed and checked by its table; UsageError for a bad command line.
Arguments parse_arguments(int argc, char** argv);

}  // namespace modelgen::gen
