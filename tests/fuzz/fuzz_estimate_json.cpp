// Estimate files (EST.json of modelid fit) as modelgen --params reads them for the firmware
// constants, against the two-axis robot the bad estimates of tests/bad_inputs/estimate/ are
// written for: the reader, the values by base parameter, the float range check.

#include <cstdint>

#include "generator/estimate/estimate_file.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

constexpr const char* kRobot = MODELGEN_SOURCE_DIR "/tests/bad_inputs/robots/two_axes.yaml";

struct TwoAxes {
  std::string sha256;
  std::vector<std::string> base_names;
  std::string name;
};

const TwoAxes& two_axes() {
  static const TwoAxes robot = [] {
    const modelgen::RobotModel model = modelgen::load_robot(kRobot);
    std::vector<std::string> names;
    for (const modelgen::BaseParameter& p : modelgen::derive_base_parameters(model.tree).params) {
      names.push_back(p.name);
    }
    return TwoAxes{modelgen::sha256_hex(modelgen::read_source_file(kRobot)), names, model.name};
  }();
  return robot;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const TwoAxes& robot = two_axes();
  const std::string path = modelgen::fuzz::input_file(data, size, "json");
  modelgen::fuzz::expect_only_input_errors([&] {
    const modelgen::gen::EstimateFile estimate =
        modelgen::gen::read_estimate_file(path, kRobot, robot.sha256);
    modelgen::gen::base_values(estimate, robot.base_names, robot.name);
    modelgen::gen::check_fits_float(estimate);
  });
  return 0;
}
