// modelgen's option tables and the parsed command line (generator/cli_options.hpp).

#include "generator/cli_options.hpp"

#include <cstring>

namespace modelgen::gen {

namespace {

constexpr const char* kSelection = "Part of a URDF tree and naming";

// The options that read the description: every command takes them.
std::vector<OptionSpec> description_options() {
  return {
      {.name = "--base",
       .value = "LINK",
       .help = "URDF: the link to use as the fixed base",
       .default_value = "the URDF root",
       .group = kSelection},
      {.name = "--tip",
       .value = "LINK",
       .help = "URDF: keep only the chain from the base to "
               "this link",
       .group = kSelection},
      {.name = "--mimic-as-joint",
       .type = ValueType::kFlag,
       .help = "URDF: keep a <mimic> follower as an independent joint (refused without: modelgen "
               "has no mimic constraint)",
       .group = kSelection},
      {.name = "--name",
       .value = "NAME",
       .help = "the robot name (the C++ namespace of generated code)",
       .default_value = "from the file",
       .group = kSelection},
      {.name = "--angle-tolerance",
       .type = ValueType::kNonNegative,
       .value = "RAD",
       .help = "angles within RAD of a multiple of pi/2 (URDF rpy, MDH alpha and theta) and axis "
               "components within RAD of 0 are taken as exact, with a note; 0 takes every value "
               "as written (below 0.7)",
       .unit = "rad",
       .default_value = "1e-4",
       .group = kSelection},
  };
}

CommandSpec make_generate_spec() {
  CommandSpec spec{.program = "modelgen",
                   .summary =
                       "generate the C++ model of ROBOT (.yaml modified DH or .urdf) into "
                       "DIR: STEM.hpp, STEM.cpp (tables), STEM_<function>.cpp per function "
                       "and the manifest STEM.json, all replaced together or not at all",
                   .operands = "ROBOT"};
  spec.options = {
      {.name = "-o",
       .value = "DIR",
       .help = "the output folder (function files of an earlier "
               "run that this one does not make are removed)"},
      {.name = "--output", .value = "DIR", .help = "the same as -o"},
      {.name = "--scalar",
       .type = ValueType::kChoice,
       .help = "entry points for double, float "
               "or both",
       .default_value = "both",
       .choices = {"double", "float", "both"}},
      {.name = "--functions",
       .value = "NAME,...",
       .help = "generate only these entry points (modelgen --list-functions) and those they call",
       .default_value = "all"},
      {.name = "--params",
       .value = "EST.json",
       .help = "an estimate of 'modelid fit -o' made on ROBOT: its base parameters become "
               "kIdentifiedBase and inverse_dynamics_identified uses them (firmware values)"},
      {.name = "--loadable",
       .type = ValueType::kFlag,
       .help = "also write STEM_loadable.cpp, the C entry point of the model compiled as a "
               "shared library, for the runtime to load at run time (needs every function, in "
               "double)"},
  };
  const std::vector<OptionSpec> shared = description_options();
  spec.options.insert(spec.options.end(), shared.begin(), shared.end());
  spec.exclusive = {
      {"-o", "--output", "they name the same folder"},
      {"--loadable", "--functions", "a loadable model needs every function the runtime calls"}};
  return spec;
}

CommandSpec make_inspect_spec(const char* name, const char* summary) {
  CommandSpec spec{.program = "modelgen", .name = name, .summary = summary, .operands = "ROBOT"};
  spec.options = description_options();
  for (const char* option :
       {"-o", "--output", "--scalar", "--functions", "--params", "--loadable"}) {
    spec.elsewhere.emplace_back(option, "generation (-o DIR)");
  }
  return spec;
}

}  // namespace

const CommandSpec& generate_spec() {
  static const CommandSpec spec = make_generate_spec();
  return spec;
}

const CommandSpec& describe_spec() {
  static const CommandSpec spec = make_inspect_spec(
      "describe", "print the parsed model: joints, drive chain, standard parameters");
  return spec;
}

const CommandSpec& base_spec() {
  static const CommandSpec spec =
      make_inspect_spec("base", "print the base parameters and their regrouping relations");
  return spec;
}

std::string modelgen_usage() {
  std::string text = "usage: " + usage_line(generate_spec()) + "\n";
  for (const CommandSpec* spec : {&describe_spec(), &base_spec()}) {
    text += "       " + usage_line(*spec) + "\n";
  }
  text +=
      "       modelgen --list-functions | --version | --help\n\n"
      "'modelgen --help', 'modelgen describe --help' and 'modelgen base --help' list the options;\n"
      "docs/commands/modelgen.md has the details. Exit codes: 0 success, 1 bad input (the\n"
      "message names file, line and column), 2 bad usage, 3 internal error.\n";
  return text;
}

const CommandSpec& spec_for(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "describe") == 0) return describe_spec();
  if (argc >= 2 && std::strcmp(argv[1], "base") == 0) return base_spec();
  return generate_spec();
}

Arguments parse_arguments(int argc, char** argv) {
  const CommandSpec& spec = spec_for(argc, argv);
  const int first = spec.name.empty() ? 1 : 2;
  const CommandLine line = parse_command(spec, argc, argv, first);
  Arguments args;
  args.command = spec.name.empty() ? "generate" : spec.name;
  args.load.base_link = line.one_or("--base", "");
  args.load.tip_link = line.one_or("--tip", "");
  args.load.name = line.one_or("--name", "");
  args.load.mimic_as_joint = line.has("--mimic-as-joint");
  args.load.angle_tolerance = angle_tolerance_option(line);
  args.generation.scalar = line.one_or("--scalar", "both");
  args.output_dir = line.one_or("-o", line.one_or("--output", ""));
  args.generation.params_path = line.one_or("--params", "");
  if (line.has("--params") && args.generation.params_path.empty()) {
    throw UsageError("--params needs a file");
  }
  if (line.has("--functions")) {
    args.generation.functions = comma_items(line.one("--functions"), "--functions");
  }
  args.generation.loadable = line.has("--loadable");
  if (args.generation.loadable && args.generation.scalar == "float") {
    throw UsageError("--loadable needs the double entry points: use --scalar double or both");
  }
  if (line.positional.empty()) throw UsageError("no robot description given");
  if (line.positional.size() != 1) {
    throw UsageError(spec.name.empty() ? "give exactly one ROBOT file"
                                       : spec.name + " takes exactly one ROBOT file");
  }
  if (spec.name.empty() && args.output_dir.empty()) {
    throw UsageError("no output directory: add -o DIR");
  }
  args.robot = line.positional.front();
  return args;
}

}  // namespace modelgen::gen
