// The search coordinates of physical_coordinates.hpp. The load's log-Cholesky parameters map to
// its standard parameters (inertial_from_log_cholesky) and on to the load's own terms; Ceres' jets
// carry dg/dphi through both maps.

#include "runtime/src/ml/physical_coordinates.hpp"

#include <ceres/jet.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <utility>

#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/model/pseudo_inertia.hpp"

namespace modelgen::detail {
namespace {

// The load (LoadParameters::to_vector order) of its ten standard parameters about the payload
// link's frame (XX XY XZ YY YZ ZZ MX MY MZ M): standard_from_load inverted, as a template for
// Ceres' jets. The mass must be positive, which the log-Cholesky map guarantees.
template <class T>
void load_from_standard_parameters(const T* s, T* load) {
  const T m = s[9];
  const T cx = s[6] / m, cy = s[7] / m, cz = s[8] / m;
  load[0] = m;
  load[1] = cx;
  load[2] = cy;
  load[3] = cz;
  load[4] = s[0] - m * (cy * cy + cz * cz);  // Ixx
  load[5] = s[3] - m * (cx * cx + cz * cz);  // Iyy
  load[6] = s[5] - m * (cx * cx + cy * cy);  // Izz
  load[7] = s[1] + m * cx * cy;              // Ixy
  load[8] = s[2] + m * cx * cz;              // Ixz
  load[9] = s[4] + m * cy * cz;              // Iyz
}

}  // namespace

void Coordinates::unknowns(const double* phi, double* theta1, Eigen::MatrixXd* G) const {
  for (int u = 0; u < U; ++u) theta1[u] = held[u];
  if (G) G->setZero(U, size());
  for (std::size_t f = 0; f < free.size(); ++f) {
    theta1[free[f]] = phi[f];
    if (G) (*G)(free[f], static_cast<Eigen::Index>(f)) = 1;
  }
  if (!has_load) return;
  using Jet = ceres::Jet<double, 10>;
  Jet log_cholesky[10], standard[10], values[10];
  for (int i = 0; i < 10; ++i) log_cholesky[i] = Jet(phi[load_offset() + i], i);
  inertial_from_log_cholesky(log_cholesky, standard);
  load_from_standard_parameters(standard, values);
  for (int i = 0; i < 10; ++i) {
    theta1[load[i]] = values[i].a;
    if (G) {
      for (int j = 0; j < 10; ++j) (*G)(load[i], load_offset() + j) = values[i].v[j];
    }
  }
}

void Coordinates::standard_of(const double* log_cholesky, double* standard,
                              Eigen::Matrix<double, 10, 10>* D) {
  using Jet = ceres::Jet<double, 10>;
  Jet in[10], out[10];
  for (int i = 0; i < 10; ++i) in[i] = Jet(log_cholesky[i], i);
  inertial_from_log_cholesky(in, out);
  for (int i = 0; i < 10; ++i) {
    standard[i] = out[i].a;
    if (D) D->row(i) = out[i].v.transpose();
  }
}

CostInCoordinates::CostInCoordinates(const ceres::CostFunction* inner,
                                     const Coordinates& coordinates)
    : inner_(inner), coordinates_(coordinates) {
  set_num_residuals(inner->num_residuals());
  mutable_parameter_block_sizes()->push_back(coordinates.size());
}

bool CostInCoordinates::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const bool jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  Eigen::VectorXd theta1(coordinates_.U);
  Eigen::MatrixXd G;
  coordinates_.unknowns(parameters[0], theta1.data(), jacobian ? &G : nullptr);
  const double* inner_parameters[1] = {theta1.data()};
  if (!jacobian) return inner_->Evaluate(inner_parameters, residuals, nullptr);
  RowMajor J(num_residuals(), coordinates_.U);
  double* inner_jacobians[1] = {J.data()};
  if (!inner_->Evaluate(inner_parameters, residuals, inner_jacobians)) return false;
  Eigen::Map<RowMajor>(jacobians[0], num_residuals(), coordinates_.size()) = J * G;
  return true;
}

PriorCost::PriorCost(const Coordinates& coordinates, Eigen::VectorXd centre, Eigen::VectorXd weight)
    : coordinates_(coordinates), centre_(std::move(centre)), weight_(std::move(weight)) {
  set_num_residuals(static_cast<int>(centre_.size()));
  mutable_parameter_block_sizes()->push_back(coordinates.size());
}

bool PriorCost::Evaluate(double const* const* parameters, double* residuals,
                         double** jacobians) const {
  const double* phi = parameters[0];
  const int F = coordinates_.size();
  const int free = coordinates_.load_offset();
  double* J = jacobians != nullptr ? jacobians[0] : nullptr;
  if (J) std::fill(J, J + num_residuals() * F, 0.0);
  for (int f = 0; f < free; ++f) {
    residuals[f] = weight_[f] * (phi[f] - centre_[f]);
    if (J) J[f * F + f] = weight_[f];
  }
  if (!coordinates_.has_load) return true;
  double standard[10];
  Eigen::Matrix<double, 10, 10> D;
  Coordinates::standard_of(phi + free, standard, J ? &D : nullptr);
  for (int i = 0; i < 10; ++i) {
    residuals[free + i] = weight_[free + i] * (standard[i] - centre_[free + i]);
    if (!J) continue;
    for (int j = 0; j < 10; ++j) J[(free + i) * F + free + j] = weight_[free + i] * D(i, j);
  }
  return true;
}

Eigen::Matrix4d load_pseudo_inertia(const double* load) {
  double standard[10];
  standard_from_load(load, standard);
  return pseudo_inertia(standard);
}

Eigen::Matrix<double, 10, 1> consistent_standard(const double* load) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(load_pseudo_inertia(load));
  Eigen::Vector4d lambda = eigen.eigenvalues();
  const double largest = std::max(lambda.cwiseAbs().maxCoeff(), 1e-9);
  lambda = lambda.cwiseMax(1e-4 * largest);
  const Eigen::Matrix4d P =
      eigen.eigenvectors() * lambda.asDiagonal() * eigen.eigenvectors().transpose();
  Eigen::Matrix<double, 10, 1> standard;
  inertial_from_pseudo_inertia(P, standard.data());
  return standard;
}

}  // namespace modelgen::detail
