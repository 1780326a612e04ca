// The parameter file of predict, simulate, export and fit --truth is opened once: inotify
// counts the openings of the file while each command runs. (They once opened and parsed it
// three to five times, once per check.)

#include <sys/inotify.h>
#include <unistd.h>

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

// How often the file at `path` is opened while `run` runs, by any process.
template <typename Run>
int openings_during(const fs::path& path, Run&& run) {
  const int watch = ::inotify_init1(IN_NONBLOCK);
  EXPECT_GE(watch, 0);
  // Closings are watched too: inotify merges an event with an identical one queued just before
  // it, so openings alone would count as one.
  EXPECT_GE(::inotify_add_watch(watch, path.c_str(), IN_OPEN | IN_CLOSE), 0) << path;
  run();
  int openings = 0;
  alignas(inotify_event) char buffer[4096];
  for (ssize_t n; (n = ::read(watch, buffer, sizeof buffer)) > 0;) {
    for (ssize_t at = 0; at < n;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
      openings += (event->mask & IN_OPEN) != 0;
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
    }
  }
  ::close(watch);
  return openings;
}

constexpr const char* kRobot = "tests/bad_inputs/robots/two_axes.yaml";

// Runs `modelid ARGUMENTS OPTION FILE` with `text` in FILE; `openings` how often FILE was opened.
CliRun with_file(const std::string& arguments, const std::string& option, const std::string& text,
                 int& openings) {
  const fs::path file = test_folder("read_once") / "params.json";
  write_text(file, text);
  CliRun run;
  openings = openings_during(file, [&] {
    run = modelid(arguments + " " + option + " " + quoted(file),
                  {.working_directory = source_path("")});
  });
  return run;
}

const std::string kParams =
    R"({"base": {"ZZ1R": 1.5, "ZZ2": 0.3, "MX2": 0.8, "Fv1": 2, "Fv2": 1}})";

TEST(ModelidParamsReadOnce, PredictSimulateAndFitTruth) {
  const fs::path out = test_folder("read_once_out");
  const std::string robot = std::string("--robot ") + kRobot;
  const std::string data = " --data tests/bad_inputs/robots/two_axes_data.csv";
  const std::string trajectory = " --trajectory tests/bad_inputs/robots/two_axes_trajectory.yaml";
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"predict " + robot + data + " --raw -o " + quoted(out / "p.csv"), "--params"},
      {"simulate " + robot + trajectory + " --noise 0 -o " + quoted(out / "s.csv"), "--params"},
      {"fit " + robot + data + " --method ols -o " + quoted(out / "e.json"), "--truth"},
  };
  for (const auto& [arguments, option] : commands) {
    int openings = 0;
    const CliRun run = with_file(arguments, option, kParams, openings);
    EXPECT_EQ(run.exit_code, 0) << arguments << "\n" << run.err;
    EXPECT_EQ(openings, 1) << arguments;
  }
}

TEST(ModelidParamsReadOnce, Export) {
  // A hand-written estimate of fit --physical: every standard parameter of two_axes.yaml (its
  // inertias reach beyond the regions guessed from the DH rows: --force).
  const std::string estimate = R"({"standard": {
    "XX1": 0.8, "XY1": 0, "XZ1": 0, "YY1": 0.8, "YZ1": 0, "ZZ1": 1.5,
    "MX1": 0, "MY1": 0, "MZ1": 0, "M1": 2, "Ia1": 0.5, "Fv1": 2, "Fc1": 0.5, "OFF1": 0,
    "XX2": 0.1, "XY2": 0, "XZ2": 0, "YY2": 0.35, "YZ2": 0, "ZZ2": 0.35,
    "MX2": 0.5, "MY2": 0, "MZ2": 0, "M2": 1, "Ia2": 0.1, "Fv2": 1, "Fc2": 0.3, "OFF2": 0}})";
  const fs::path out = test_folder("read_once_out");
  int openings = 0;
  const CliRun run = with_file(
      std::string("export --force --robot ") + kRobot + " -o " + quoted(out / "identified.yaml"),
      "--params", estimate, openings);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(openings, 1);
}

}  // namespace
}  // namespace modelgen::test
