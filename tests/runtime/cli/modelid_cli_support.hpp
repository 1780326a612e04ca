// Helpers of the modelid command-line tests: the CSV tables modelid writes. Running modelid,
// folders and files come from tests/support/cli_runner.hpp.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {

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
