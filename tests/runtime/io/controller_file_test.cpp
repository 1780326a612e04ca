// The controller file's warning on a sample time of 0.1 s or more (no joint controller runs
// that slowly; 1 written for 1 ms is the likely slip): accepted, with the file, line and column.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/io/experiment/controller_file.hpp"
#include "tests/support/cli_runner.hpp"

namespace modelgen::test {
namespace {

std::string controller(const std::string& sample_time) {
  return "type: pid\nsample_time: " + sample_time + "\nkp: [100, 100]\nki: [0, 0]\nkd: [1, 1]\n";
}

TEST(ControllerFile, SlowSampleTimeIsAcceptedWithAWarning) {
  const std::filesystem::path path = test_folder("controller") / "controller.yaml";
  write_text(path, controller("1"));
  std::vector<std::string> warnings;
  const PidGains gains = io::read_controller(path.string(), 2, &warnings);
  EXPECT_EQ(gains.sample_time, 1);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], path.string() +
                             ":2:14: warning: 'sample_time' is 1 s, a controller running at 1 Hz; "
                             "sample_time is in seconds: milliseconds? (0.001 for 1 kHz)");
  // Without the out-parameter the gains are read as before.
  EXPECT_EQ(io::read_controller(path.string(), 2).sample_time, 1);
}

TEST(ControllerFile, UsualSampleTimesGiveNoWarning) {
  const std::filesystem::path path = test_folder("controller") / "controller.yaml";
  for (const char* ts : {"0.001", "0.004", "0.0999"}) {
    write_text(path, controller(ts));
    std::vector<std::string> warnings;
    io::read_controller(path.string(), 2, &warnings);
    EXPECT_TRUE(warnings.empty()) << ts;
  }
  write_text(path, controller("0.1"));
  std::vector<std::string> warnings;
  io::read_controller(path.string(), 2, &warnings);
  EXPECT_EQ(warnings.size(), 1u);
}

}  // namespace
}  // namespace modelgen::test
