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

std::function<double(const gen::Symbol&)> symbol_values(const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& dq,
                                                        const Eigen::VectorXd& ddq,
                                                        const Eigen::VectorXd& p) {
  return [&q, &dq, &ddq, &p](const gen::Symbol& s) {
    auto input = [&](const std::string& text) {
      const std::size_t open = text.find('[');
      const std::string array = text.substr(0, open);
      const int index = std::stoi(text.substr(open + 1));
      if (array == "q") return q[index];
      if (array == "dq") return dq[index];
      if (array == "ddq") return ddq[index];
      return p[index];
    };
    switch (s.kind) {
      case gen::SymbolKind::kInput: return input(s.name);
      case gen::SymbolKind::kSin: return std::sin(input(s.input));
      case gen::SymbolKind::kCos: return std::cos(input(s.input));
      case gen::SymbolKind::kSign: {
        const double x = input(s.input);
        return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
      }
      case gen::SymbolKind::kPositive: return input(s.input) > 0 ? 1.0 : 0.0;
      case gen::SymbolKind::kNegative: return input(s.input) < 0 ? 1.0 : 0.0;
    }
    return 0.0;
  };
}

}  // namespace modelgen::test
