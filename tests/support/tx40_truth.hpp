// The true base parameters of the simulated Staubli TX-40 (robots/tx40.yaml), for the tests that
// simulate it: Gautier & Briot's identified values where the paper has them.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen::test {

struct NamedValue {
  const char* name;
  double value;
};

/// One value per base parameter of robots/tx40.yaml (kg m^2, kg m, N m s/rad, N m); sources
/// in tx40_truth.cpp.
std::span<const NamedValue> tx40_true_base();

/// tx40_true_base() in the order of `names`: NaN for a name the table lacks.
Eigen::VectorXd tx40_true_base(const std::vector<std::string>& names);

}  // namespace modelgen::test
