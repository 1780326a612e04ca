// Parameter and estimate JSON files (simulate --params, predict --params, fit --truth) and
// drive-model parameter files (simulate --drive, fit --method ml --known/--truth), read for
// the two-axis robot of tests/bad_inputs/robots/.

#include <cstdint>
#include <memory>

#include "modelgen/io/drive_parameter_file.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

const modelgen::IdentificationModel& two_axes() {
  static const modelgen::RobotModel robot =
      modelgen::load_robot(MODELGEN_SOURCE_DIR "/tests/bad_inputs/robots/two_axes.yaml");
  static const modelgen::ReferenceModel model(robot.name, robot.tree, "0", robot.drives);
  return model;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const modelgen::IdentificationModel& model = two_axes();
  const std::string path = modelgen::fuzz::input_file(data, size, "json");
  modelgen::fuzz::expect_only_input_errors([&] {
    modelgen::io::check_estimate_model(path, model);
    modelgen::io::read_base_parameters(path, model);
  });
  modelgen::fuzz::expect_only_input_errors([&] {
    modelgen::io::read_drive_parameter_values(path, {"M1", "ZZ1", "Rv1", "load_m"});
  });
  return 0;
}
