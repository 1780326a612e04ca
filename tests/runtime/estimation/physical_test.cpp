// The physically consistent fit against facts that do not come from it: a consistent estimate
// is returned unchanged at no cost; a negative friction estimate ends on its bound at the cost
// its distance gives in closed form; and the constrained optimum is not improved by any of
// thousands of feasible perturbations (consistent bodies by construction of the log-Cholesky
// map, bounded parameters kept >= 0), with the cost written again here.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Dense>

#include <gtest/gtest.h>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

class PhysicalFit : public testing::Test {
 protected:
  void SetUp() override {
    robot_ = load_robot(test::source_path("robots/tx40.yaml"));
    model_ = std::make_unique<ReferenceModel>("tx40", robot_.tree);
    K_ = regrouping_matrix(*model_);
    truth_ = random_consistent(rng_);
    no_prior_.assign(robot_.tree.params.size(), std::nullopt);
  }

  // Random consistent standard parameters: bodies of four point masses, positive drive terms.
  Eigen::VectorXd random_consistent(std::mt19937& rng) const {
    std::uniform_real_distribution<double> mass(0.5, 5), pos(-0.3, 0.3), drive(0.1, 2);
    Eigen::VectorXd p = Eigen::VectorXd::Zero(K_.cols());
    for (const auto& index : inertial_param_indices(robot_.tree)) {
      if (index[0] < 0) continue;
      for (int i = 0; i < 4; ++i) {
        const double m = mass(rng);
        const Eigen::Vector3d r(pos(rng), pos(rng), pos(rng));
        const Eigen::Matrix3d I = m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
        const double values[10] = {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2),
                                   m * r.x(), m * r.y(), m * r.z(), m};
        for (int s = 0; s < 10; ++s) p[index[s]] += values[s];
      }
    }
    for (std::size_t k = 0; k < robot_.tree.params.size(); ++k) {
      if (must_be_nonnegative(robot_.tree.params[k].kind)) p[static_cast<Eigen::Index>(k)] = drive(rng);
    }
    return p;
  }

  int base_index(const std::string& name) const {
    const auto& names = model_->base_param_names();
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }

  std::mt19937 rng_{2017};
  RobotModel robot_;
  std::unique_ptr<ReferenceModel> model_;
  Eigen::MatrixXd K_;
  Eigen::VectorXd truth_;
  std::vector<std::optional<double>> no_prior_;
};

TEST_F(PhysicalFit, LeavesAConsistentEstimateAlone) {
  const Eigen::VectorXd beta = K_ * truth_;
  const Eigen::MatrixXd F = Eigen::MatrixXd::Identity(beta.size(), beta.size());
  const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta, F, no_prior_);
  EXPECT_TRUE(fit.converged);
  // The default weight rule moves it by no more than a thousandth of a standard deviation.
  EXPECT_LT(fit.cost_increase, 1e-6);
  EXPECT_LT((fit.base - beta).cwiseAbs().maxCoeff(), 1e-3);
  for (const auto& v : physical_violations(robot_.tree, fit.standard)) ADD_FAILURE() << v.parameter << ": " << v.condition;
  EXPECT_LT((K_ * fit.standard - fit.base).norm(), 1e-12 * beta.norm());
  for (const std::string& c : fit.active_constraints) ADD_FAILURE() << "binding: " << c;
  // With F the identity, the base standard deviations are all 1 when no bound is active.
  EXPECT_LT((fit.base_std_dev - Eigen::VectorXd::Ones(beta.size())).cwiseAbs().maxCoeff(), 1e-3);
}

TEST_F(PhysicalFit, PutsANegativeFrictionOnItsBoundAtItsDistanceCost) {
  Eigen::VectorXd beta = K_ * truth_;
  const int fv = base_index("Fv2");
  ASSERT_LT(fv, beta.size());
  beta[fv] = -0.3;
  // A diagonal information matrix: the closed-form cost is (0.3 / sigma)^2, nothing else moves.
  Eigen::VectorXd variance = Eigen::VectorXd::LinSpaced(beta.size(), 0.5, 2.0);
  const Eigen::MatrixXd F = variance.cwiseInverse().asDiagonal();
  const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta, F, no_prior_);
  EXPECT_NEAR(fit.base[fv], 0.0, 1e-12);
  EXPECT_NEAR(fit.cost_increase, 0.09 / variance[fv], 1e-6 * 0.09 / variance[fv]);
  ASSERT_EQ(fit.active_constraints, std::vector<std::string>{"Fv2 >= 0"});
  // On its bound, Fv2 reports the unconstrained spread (the upper bound; not 0); a base
  // parameter the bound does not touch keeps the unconstrained one (F is diagonal).
  EXPECT_NEAR(fit.base_std_dev[fv], std::sqrt(variance[fv]), 1e-6);
  const int fv3 = base_index("Fv3");
  EXPECT_NEAR(fit.base_std_dev[fv3], std::sqrt(variance[fv3]), 1e-3 * std::sqrt(variance[fv3]));
  for (const auto& v : physical_violations(robot_.tree, fit.standard)) ADD_FAILURE() << v.parameter << ": " << v.condition;
}

TEST_F(PhysicalFit, BoundaryStandardDeviationBoundsTheSpreadOfRepeatedFits) {
  // The truth has Fv2 = 0, on its bound; unconstrained estimates drawn around it (sd 1 for Fv2,
  // 0.01 elsewhere, so nothing else leaves the consistent set). The consistent Fv2 is then
  // max(Fv2_hat, 0): its sd is sqrt(1/2 - 1/(2 pi)) = 0.584 in closed form. The reported sd
  // must be an honest bound on that spread: not 0, not below it, at most the unconstrained 1.
  const int fv = base_index("Fv2");
  Eigen::VectorXd truth = truth_;
  for (std::size_t k = 0; k < robot_.tree.params.size(); ++k) {
    if (robot_.tree.params[k].name == "Fv2") truth[static_cast<Eigen::Index>(k)] = 0;
  }
  const Eigen::VectorXd beta_true = K_ * truth;
  ASSERT_EQ(beta_true[fv], 0.0);
  Eigen::VectorXd sd = Eigen::VectorXd::Constant(beta_true.size(), 0.01);
  sd[fv] = 1;
  const Eigen::MatrixXd F = sd.cwiseAbs2().cwiseInverse().asDiagonal();
  PhysicalFitOptions options;
  options.prior_weight = 1e-6;
  std::normal_distribution<double> normal(0, 1);
  std::mt19937 rng(30);
  const int draws = 30;  // 0.1-0.3 s a fit
  double sum = 0, sum_squares = 0, smallest_reported = 1e300, largest_reported = 0;
  for (int draw = 0; draw < draws; ++draw) {
    Eigen::VectorXd beta = beta_true;
    for (Eigen::Index j = 0; j < beta.size(); ++j) beta[j] += sd[j] * normal(rng);
    const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta, F, no_prior_, options);
    EXPECT_NEAR(fit.base[fv], std::max(beta[fv], 0.0), 1e-6);
    sum += fit.base[fv];
    sum_squares += fit.base[fv] * fit.base[fv];
    smallest_reported = std::min(smallest_reported, fit.base_std_dev[fv]);
    largest_reported = std::max(largest_reported, fit.base_std_dev[fv]);
  }
  const double mean = sum / draws;
  const double spread = std::sqrt(sum_squares / draws - mean * mean);
  const double closed_form = std::sqrt(0.5 - 0.5 / M_PI);
  EXPECT_NEAR(spread, closed_form, 0.3);  // 30 draws agree with the closed form
  EXPECT_GE(smallest_reported, closed_form);
  EXPECT_LE(largest_reported, 1 + 1e-6);
}

TEST_F(PhysicalFit, NoFeasiblePerturbationLowersTheCostOfAnInconsistentEstimate) {
  // A base estimate far from any consistent robot: the truth's base parameters with their
  // signs flipped, under a random positive definite information matrix; the truth as the prior.
  Eigen::VectorXd beta = -(K_ * truth_);
  std::normal_distribution<double> normal(0, 1);
  Eigen::MatrixXd A(beta.size(), beta.size());
  for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = normal(rng_);
  const Eigen::MatrixXd F = A.transpose() * A / static_cast<double>(beta.size()) +
                            Eigen::MatrixXd::Identity(beta.size(), beta.size());
  std::vector<std::optional<double>> prior(truth_.data(), truth_.data() + truth_.size());
  PhysicalFitOptions options;
  options.prior_weight = 1e-4;
  const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta, F, prior, options);
  EXPECT_TRUE(fit.converged) << fit.iterations << " iterations";
  for (const auto& v : physical_violations(robot_.tree, fit.standard)) {
    ADD_FAILURE() << v.parameter << ": " << v.condition;
  }
  // The documented cost, written again (physical_prior.hpp): the base term plus w times the
  // prior, which is, per body with a-priori inertials, twice the log-det divergence
  // D(P || P0) = -log det(P0^-1 P) + tr(P0^-1 P) - 4 of its pseudo-inertia (formed here), and on
  // the other parameters their squared deviation relative to the reported scales, of its part
  // that changes no base parameter: z = L (p - prior) projected on the null space of K L^-1.
  ASSERT_EQ(fit.prior, truth_);
  const auto pseudo = [](const double* p) {
    Eigen::Matrix3d I;
    I << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
    Eigen::Matrix4d P;
    P.topLeftCorner<3, 3>() = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
    P.topRightCorner<3, 1>() = Eigen::Vector3d(p[6], p[7], p[8]);
    P.bottomLeftCorner<1, 3>() = Eigen::Vector3d(p[6], p[7], p[8]).transpose();
    P(3, 3) = p[9];
    return P;
  };
  std::vector<std::array<int, 10>> bodies_with_prior;
  std::vector<Eigen::Index> others;
  std::vector<char> in_body(static_cast<std::size_t>(truth_.size()), 0);
  for (const auto& index : inertial_param_indices(robot_.tree)) {
    if (std::find(index.begin(), index.end(), -1) != index.end()) continue;
    bodies_with_prior.push_back(index);
    for (int k : index) in_body[static_cast<std::size_t>(k)] = 1;
  }
  for (Eigen::Index k = 0; k < truth_.size(); ++k) {
    if (!in_body[static_cast<std::size_t>(k)]) others.push_back(k);
  }
  const auto divergence = [&](const Eigen::VectorXd& standard) {
    double sum = 0;
    for (const auto& index : bodies_with_prior) {
      double p[10], p0[10];
      for (int s = 0; s < 10; ++s) p[s] = standard[index[s]], p0[s] = truth_[index[s]];
      const Eigen::Matrix4d ratio = pseudo(p0).inverse() * pseudo(p);
      const double det = ratio.determinant();
      if (!(det > 0)) return std::numeric_limits<double>::infinity();
      sum += -std::log(det) + ratio.trace() - 4;
    }
    return sum;
  };
  const auto q = static_cast<Eigen::Index>(others.size());
  Eigen::MatrixXd M(K_.rows(), q);
  Eigen::VectorXd L(q);
  for (Eigen::Index i = 0; i < q; ++i) {
    L[i] = 1 / fit.prior_scale[others[static_cast<std::size_t>(i)]];
    M.col(i) = K_.col(others[static_cast<std::size_t>(i)]) / L[i];
  }
  const Eigen::MatrixXd null_projection =
      Eigen::MatrixXd::Identity(q, q) - M.completeOrthogonalDecomposition().pseudoInverse() * M;
  const auto cost = [&](const Eigen::VectorXd& standard) {
    const Eigen::VectorXd d = K_ * standard - beta;
    Eigen::VectorXd z(q);
    for (Eigen::Index i = 0; i < q; ++i) {
      const Eigen::Index k = others[static_cast<std::size_t>(i)];
      z[i] = L[i] * (standard[k] - truth_[k]);
    }
    return d.dot(F * d) +
           *options.prior_weight * (z.dot(null_projection * z) + 2 * divergence(standard));
  };
  const double best = cost(fit.standard);
  EXPECT_LT(fit.cost_increase, best);
  EXPECT_GT(fit.cost_increase, 0.95 * best);  // the prior term, 1 % here, only picks among fits
  EXPECT_GT(best, 1.0);  // the estimate was not consistent: the constraints cost something
  // Bodies on the boundary: every base parameter still has a spread, at most the
  // unconstrained one (the prior adds information, the constraints only take it away).
  ASSERT_FALSE(fit.active_constraints.empty());
  const Eigen::VectorXd unconstrained_sd = F.inverse().diagonal().cwiseSqrt();
  for (Eigen::Index j = 0; j < beta.size(); ++j) {
    EXPECT_GT(fit.base_std_dev[j], 1e-3 * unconstrained_sd[j]) << j;
    EXPECT_LE(fit.base_std_dev[j], unconstrained_sd[j] * (1 + 1e-6)) << j;
  }
  // Feasible perturbations: each body through its log-Cholesky parameters, bounded drive
  // parameters kept >= 0, the rest free.
  const auto bodies = inertial_param_indices(robot_.tree);
  for (int trial = 0; trial < 2000; ++trial) {
    const double step = 1e-4 * std::pow(10.0, trial % 4);
    Eigen::VectorXd moved = fit.standard;
    for (const auto& index : bodies) {
      if (index[0] < 0) continue;
      Eigen::Matrix<double, 10, 1> p;
      for (int s = 0; s < 10; ++s) p[s] = fit.standard[index[s]];
      auto theta = log_cholesky_from_inertial(p.data());
      ASSERT_TRUE(theta.has_value());
      for (int i = 0; i < 10; ++i) (*theta)[i] += step * normal(rng_);
      inertial_from_log_cholesky(theta->data(), p.data());
      for (int s = 0; s < 10; ++s) moved[index[s]] = p[s];
    }
    for (std::size_t k = 0; k < robot_.tree.params.size(); ++k) {
      if (is_inertial(robot_.tree.params[k].kind)) continue;
      double& v = moved[static_cast<Eigen::Index>(k)];
      v += step * normal(rng_) * (1 + std::abs(v));
      if (must_be_nonnegative(robot_.tree.params[k].kind)) v = std::max(v, 0.0);
    }
    EXPECT_GE(cost(moved), best * (1 - 1e-9)) << "trial " << trial << ", step " << step;
  }
}

TEST_F(PhysicalFit, RefusesMismatchedSizesAndAnIndefiniteInformation) {
  const Eigen::VectorXd beta = K_ * truth_;
  EXPECT_THROW(fit_physical(robot_.tree, K_, beta.head(3), Eigen::MatrixXd::Identity(3, 3),
                            no_prior_),
               EstimationError);
  EXPECT_THROW(fit_physical(robot_.tree, K_, beta,
                            -Eigen::MatrixXd::Identity(beta.size(), beta.size()), no_prior_),
               EstimationError);
}

}  // namespace
}  // namespace modelgen
