// Controller YAML files (simulate, fit --method iv/didim --controller) for a two- and a six-axis
// robot: the reader must refuse with a positioned input error or return gains a PID can run
// with (a positive sample time, finite non-negative gains, kp > 0).

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "modelgen/io/experiment/controller_file.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = modelgen::fuzz::input_file(data, size, "yaml");
  for (int dof : {2, 6}) {
    modelgen::fuzz::expect_only_input_errors([&] {
      const modelgen::PidGains gains = modelgen::io::read_controller(path, dof);
      const bool usable = gains.sample_time > 0 && std::isfinite(gains.sample_time) &&
                          gains.kp.size() == dof && gains.ki.size() == dof &&
                          gains.kd.size() == dof && gains.kp.allFinite() && gains.ki.allFinite() &&
                          gains.kd.allFinite() && (gains.kp.array() > 0).all() &&
                          (gains.ki.array() >= 0).all() && (gains.kd.array() >= 0).all();
      // Not a modelgen::Error: the harness reports it as a finding.
      if (!usable) throw std::logic_error("read_controller accepted gains a PID cannot run");
    });
  }
  return 0;
}
