// Implementation of the shared test helpers.

#include "tests/support/test_support.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <numbers>

namespace modelgen::test {

std::string source_path(std::string_view relative) {
  return std::string(MODELGEN_SOURCE_DIR) + "/" + std::string(relative);
}

std::string shared_path(std::string_view relative) {
  return std::string(MODELGEN_SHARED_DIR) + "/" + std::string(relative);
}

std::vector<std::string> shipped_robots() {
  std::vector<std::string> files;
  namespace fs = std::filesystem;
  for (const auto& entry : fs::directory_iterator(source_path("robots"))) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  for (const auto& entry : fs::directory_iterator(source_path("robots/urdf"))) {
    if (entry.path().extension() == ".urdf") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

double Random::uniform(double lo, double hi) {
  // Not std::uniform_real_distribution: its output is implementation-defined.
  const double unit = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * unit;
}

double Random::normal() {
  const double u = uniform(1e-300, 1.0), v = uniform(0.0, 1.0);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
}

Eigen::VectorXd Random::vector(int n, double lo, double hi) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = uniform(lo, hi);
  return v;
}

double relative_error(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double floor) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(b.lpNorm<Eigen::Infinity>(), floor);
}

std::string robot_test_name(const testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(info.param.find_last_of('/') + 1);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

}  // namespace modelgen::test
