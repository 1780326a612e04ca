// Load parameters (Swevers et al. 2002, eq. 3) <-> the payload link's standard parameters
// (Gautier & Briot eq. 3) by the parallel-axis theorem, the 10 x 10 Jacobian of that map, and the
// physical-consistency checks of an estimated load.

#include "modelgen/ml/load_parameters.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace modelgen {
namespace {

std::string format(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

}  // namespace

std::array<double, kLoadParams> LoadParameters::to_vector() const {
  return {mass,       com[0],     com[1],     com[2],     inertia[0],
          inertia[1], inertia[2], inertia[3], inertia[4], inertia[5]};
}

LoadParameters LoadParameters::from_vector(const double* values) {
  LoadParameters load;
  load.mass = values[0];
  for (int i = 0; i < 3; ++i) load.com[i] = values[1 + i];
  for (int i = 0; i < 6; ++i) load.inertia[i] = values[4 + i];
  return load;
}

const std::vector<std::string>& load_param_names() {
  static const std::vector<std::string> names = {"load_m",   "load_cx",  "load_cy",  "load_cz",
                                                 "load_Ixx", "load_Iyy", "load_Izz", "load_Ixy",
                                                 "load_Ixz", "load_Iyz"};
  return names;
}

std::array<double, 10> standard_from_load(const LoadParameters& load) {
  const std::array<double, kLoadParams> v = load.to_vector();
  std::array<double, 10> standard{};
  standard_from_load(v.data(), standard.data());
  return standard;
}

Eigen::MatrixXd standard_from_load_jacobian(const LoadParameters& load) {
  const double m = load.mass, cx = load.com[0], cy = load.com[1], cz = load.com[2];
  // Columns: m cx cy cz Ixx Iyy Izz Ixy Ixz Iyz; rows: XX XY XZ YY YZ ZZ MX MY MZ M.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(10, kLoadParams);
  J(0, 0) = cy * cy + cz * cz, J(0, 2) = 2 * m * cy, J(0, 3) = 2 * m * cz, J(0, 4) = 1;
  J(1, 0) = -cx * cy, J(1, 1) = -m * cy, J(1, 2) = -m * cx, J(1, 7) = 1;
  J(2, 0) = -cx * cz, J(2, 1) = -m * cz, J(2, 3) = -m * cx, J(2, 8) = 1;
  J(3, 0) = cx * cx + cz * cz, J(3, 1) = 2 * m * cx, J(3, 3) = 2 * m * cz, J(3, 5) = 1;
  J(4, 0) = -cy * cz, J(4, 2) = -m * cz, J(4, 3) = -m * cy, J(4, 9) = 1;
  J(5, 0) = cx * cx + cy * cy, J(5, 1) = 2 * m * cx, J(5, 2) = 2 * m * cy, J(5, 6) = 1;
  J(6, 0) = cx, J(6, 1) = m;
  J(7, 0) = cy, J(7, 2) = m;
  J(8, 0) = cz, J(8, 3) = m;
  J(9, 0) = 1;
  return J;
}

LoadParameters load_from_standard(const double* standard) {
  static const char* const kNames[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
  for (int k = 0; k < 10; ++k) {
    if (!std::isfinite(standard[k])) {
      throw std::invalid_argument(std::string("load from standard parameters: ") + kNames[k] +
                                  " is '" + format(standard[k]) + "'; values must be finite");
    }
  }
  const double m = standard[9];
  if (!(m > 0)) {
    throw std::invalid_argument("load from standard parameters: the mass M is " + format(m) +
                                " kg; a load needs a positive mass to have a centre of gravity");
  }
  LoadParameters load;
  load.mass = m;
  const double cx = standard[6] / m, cy = standard[7] / m, cz = standard[8] / m;
  load.com = {cx, cy, cz};
  // Parallel-axis theorem backwards: I_c = J_O - m (|c|^2 1 - c c^T).
  load.inertia = {standard[0] - m * (cy * cy + cz * cz),
                  standard[3] - m * (cx * cx + cz * cz),
                  standard[5] - m * (cx * cx + cy * cy),
                  standard[1] + m * cx * cy,
                  standard[2] + m * cx * cz,
                  standard[4] + m * cy * cz};
  return load;
}

std::vector<std::string> physical_consistency_warnings(const LoadParameters& load) {
  std::vector<std::string> warnings;
  const std::array<double, kLoadParams> v = load.to_vector();
  for (int k = 0; k < kLoadParams; ++k) {
    if (!std::isfinite(v[k])) {
      warnings.push_back(load_param_names()[k] + " is '" + format(v[k]) + "', not a number");
    }
  }
  if (!warnings.empty()) return warnings;
  if (!(load.mass > 0)) {
    warnings.push_back("the load mass " + format(load.mass) + " kg is not positive");
  }
  const auto& I = load.inertia;
  Eigen::Matrix3d Ic;
  Ic << I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2];
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ic).eigenvalues();
  const std::string listed =
      format(moments[0]) + ", " + format(moments[1]) + ", " + format(moments[2]) + " kg m^2";
  if (!(moments[0] > 0)) {
    warnings.push_back(
        "the inertia about the centre of gravity is not positive definite: principal moments " +
        listed);
  }
  // Triangle inequality of the principal moments: the largest may not exceed the sum of the
  // other two (a body of zero thickness reaches equality). Eigenvalues come sorted ascending.
  const double slack = 1e-12 * std::max(1.0, std::abs(moments[2]));
  if (moments[2] > moments[0] + moments[1] + slack) {
    warnings.push_back("the principal moments of inertia " + listed +
                       " violate the triangle inequality: " + format(moments[2]) + " > " +
                       format(moments[0]) + " + " + format(moments[1]));
  }
  return warnings;
}

std::vector<std::string> load_warnings(const LoadParameters& load) {
  const std::array<double, kLoadParams> v = load.to_vector();
  if (std::any_of(v.begin(), v.end(), [](double x) { return std::isnan(x); })) return {};
  return physical_consistency_warnings(load);
}

}  // namespace modelgen
