// generated/ must be byte-identical to a fresh generation of every shipped robot (run in-process
// here), contain nothing else, and generation must be deterministic: twice in one process and
// once through the modelgen executable give the same bytes. This proves the checked-in code was
// regenerated and reviewed, not that it is correct (numeric_diff_test does that).

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "generator/generate.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRefresh = "cmake --build build --target regenerate";

struct ShippedRobot {
  std::string description;  // relative to the source tree
  std::string stem;
};

std::vector<ShippedRobot> shipped_robots() {
  std::vector<ShippedRobot> robots;
  std::stringstream list(MODELGEN_SHIPPED_ROBOTS);
  std::string entry;
  while (std::getline(list, entry, ',')) {
    const std::string description = entry.substr(0, entry.find('|'));
    robots.push_back({description, fs::path(description).stem().string()});
  }
  return robots;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// "" when equal, else where and how the two texts first differ.
std::string first_difference(const std::string& expected, const std::string& actual) {
  if (expected == actual) return "";
  std::istringstream a(expected), b(actual);
  std::string line_a, line_b;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(a, line_a));
    const bool more_b = static_cast<bool>(std::getline(b, line_b));
    if (!more_a && !more_b) return "files differ only in their final newline";
    if (!more_a || !more_b || line_a != line_b) {
      return "first difference at line " + std::to_string(line) + "\n  checked in: " +
             (more_a ? line_a : "<end of file>") + "\n  generated:  " +
             (more_b ? line_b : "<end of file>");
    }
  }
}

TEST(GeneratedUpToDate, CheckedInFilesEqualFreshGeneration) {
  for (const ShippedRobot& robot : shipped_robots()) {
    const GeneratedModel fresh = generate_from_file(test::source_path(robot.description), {});
    for (const OutputFile& file : fresh.files.files()) {
      const fs::path checked_in = fs::path(test::source_path("generated")) / robot.stem / file.name;
      ASSERT_TRUE(fs::exists(checked_in))
          << checked_in << " is missing; refresh generated/ with: " << kRefresh;
      const std::string difference = first_difference(read(checked_in), file.content);
      EXPECT_EQ(difference, "") << checked_in << " is out of date: " << difference
                                << "\nRefresh generated/ with: " << kRefresh;
    }
  }
}

TEST(GeneratedUpToDate, NoFileThatNoRobotProduces) {
  std::set<fs::path> expected = {fs::path(test::source_path("generated/.clang-format"))};
  for (const ShippedRobot& robot : shipped_robots()) {
    const GeneratedModel fresh = generate_from_file(test::source_path(robot.description), {});
    for (const OutputFile& file : fresh.files.files()) {
      expected.insert(fs::path(test::source_path("generated")) / robot.stem / file.name);
    }
  }
  for (const auto& entry : fs::recursive_directory_iterator(test::source_path("generated"))) {
    if (entry.is_directory()) continue;
    EXPECT_TRUE(expected.count(entry.path()))
        << entry.path() << " is produced by no shipped robot; remove it or add its robot to "
        << "MODELGEN_SHIPPED_ROBOTS in CMakeLists.txt";
  }
}

TEST(GeneratedUpToDate, GenerationIsDeterministic) {
  const std::string description = test::source_path("robots/kr150.yaml");
  const GeneratedModel first = generate_from_file(description, {});
  const GeneratedModel second = generate_from_file(description, {});
  const fs::path directory = fs::path(testing::TempDir()) / "modelgen_determinism";
  fs::remove_all(directory);
  const test::CliRun run =
      test::modelgen(test::quoted(description) + " -o " + test::quoted(directory));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Header, tables, manifest and a file for each of the 24 entry points of a model without
  // --params.
  ASSERT_EQ(first.files.files().size(), 27u);
  for (std::size_t i = 0; i < first.files.files().size(); ++i) {
    const OutputFile& file = first.files.files()[i];
    EXPECT_EQ(file.content, second.files.files()[i].content) << file.name;
    EXPECT_EQ(first_difference(file.content, read(directory / file.name)), "") << file.name;
  }
}

}  // namespace
}  // namespace modelgen::gen
