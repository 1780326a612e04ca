// What the tests of regions in the physically consistent fit share (physical_region_test for a
// URDF arm with shapes, mdh_guessed_region_fit_test for a YAML arm with guessed regions): the
// standard parameters of solids written from their closed forms, a link's extent in its region
// written from its definition, and torques of a truth at random states plus noise with their
// least-squares fit. Header only.
#pragma once

#include <array>
#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::test {

// Ten standard parameters (inertia about the frame origin) of mass m at c, inertia Ic about c.
inline std::array<double, 10> body_params(double m, const Eigen::Vector3d& c,
                                          const Eigen::Matrix3d& Ic) {
  const Eigen::Matrix3d I =
      Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), m * c.x(), m * c.y(), m * c.z(), m};
}

// A solid box of sides s (about its centre).
inline Eigen::Matrix3d solid_box(double m, const Eigen::Vector3d& s) {
  return Eigen::Vector3d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                         s.x() * s.x() + s.y() * s.y())
             .asDiagonal() *
         (m / 12);
}

// A solid cylinder of radius r and length l along `axis` (0 x, 2 z).
inline Eigen::Matrix3d solid_cylinder(double m, double r, double l, int axis) {
  Eigen::Vector3d d = Eigen::Vector3d::Constant(m * (3 * r * r + l * l) / 12);
  d[axis] = m * r * r / 2;
  return d.asDiagonal();
}

// The rms extent of p in region, written here from its definition: the mean over the mass of
// (x - c)' A (x - c) = tr(A (S - c h' - h c' + m c c')) / m, S the second moment.
inline double extent(const double* p, const BodyRegion& region) {
  const Eigen::Matrix4d P = pseudo_inertia(p);
  const Eigen::Vector3d c(region.centre[0], region.centre[1], region.centre[2]);
  const Eigen::Vector3d s(region.semi_axes[0], region.semi_axes[1], region.semi_axes[2]);
  const Eigen::Matrix3d A = s.cwiseAbs2().cwiseInverse().asDiagonal();
  const Eigen::Vector3d h = P.topRightCorner<3, 1>();
  const double m = P(3, 3);
  const Eigen::Matrix3d spread =
      P.topLeftCorner<3, 3>() - c * h.transpose() - h * c.transpose() + m * c * c.transpose();
  return std::sqrt((A * spread).trace() / m);
}

// Torques of `truth` (standard parameters; K regroups them) at random states plus white noise,
// and their least-squares base estimate with its information matrix.
struct SimulatedFit {
  Eigen::MatrixXd W, information;
  Eigen::VectorXd tau, beta_hat;

  double rel_error_norm(const Eigen::VectorXd& beta) const {
    return (tau - W * beta).norm() / tau.norm();
  }
};

inline SimulatedFit simulate_and_fit(const ReferenceModel& model, const Eigen::MatrixXd& K,
                                     const Eigen::VectorXd& truth, std::mt19937& rng,
                                     double noise_std, int states = 400) {
  const int dof = model.dof(), b = model.num_base_params();
  std::uniform_real_distribution<double> angle(-3, 3), speed(-2, 2), acceleration(-6, 6);
  std::normal_distribution<double> noise(0, noise_std);
  SimulatedFit fit;
  fit.W.resize(dof * states, b);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(dof, b);
  for (int s = 0; s < states; ++s) {
    Eigen::VectorXd q(dof), dq(dof), ddq(dof);
    for (int j = 0; j < dof; ++j) q[j] = angle(rng), dq[j] = speed(rng), ddq[j] = acceleration(rng);
    model.regressor(q.data(), dq.data(), ddq.data(), rows.data());
    fit.W.middleRows(s * dof, dof) = rows;
  }
  fit.tau = fit.W * (K * truth);
  for (Eigen::Index i = 0; i < fit.tau.size(); ++i) fit.tau[i] += noise(rng);
  fit.beta_hat = fit.W.colPivHouseholderQr().solve(fit.tau);
  const double sigma2 =
      (fit.tau - fit.W * fit.beta_hat).squaredNorm() / static_cast<double>(fit.tau.size() - b);
  fit.information = fit.W.transpose() * fit.W / sigma2;
  return fit;
}

}  // namespace modelgen::test
