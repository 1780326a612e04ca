// Shared test helpers: paths to the project and ../shared, seeded random states, error norms.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>


namespace modelgen::test {

/// Absolute path of a file in the source tree, e.g. source_path("robots/kr150.yaml").
std::string source_path(std::string_view relative);

/// Absolute path under ../shared (datasets, reference URDFs); may not exist.
std::string shared_path(std::string_view relative);

/// Every shipped robot description: robots/*.yaml and robots/urdf/*.urdf, sorted.
std::vector<std::string> shipped_robots();

/// Seeded uniform random numbers; the same seed gives the same sequence on every machine.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi);
  /// Standard normal numbers (Box-Muller on two uniform() draws).
  double normal();
  Eigen::VectorXd vector(int n, double lo, double hi);

 private:
  std::mt19937_64 engine_;
};

/// max_i |a_i - b_i| / max(max_i |b_i|, floor): relative error in the infinity norm.
double relative_error(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double floor = 1e-12);

/// A test name from a robot description path: "robots/tx40.yaml" -> "tx40_yaml".
std::string robot_test_name(const testing::TestParamInfo<std::string>& info);

}  // namespace modelgen::test
