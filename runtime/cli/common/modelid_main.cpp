// modelid command line: finds the command in the command table, parses its options by the
// command's option table (or prints its --help) and turns errors into messages and exit codes: 0
// success, 1 bad input or
// data, 2 bad usage, 3 internal error.

#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "modelgen/data/data_error.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/error.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/common/version.hpp"

namespace {

using namespace modelgen;
using namespace modelgen::internal;

int dispatch(int argc, char** argv) {
  const std::string name = argv[1];
  const Command* command = find_command(name);
  if (command == nullptr) {
    std::vector<std::string> names;
    for (const Command& known : modelid_commands()) names.push_back(known.spec().name);
    throw UsageError{"unknown command '" + name + "'" + did_you_mean(name, names)};
  }
  const CommandSpec& spec = command->spec();
  if (asks_for_help(argc, argv, 2)) {
    std::cout << command_help(spec);
    return 0;
  }
  const CommandLine args = parse_command(spec, argc, argv, 2);
  if (args.has("--progress")) show_progress_in_logs(true);
  return command->run(args);
}

// The usage after a usage error: the command's own when the command is known.
std::string usage_after_error(int argc, char** argv) {
  const Command* command = argc >= 2 ? find_command(argv[1]) : nullptr;
  if (command == nullptr) return modelid_usage();
  return "usage: " + usage_line(command->spec()) + "\n('modelid " + command->spec().name +
         " --help' lists its options)\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    (argc < 2 ? std::cerr : std::cout) << modelid_usage();
    return argc < 2 ? 2 : 0;
  }
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
    std::cout << "modelid " << kModelidVersion << "\n";
    return 0;
  }
  try {
    return dispatch(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "modelid: " << e.what() << "\n\n" << usage_after_error(argc, argv);
    return 2;
  } catch (const modelgen::InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const DataError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const EstimationError& e) {
    std::cerr << "modelid: cannot identify: " << e.what() << "\n";
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "modelid: " << e.what() << "\n";
    return 1;
  } catch (const std::runtime_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "modelid: internal error: " << e.what() << "; please report this\n";
    return 3;
  }
}
