// Helpers of the modelid command-line tests: run the built binary as a user would (std::system,
// stdout and stderr captured), a fresh folder per test, small files, CSV tables.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace modelgen::test {

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A folder of its own for the running test, emptied first: TempDir()/modelid_<suite>_<test>.
inline std::filesystem::path test_folder() {
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) /
      (std::string("modelid_") + info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs build/bin/modelid with `arguments` (already shell-quoted where needed).
inline CliRun modelid(const std::string& arguments) {
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir());
  const std::string stem = std::string(info->test_suite_name()) + "_" + info->name();
  const std::filesystem::path out = dir / ("modelid_out_" + stem),
                              err = dir / ("modelid_err_" + stem);
  const std::string command = "'" + std::string(MODELGEN_BINARY_DIR) + "/bin/modelid' " +
                              arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
}

/// A path in single quotes for the shell.
inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

/// A file of the source tree, quoted.
inline std::string quoted_source(const std::string& relative) {
  return "'" + source_path(relative) + "'";
}

/// A CSV file as a header and numeric rows; fails the test on a malformed row.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;

  int column(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (header[c] == name) return static_cast<int>(c);
    }
    ADD_FAILURE() << "no column '" << name << "'";
    return 0;
  }
  double at(std::size_t row, const std::string& name) const { return rows[row][column(name)]; }
};

inline CsvTable read_csv(const std::filesystem::path& path) {
  CsvTable table;
  std::istringstream in(read_text(path));
  std::string line;
  auto split = [](const std::string& text) {
    std::vector<std::string> fields;
    std::istringstream fields_in(text);
    for (std::string field; std::getline(fields_in, field, ',');) fields.push_back(field);
    return fields;
  };
  if (!std::getline(in, line)) return table;
  table.header = split(line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    for (const std::string& field : split(line)) row.push_back(std::stod(field));
    EXPECT_EQ(row.size(), table.header.size()) << path << ": " << line;
    table.rows.push_back(std::move(row));
  }
  return table;
}

/// The header a CSV with `prefixes` per axis should have: experiment, t, then prefix1..prefixN
/// for each prefix.
inline std::vector<std::string> expected_header(const std::vector<std::string>& prefixes, int dof) {
  std::vector<std::string> header = {"experiment", "t"};
  for (const std::string& prefix : prefixes) {
    for (int j = 1; j <= dof; ++j) header.push_back(prefix + std::to_string(j));
  }
  return header;
}

}  // namespace modelgen::test
