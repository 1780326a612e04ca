// Fourier trajectory YAML files (simulate --trajectory) for a two- and a six-axis robot (the
// seeds have both), then one period sampled at 100 points, as simulate does with what the
// reader accepts.

#include <cstdint>

#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/io/experiment/fourier_file.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = modelgen::fuzz::input_file(data, size, "yaml");
  for (int dof : {2, 6}) {
    modelgen::fuzz::expect_only_input_errors([&] {
      const modelgen::FourierTrajectory f = modelgen::io::read_fourier(path, dof);
      modelgen::sample(f, f.period / 100, f.period);
    });
  }
  return 0;
}
