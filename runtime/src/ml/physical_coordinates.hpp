// The search coordinates of the consistent maximum-likelihood fit (physical_fit.cpp): theta1 as
// a function of phi (the free drive unknowns as themselves, the load as the ten log-Cholesky
// parameters of its standard parameters about the payload link's frame), the problem's cost
// blocks and the prior term in those coordinates, and the load's pseudo-inertia and nearest
// consistent standard parameters.
#pragma once

#include <array>
#include <vector>

#include <ceres/ceres.h>

#include <Eigen/Core>

namespace modelgen::detail {

// theta1 (the problem's unknowns) as a function of the search coordinates phi: the free drive
// unknowns first, then the load's log-Cholesky parameters.
struct Coordinates {
  int U = 0;
  std::vector<int> free;       // theta1 positions searched as themselves
  std::array<int, 10> load{};  // theta1 positions of the load, to_vector() order
  bool has_load = false;
  Eigen::VectorXd held;  // theta1 values, used where a position is not searched

  int size() const { return static_cast<int>(free.size()) + (has_load ? 10 : 0); }
  int load_offset() const { return static_cast<int>(free.size()); }

  // theta1 = g(phi) and, when G is not null, dg/dphi (U x size()).
  void unknowns(const double* phi, double* theta1, Eigen::MatrixXd* G) const;

  // The load's standard parameters of phi and their derivatives (10 x 10).
  static void standard_of(const double* log_cholesky, double* standard,
                          Eigen::Matrix<double, 10, 10>* D);
};

// A cost block of the problem in the coordinates phi.
class CostInCoordinates final : public ceres::CostFunction {
 public:
  CostInCoordinates(const ceres::CostFunction* inner, const Coordinates& coordinates);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const ceres::CostFunction* inner_;
  const Coordinates& coordinates_;
};

// The prior term: sqrt(w) (value - start) / scale for each free drive unknown and each of the
// load's standard parameters.
class PriorCost final : public ceres::CostFunction {
 public:
  PriorCost(const Coordinates& coordinates, Eigen::VectorXd centre, Eigen::VectorXd weight);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const Coordinates& coordinates_;
  Eigen::VectorXd centre_, weight_;
};

// The pseudo-inertia of a load given in to_vector() order.
Eigen::Matrix4d load_pseudo_inertia(const double* load);

// The nearest consistent standard parameters to those of `load` in the Frobenius norm of the
// pseudo-inertia: its eigenvalues floored at a small fraction of the largest.
Eigen::Matrix<double, 10, 1> consistent_standard(const double* load);

}  // namespace modelgen::detail
