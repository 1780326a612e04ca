// modelgen command line: parses arguments, runs one command, prints diagnostics, sets the exit
// code (0 success, 1 bad input, 2 bad usage, 3 internal error).

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "generator/describe.hpp"
#include "generator/emit/function_emitter.hpp"
#include "generator/dynamics/base_report.hpp"
#include "generator/generate.hpp"
#include "generator/version.hpp"
#include "modelgen/model/command_line.hpp"
#include "modelgen/model/load_robot.hpp"

namespace {

constexpr const char* kUsage =
    "usage: modelgen ROBOT -o DIR [--scalar double|float|both] [--base LINK] [--tip LINK]\n"
    "                [--name NAME] [--angle-tolerance RAD] [--params EST.json]\n"
    "                [--functions NAME,NAME,...]\n"
    "       modelgen describe ROBOT [--base LINK] [--tip LINK] [--name NAME] [--angle-tolerance RAD]\n"
    "       modelgen base ROBOT [--base LINK] [--tip LINK] [--name NAME] [--angle-tolerance RAD]\n"
    "       modelgen --list-functions | --version | --help\n"
    "\n"
    "ROBOT is a modified-DH description (.yaml) or a URDF (.urdf).\n"
    "  -o DIR        generate into DIR (STEM: ROBOT's file name without extension) STEM.hpp,\n"
    "                STEM.cpp (tables), STEM_<function>.cpp for each function and the\n"
    "                manifest STEM.json; all are replaced together or not at all, and function\n"
    "                files of an earlier run that this one does not make are removed\n"
    "  --functions LIST\n"
    "                generate only these entry points (comma-separated, e.g.\n"
    "                inverse_dynamics,idim_regressor) and those they call; default all\n"
    "  --scalar T    entry points for double, float or both (default both)\n"
    "  --params EST.json\n"
    "                an estimate of 'modelid fit -o': its base parameters become the constants\n"
    "                kIdentifiedBase and inverse_dynamics_identified(q, dq, ddq, tau) uses them\n"
    "                (firmware values); it must have been made on ROBOT (description_sha256)\n"
    "  --list-functions\n"
    "                print every entry point, with ':' and those it calls\n"
    "  describe      print the parsed model: joints, drive chain, standard parameters\n"
    "  base          print the base parameters and their regrouping relations\n"
    "  --base LINK   URDF: link to use as the fixed base (default: the URDF root)\n"
    "  --tip LINK    URDF: keep only the chain from the base to this link\n"
    "  --name NAME   robot name (C++ namespace of generated code; default: from the file)\n"
    "  --angle-tolerance RAD\n"
    "                angles within RAD of a multiple of pi/2 (URDF rpy, MDH alpha and theta)\n"
    "                and axis components within RAD of 0 are taken as exact, with a note\n"
    "                (default 1e-4; 0 takes every value as written)\n";

struct Arguments {
  std::string command;  // "describe", "base" or "generate"
  std::string robot;
  std::string output_dir;
  std::string scalar = "both";
  std::string params;  // --params EST.json; empty without it
  std::vector<std::string> functions;  // --functions; empty for all
  modelgen::LoadOptions load;
};

Arguments parse(int argc, char** argv) {
  using modelgen::OptionKind;
  using modelgen::UsageError;
  const modelgen::CommandLine line = modelgen::parse_command_line(
      argc, argv, 1, "",
      {{"--base", OptionKind::kOnce}, {"--tip", OptionKind::kOnce}, {"--name", OptionKind::kOnce},
       {"--scalar", OptionKind::kOnce}, {"-o", OptionKind::kOnce}, {"--output", OptionKind::kOnce},
       {"--angle-tolerance", OptionKind::kOnce}, {"--params", OptionKind::kOnce},
       {"--functions", OptionKind::kOnce}});
  Arguments args;
  args.load.base_link = line.one_or("--base", "");
  args.load.tip_link = line.one_or("--tip", "");
  args.load.name = line.one_or("--name", "");
  args.load.angle_tolerance = modelgen::angle_tolerance_option(line);
  args.scalar = line.one_or("--scalar", "both");
  if (args.scalar != "double" && args.scalar != "float" && args.scalar != "both") {
    throw UsageError("--scalar must be double, float or both, not '" + args.scalar + "'");
  }
  if (line.has("-o") && line.has("--output")) throw UsageError("-o and --output given together");
  args.output_dir = line.one_or("-o", line.one_or("--output", ""));
  args.params = line.one_or("--params", "");
  if (line.has("--params") && args.params.empty()) throw UsageError("--params needs a file");
  if (line.has("--functions")) {
    const std::string list = line.one("--functions");
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = list.find(',', start);
      const std::string name = list.substr(start, comma == std::string::npos ? comma : comma - start);
      if (name.empty()) throw UsageError("--functions: empty name in '" + list + "'");
      args.functions.push_back(name);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }

  const std::vector<std::string>& positional = line.positional;
  if (positional.empty()) throw UsageError("no robot description given");
  if (positional[0] == "describe" || positional[0] == "base") {
    args.command = positional[0];
    if (positional.size() != 2) throw UsageError(args.command + " takes exactly one ROBOT file");
    if (!args.output_dir.empty()) throw UsageError(args.command + " writes no files; drop -o");
    for (const char* option : {"--params", "--functions"}) {
      if (line.has(option)) {
        throw UsageError(args.command + " takes no " + option +
                         "; it belongs to generation (-o DIR)");
      }
    }
    args.robot = positional[1];
    return args;
  }
  if (positional.size() != 1) throw UsageError("give exactly one ROBOT file");
  if (args.output_dir.empty()) throw UsageError("no output directory: add -o DIR");
  args.command = "generate";
  args.robot = positional[0];
  return args;
}

// What the loader snapped or assumed, on stderr so that standard output stays the result.
void print_notes(const std::vector<modelgen::DescriptionNote>& notes) {
  for (const modelgen::DescriptionNote& note : notes) std::cerr << note.to_string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::cout << kUsage;
    return 0;
  }
  if (argc == 2 && std::strcmp(argv[1], "--list-functions") == 0) {
    std::cout << modelgen::gen::entry_point_list();
    return 0;
  }
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
    std::cout << "modelgen " << modelgen::gen::kVersion << "\n";
    return 0;
  }
  try {
    const Arguments args = parse(argc, argv);
    if (args.command == "describe") {
      const modelgen::RobotModel model = modelgen::load_robot(args.robot, args.load);
      print_notes(model.notes);
      std::cout << modelgen::gen::describe(model);
    } else if (args.command == "base") {
      const modelgen::RobotModel model = modelgen::load_robot(args.robot, args.load);
      print_notes(model.notes);
      const auto closed = modelgen::gen::derive_closed_form_relations(model);
      std::cout << modelgen::gen::describe_base_parameters(
          model, modelgen::derive_base_parameters(model.tree), closed ? &*closed : nullptr);
    } else {
      const modelgen::gen::GeneratedModel generated =
          modelgen::gen::generate_from_file(args.robot, args.load, args.scalar, args.params,
                                            args.functions);
      print_notes(generated.notes);
      for (const std::string& added : generated.added_callees) {
        std::cerr << "modelgen: note: --functions: " << added << ", which is generated too\n";
      }
      for (const std::string& warning : generated.warnings) std::cerr << warning << "\n";
      generated.files.write_to(args.output_dir);
    }
    return 0;
  } catch (const modelgen::UsageError& e) {
    std::cerr << "modelgen: " << e.what() << "\n\n" << kUsage;
    return 2;
  } catch (const modelgen::InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "modelgen: internal error: " << e.what()
              << "\nThis is a bug in modelgen; please report it with the input file.\n";
    return 3;
  }
}
