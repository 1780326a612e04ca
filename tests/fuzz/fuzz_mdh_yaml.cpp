// MDH YAML descriptions: load_robot, then the numeric reference model (base parameters) for
// the descriptions it accepts.

#include <cstdint>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = modelgen::fuzz::input_file(data, size, "yaml");
  modelgen::fuzz::expect_only_input_errors([&] {
    const modelgen::RobotModel robot = modelgen::load_robot(path);
    const modelgen::ReferenceModel model(robot.name, robot.tree, "", robot.drives);
  });
  return 0;
}
