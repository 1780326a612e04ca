// modelid command line: identification on measured data. For now it lists the commands the
// runtime will provide and checks a description loads into the numeric reference.

#include <cstring>
#include <iostream>
#include <string>

#include "generator/description/load_robot.hpp"
#include "modelgen/reference_dynamics.hpp"

namespace {

constexpr const char* kUsage =
    "usage: modelid check ROBOT     load a description into the numeric reference dynamics\n"
    "       modelid --help\n"
    "\n"
    "Fitting (fit), prediction (predict), simulation (simulate) and excitation design\n"
    "come with the identification runtime.\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::cout << kUsage;
    return 0;
  }
  if (argc == 3 && std::strcmp(argv[1], "check") == 0) {
    try {
      const auto model = modelgen::gen::load_robot(argv[2]);
      const modelgen::ReferenceDynamics dynamics(model.tree);
      std::cout << model.name << ": " << dynamics.dof() << " dof, " << dynamics.num_params()
                << " standard parameters\n";
      return 0;
    } catch (const modelgen::gen::InputError& e) {
      std::cerr << e.what() << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "modelid: internal error: " << e.what() << "\n";
      return 3;
    }
  }
  std::cerr << kUsage;
  return 2;
}
