// modelgen command line: parses arguments, runs one command, prints diagnostics, sets the exit
// code (0 success, 1 bad input, 2 bad usage, 3 internal error).

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "generator/cli_options.hpp"
#include "generator/describe.hpp"
#include "generator/dynamics/base_report.hpp"
#include "generator/functions/entry_points.hpp"
#include "generator/generate.hpp"
#include "generator/output/file_set.hpp"
#include "generator/version.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/option_table.hpp"

namespace {

// What the loader snapped or assumed, on stderr so that standard output stays the result.
void print_notes(const std::vector<modelgen::DescriptionNote>& notes) {
  for (const modelgen::DescriptionNote& note : notes) std::cerr << note.to_string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  using modelgen::gen::modelgen_usage;
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::cout << modelgen_usage() << "\n" << modelgen::command_help(modelgen::gen::generate_spec());
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
  if (modelgen::asks_for_help(argc, argv, 1)) {
    std::cout << modelgen::command_help(modelgen::gen::spec_for(argc, argv));
    return 0;
  }
  try {
    const modelgen::gen::Arguments args = modelgen::gen::parse_arguments(argc, argv);
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
      // A run killed while writing this folder left it mixed: repaired before anything else,
      // so that a run that fails below (a bad description) does it too.
      modelgen::gen::recover_output_directory(args.output_dir);
      const modelgen::gen::GeneratedModel generated =
          modelgen::gen::generate_from_file(args.robot, args.load, args.generation);
      print_notes(generated.notes);
      for (const std::string& added : generated.added_callees) {
        std::cerr << "modelgen: note: --functions: " << added << ", which is generated too\n";
      }
      for (const std::string& warning : generated.warnings) std::cerr << warning << "\n";
      generated.files.write_to(args.output_dir);
    }
    return 0;
  } catch (const modelgen::UsageError& e) {
    std::cerr << "modelgen: " << e.what() << "\n\n" << modelgen_usage();
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
