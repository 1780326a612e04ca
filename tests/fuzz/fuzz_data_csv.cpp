// Measurement CSV files, read for a two- and a six-axis robot (the seeds have both), torques or
// currents optional.

#include <cstdint>

#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = modelgen::fuzz::input_file(data, size, "csv");
  for (int dof : {2, 6}) {
    modelgen::fuzz::expect_only_input_errors([&] {
      modelgen::io::read_trajectory_csv(path, dof, modelgen::io::EffortColumns::kOptional);
    });
  }
  return 0;
}
