// The log-det divergence prior of the physically consistent fit (Lee, Wensing & Park, T-RO
// 2020), checked against computations written here: its value against Eigen's determinant of
// the pseudo-inertia built here, its gradient and Hessian against central differences, and the
// fit's minimiser against the divergence's own minimisers, without data (the a-priori body
// itself), with data fixing a body's mass and first moments (closed form: the a-priori second
// moment about the centre of mass is kept) and with data fixing three random combinations (the
// constrained minimiser by Newton on its Lagrange multipliers, solved here).

#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/src/estimation/physical_prior.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// The pseudo-inertia of the barrier's ten variables, written here: diagonal entries as they
// are, off-diagonal ones (xy, xz, yz, x1, y1, z1 in the variables' order) divided by sqrt 2.
Eigen::Matrix4d pseudo_inertia_here(const Eigen::Matrix<double, 10, 1>& x) {
  const double r = std::sqrt(0.5);
  Eigen::Matrix4d P;
  P << x[0], r * x[1], r * x[2], r * x[6], r * x[1], x[3], r * x[4], r * x[7], r * x[2], r * x[4],
      x[5], r * x[8], r * x[6], r * x[7], r * x[8], x[9];
  return P;
}

double divergence_here(const Eigen::Matrix4d& P0, const Eigen::Matrix<double, 10, 1>& x) {
  const Eigen::Matrix4d P = pseudo_inertia_here(x);
  const Eigen::Matrix4d M = P0.inverse() * P;
  return -std::log(M.determinant()) + M.trace() - 4;
}

Eigen::Matrix4d random_body(std::mt19937& rng) {
  std::normal_distribution<double> normal(0, 1);
  Eigen::Matrix4d B;
  for (int i = 0; i < 16; ++i) B(i / 4, i % 4) = normal(rng);
  return B * B.transpose() + 0.1 * Eigen::Matrix4d::Identity();
}

TEST(LogDetDivergence, ValueGradientAndHessianMatchDifferences) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix4d P0 = random_body(rng), P = random_body(rng);
    Eigen::Matrix<double, 10, 1> x;
    const double s = std::sqrt(2.0);
    x << P(0, 0), s * P(0, 1), s * P(0, 2), P(1, 1), s * P(1, 2), P(2, 2), s * P(0, 3), s * P(1, 3),
        s * P(2, 3), P(3, 3);
    ASSERT_TRUE((pseudo_inertia_here(x) - P).norm() < 1e-12);
    const auto d = detail::log_det_divergence(P0, x.data());
    ASSERT_TRUE(d.has_value());
    EXPECT_NEAR(d->value, divergence_here(P0, x), 1e-9 * (1 + std::abs(d->value)));
    EXPECT_NEAR(detail::log_det_divergence(P0, x.data(), false)->value, d->value, 1e-12);
    const double h = 1e-5;
    for (int e = 0; e < 10; ++e) {
      Eigen::Matrix<double, 10, 1> up = x, down = x;
      up[e] += h, down[e] -= h;
      const double slope = (divergence_here(P0, up) - divergence_here(P0, down)) / (2 * h);
      EXPECT_NEAR(d->gradient[e], slope, 1e-6 * (1 + std::abs(slope))) << trial << " " << e;
      const auto gu = detail::log_det_divergence(P0, up.data());
      const auto gd = detail::log_det_divergence(P0, down.data());
      for (int f = 0; f < 10; ++f) {
        const double curve = (gu->gradient[f] - gd->gradient[f]) / (2 * h);
        EXPECT_NEAR(d->hessian(e, f), curve, 1e-6 * (1 + std::abs(curve))) << e << " " << f;
      }
    }
    // Scale-free: the same divergence for P and P0 in any unit (P -> c P, P0 -> c P0).
    const Eigen::Matrix<double, 10, 1> scaled = 1e-3 * x;
    EXPECT_NEAR(detail::log_det_divergence(1e-3 * P0, scaled.data())->value, d->value,
                1e-9 * (1 + d->value));
  }
  // Not a body: no value.
  Eigen::Matrix<double, 10, 1> flat = Eigen::Matrix<double, 10, 1>::Zero();
  flat[9] = 1;
  EXPECT_FALSE(detail::log_det_divergence(Eigen::Matrix4d::Identity(), flat.data()).has_value());
}

// The UR5's bodies as the a-priori model (all ten values of every moving body), drive
// parameters without a-priori values.
class DivergencePrior : public testing::Test {
 protected:
  void SetUp() override {
    robot_ = load_robot(test::source_path("robots/urdf/ur5.urdf"));
    n_ = static_cast<Eigen::Index>(robot_.tree.params.size());
    for (const auto& index : inertial_param_indices(robot_.tree)) {
      if (index[0] >= 0) bodies_.push_back(index);
    }
    a_priori_.assign(static_cast<std::size_t>(n_), std::nullopt);
    for (const auto& index : bodies_) {
      for (int k : index)
        a_priori_[static_cast<std::size_t>(k)] = robot_.known_values[static_cast<std::size_t>(k)];
    }
  }

  Eigen::Matrix4d a_priori_body(std::size_t b) const {
    double p[10];
    for (int s = 0; s < 10; ++s) p[s] = *a_priori_[static_cast<std::size_t>(bodies_[b][s])];
    return pseudo_inertia(p);
  }

  Eigen::Matrix4d fitted_body(const PhysicalFitResult& fit, std::size_t b) const {
    double p[10];
    for (int s = 0; s < 10; ++s) p[s] = fit.standard[bodies_[b][s]];
    return pseudo_inertia(p);
  }

  // Rows of K that read `rows` (r x 10) of body b's standard parameters.
  Eigen::MatrixXd rows_on_body(std::size_t b, const Eigen::MatrixXd& rows) const {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(rows.rows(), n_);
    for (int s = 0; s < 10; ++s) K.col(bodies_[b][s]) = rows.col(s);
    return K;
  }

  PhysicalFitResult fit(const Eigen::MatrixXd& K, const Eigen::VectorXd& beta,
                        double information) const {
    PhysicalFitOptions options;
    options.prior_weight = 1;
    const Eigen::MatrixXd F = information * Eigen::MatrixXd::Identity(K.rows(), K.rows());
    return fit_physical(robot_.tree, K, beta, F, a_priori_, options);
  }

  RobotModel robot_;
  Eigen::Index n_ = 0;
  std::vector<std::array<int, 10>> bodies_;
  std::vector<std::optional<double>> a_priori_;
};

TEST_F(DivergencePrior, WithoutDataTheMinimiserIsTheAPrioriBody) {
  // One row of data on one body's mass, twice the a-priori value, with information 1e-20:
  // nothing; every body is its a-priori body, to the solver's accuracy.
  ASSERT_GE(bodies_.size(), 3u);
  Eigen::MatrixXd mass_row = Eigen::MatrixXd::Zero(1, 10);
  mass_row(0, 9) = 1;
  const Eigen::VectorXd beta =
      Eigen::VectorXd::Constant(1, 2 * *a_priori_[static_cast<std::size_t>(bodies_[1][9])]);
  const PhysicalFitResult result = fit(rows_on_body(1, mass_row), beta, 1e-20);
  ASSERT_TRUE(result.converged);
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const Eigen::Matrix4d P0 = a_priori_body(b);
    EXPECT_LT((fitted_body(result, b) - P0).norm(), 1e-7 * P0.norm()) << b;
  }
}

TEST_F(DivergencePrior, DataFixingMassAndFirstMomentsKeepTheAPrioriSpreadAboutTheCentre) {
  // Data fix mass and first moments of body 2 at 1.4 times the mass and a centre of mass 5 cm
  // away. min D(P || P0) over the P with that m and h: the stationarity of the second-moment
  // block, (P^-1)_SS = (P0^-1)_SS, is Sigma = Sigma0 with Sigma = S - h h' / m (the second moment
  // about the centre of mass, a Schur complement): S = Sigma0 + h h' / m.
  const std::size_t b = 2;
  const Eigen::Matrix4d P0 = a_priori_body(b);
  const double m0 = P0(3, 3), m = 1.4 * m0;
  const Eigen::Vector3d h0 = P0.topRightCorner<3, 1>();
  const Eigen::Vector3d c = h0 / m0 + Eigen::Vector3d(0.03, -0.04, 0.0);
  const Eigen::Vector3d h = m * c;
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(4, 10);
  for (int i = 0; i < 4; ++i) rows(i, 6 + i) = 1;
  const Eigen::VectorXd beta = (Eigen::VectorXd(4) << h, m).finished();
  const PhysicalFitResult result = fit(rows_on_body(b, rows), beta, 1e12);
  ASSERT_TRUE(result.converged);
  Eigen::Matrix4d want;
  const Eigen::Matrix3d Sigma0 = P0.topLeftCorner<3, 3>() - h0 * h0.transpose() / m0;
  want << Sigma0 + h * h.transpose() / m, h, h.transpose(), m;
  EXPECT_LT((fitted_body(result, b) - want).norm(), 1e-6 * want.norm())
      << fitted_body(result, b) << "\nwant\n"
      << want;
  for (std::size_t other = 0; other < bodies_.size(); ++other) {
    if (other == b) continue;
    EXPECT_LT((fitted_body(result, other) - a_priori_body(other)).norm(), 1e-7 * P0.norm());
  }
}

TEST_F(DivergencePrior, DataFixingRandomCombinationsGiveTheConstrainedMinimiser) {
  // Three random combinations k_i' p of body 1's standard parameters fixed at a consistent
  // body's values. The minimiser of D(P || P0) subject to <A_i, P> = beta_i (A_i the matrix of
  // k_i' p in P) has P^-1 = P0^-1 - sum lambda_i A_i: Newton on lambda, Jacobian by differences.
  const std::size_t b = 1;
  const Eigen::Matrix4d P0 = a_priori_body(b);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0, 1);
  Eigen::MatrixXd rows(3, 10);
  for (int i = 0; i < 30; ++i) rows(i / 10, i % 10) = normal(rng);
  Eigen::Matrix4d truth = P0;  // the a-priori body with 30 % more mass, 2 cm off, 20 % wider
  truth.topLeftCorner<3, 3>() *= 1.2;
  const Eigen::Vector4d shift(0.02, 0.0, -0.01, 1);
  truth += 0.3 * P0(3, 3) * shift * shift.transpose();
  const auto standard_of = [](const Eigen::Matrix4d& P) {
    Eigen::Matrix<double, 10, 1> p;
    inertial_from_pseudo_inertia(P, p.data());
    return p;
  };
  const Eigen::VectorXd beta = rows * standard_of(truth);
  std::array<Eigen::Matrix4d, 3> A;  // <A_i, P> = k_i' p(P), p linear in P
  for (int i = 0; i < 3; ++i) {
    for (int r = 0; r < 4; ++r) {
      for (int col = 0; col < 4; ++col) {
        Eigen::Matrix4d unit = Eigen::Matrix4d::Zero();
        unit(r, col) = 1;  // not symmetric: its p is the linear map's derivative along (r, col)
        A[static_cast<std::size_t>(i)](r, col) = rows.row(i).dot(standard_of(unit));
      }
    }
  }
  const auto body_of = [&](const Eigen::Vector3d& lambda) {
    Eigen::Matrix4d inverse = P0.inverse();
    for (int i = 0; i < 3; ++i) inverse -= lambda[i] * 0.5 * (A[i] + A[i].transpose());
    return Eigen::Matrix4d(inverse.inverse());
  };
  const auto residual = [&](const Eigen::Vector3d& lambda) {
    return Eigen::Vector3d(rows * standard_of(body_of(lambda)) - beta);
  };
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
  for (int iteration = 0; iteration < 100 && residual(lambda).norm() > 1e-13 * beta.norm();
       ++iteration) {
    Eigen::Matrix3d jacobian;
    for (int i = 0; i < 3; ++i) {
      const double step = 1e-7 * (1 + std::abs(lambda[i]));
      Eigen::Vector3d up = lambda, down = lambda;
      up[i] += step, down[i] -= step;
      jacobian.col(i) = (residual(up) - residual(down)) / (2 * step);
    }
    const Eigen::Vector3d direction = -jacobian.fullPivLu().solve(residual(lambda));
    double s = 1;  // halve until the body stays positive definite and the residual falls
    while (s > 1e-8) {
      const Eigen::Vector3d trial = lambda + s * direction;
      if (Eigen::LLT<Eigen::Matrix4d>(body_of(trial)).info() == Eigen::Success &&
          residual(trial).norm() < residual(lambda).norm()) {
        break;
      }
      s *= 0.5;
    }
    lambda += s * direction;
  }
  ASSERT_LT(residual(lambda).norm(), 1e-10 * beta.norm());
  const Eigen::Matrix4d want = body_of(lambda);

  const PhysicalFitResult result = fit(rows_on_body(b, rows), beta, 1e10);
  ASSERT_TRUE(result.converged) << result.iterations << " Newton steps";
  EXPECT_LT((fitted_body(result, b) - want).norm(), 1e-5 * want.norm())
      << fitted_body(result, b) << "\nwant\n"
      << want;
  EXPECT_GT((want - P0).norm(), 1e-2 * P0.norm());  // the data moved it
}

}  // namespace
}  // namespace modelgen
