// Implementation of the shared test helpers.

#include "tests/support/test_support.hpp"

#include <algorithm>
#include <filesystem>

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

Eigen::VectorXd Random::vector(int n, double lo, double hi) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = uniform(lo, hi);
  return v;
}

double relative_error(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double floor) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(b.lpNorm<Eigen::Infinity>(), floor);
}

}  // namespace modelgen::test
