// The a-priori model as the prior of the physically consistent fit, checked against the truth
// that made the data: torques of the shipped UR5 URDF's own inertials (with positive drive
// terms) at random states plus noise, fitted by least squares here; the a-priori inertials
// given to the fit are perturbed (masses by +-30 %, centres of mass by 2 cm). With the default
// weight rule the base parameters stay within a fraction of their standard deviation of the
// unconstrained fit, every moving link's mass and centre of mass stay near the truth, and the
// torques are predicted as well. The per-link summary's "decided by data" is checked against
// the null space of the regrouping map computed here.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/link_summary.hpp"
#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// Ten standard parameters (inertia about the frame origin) from mass, com, inertia about com.
std::array<double, 10> body_params(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic) {
  const Eigen::Matrix3d I =
      Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), m * c.x(), m * c.y(), m * c.z(), m};
}

// Torque noise: 0.05 N m, 0.3 % of the UR5's rms torque (16 N m) at these states; the 0.19 kg last
// link's first moments are then known to about 1 cm times its mass.
constexpr double kNoise = 0.05;

class PhysicalPrior : public testing::Test {
 protected:
  void SetUp() override { make(0.0, kNoise); }

  // The truth: the URDF's bodies, each with `margin` m^2 times its mass added to its inertia
  // about the centre of mass on every axis (0: the URDF as shipped, whose wrists are flat discs
  // on the boundary of consistency, izz = ixx + iyy to 1.5 %).
  void make(double margin, double noise) {
    robot_ = load_robot(test::source_path("robots/urdf/ur5.urdf"));
    model_ = std::make_unique<ReferenceModel>("ur5", robot_.tree);
    K_ = regrouping_matrix(*model_);
    const auto n = static_cast<Eigen::Index>(robot_.tree.params.size());
    truth_ = Eigen::VectorXd::Zero(n);
    std::mt19937 rng(30);
    std::uniform_real_distribution<double> drive(0.2, 1.0);
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto& known = robot_.known_values[static_cast<std::size_t>(k)];
      if (known) {
        truth_[k] = *known;
      } else if (must_be_nonnegative(robot_.tree.params[static_cast<std::size_t>(k)].kind)) {
        truth_[k] = drive(rng);
      }
    }
    if (margin > 0) fatten(margin);
    a_priori_ = perturbed_inertials();
    simulate(rng, noise);
  }

  void fatten(double margin) {
    for (const auto& index : inertial_param_indices(robot_.tree)) {
      if (index[0] < 0) continue;
      const double m = truth_[index[9]];
      for (int s : {0, 3, 5}) truth_[index[s]] += margin * m;
    }
  }

  // The a-priori values given to the fit: the truth's bodies with masses alternately 30 % up
  // and down and centres of mass moved by 2 cm, inertia about the centre of mass kept.
  std::vector<std::optional<double>> perturbed_inertials(double mass_change = 0.3,
                                                         double com_shift = 0.02) const {
    std::vector<std::optional<double>> out(static_cast<std::size_t>(truth_.size()));
    int moved = 0;
    for (const auto& index : inertial_param_indices(robot_.tree)) {
      if (index[0] < 0) continue;
      double p[10];
      for (int s = 0; s < 10; ++s) p[s] = truth_[index[s]];
      const LinkQuantities q = link_quantities(p);
      Eigen::Matrix3d Ic;
      const auto& i = q.inertia_com;
      Ic << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
      const double sign = (moved++ % 2 == 0) ? 1.0 : -1.0;
      const Eigen::Vector3d shift = com_shift * Eigen::Vector3d(sign, -sign, 1).normalized();
      const auto values = body_params(q.mass * (1 + mass_change * sign),
                                      Eigen::Vector3d(q.com[0], q.com[1], q.com[2]) + shift, Ic);
      for (int s = 0; s < 10; ++s)
        out[static_cast<std::size_t>(index[s])] = values[static_cast<std::size_t>(s)];
    }
    return out;
  }

  // Torques of the truth at random states, noise of `noise` N m, and their least-squares fit.
  void simulate(std::mt19937& rng, double noise_std) {
    const int dof = model_->dof(), b = model_->num_base_params(), states = 600;
    std::uniform_real_distribution<double> angle(-3, 3), speed(-2, 2), acceleration(-6, 6);
    std::normal_distribution<double> noise(0, noise_std);
    W_.resize(dof * states, b);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(dof, b);
    const Eigen::VectorXd beta_true = K_ * truth_;
    for (int s = 0; s < states; ++s) {
      Eigen::VectorXd q(dof), dq(dof), ddq(dof);
      for (int j = 0; j < dof; ++j)
        q[j] = angle(rng), dq[j] = speed(rng), ddq[j] = acceleration(rng);
      model_->regressor(q.data(), dq.data(), ddq.data(), rows.data());
      W_.middleRows(s * dof, dof) = rows;
    }
    tau_ = W_ * beta_true;
    for (Eigen::Index i = 0; i < tau_.size(); ++i) tau_[i] += noise(rng);
    beta_hat_ = W_.colPivHouseholderQr().solve(tau_);
    sigma2_ = (tau_ - W_ * beta_hat_).squaredNorm() / static_cast<double>(tau_.size() - b);
    information_ = W_.transpose() * W_ / sigma2_;
    std_dev_ = information_.inverse().diagonal().cwiseSqrt();
  }

  double rel_error_norm(const Eigen::VectorXd& beta) const {
    return (tau_ - W_ * beta).norm() / tau_.norm();
  }

  // The least-squares cost of `beta` in sigma^2 units, from the simulated torques.
  double weighted_squares(const Eigen::VectorXd& beta) const {
    return (tau_ - W_ * beta).squaredNorm() / sigma2_;
  }

  PhysicalFitOptions with_residual() const {
    PhysicalFitOptions options;
    options.residual_sum_of_squares = weighted_squares(beta_hat_);
    return options;
  }

  PhysicalFitResult fit_with_weight(double weight) const {
    PhysicalFitOptions options = with_residual();
    options.prior_weight = weight;
    return fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_, options);
  }

  RobotModel robot_;
  std::unique_ptr<ReferenceModel> model_;
  Eigen::MatrixXd K_, W_, information_;
  Eigen::VectorXd truth_, tau_, beta_hat_, std_dev_;
  double sigma2_ = 1;
  std::vector<std::optional<double>> a_priori_;
};

// Every moving link of `standard` near the truth that made the data: mass within [0.6, 1.67]
// times the truth's, centre of mass within 8 cm.
void expect_links_near(const RigidBodyTree& tree, const Eigen::VectorXd& standard,
                       const Eigen::VectorXd& truth) {
  for (const auto& index : inertial_param_indices(tree)) {
    if (index[0] < 0) continue;
    double p[10], t[10];
    for (int s = 0; s < 10; ++s) p[s] = standard[index[s]], t[s] = truth[index[s]];
    const LinkQuantities got = link_quantities(p), want = link_quantities(t);
    const auto body =
        static_cast<std::size_t>(tree.params[static_cast<std::size_t>(index[9])].body);
    const std::string& name = tree.bodies[body].name;
    EXPECT_GE(got.mass, 0.6 * want.mass) << name;
    EXPECT_LE(got.mass, 1.67 * want.mass) << name;
    const double distance = (Eigen::Vector3d(got.com[0], got.com[1], got.com[2]) -
                             Eigen::Vector3d(want.com[0], want.com[1], want.com[2]))
                                .norm();
    EXPECT_LE(distance, 0.08) << name;
  }
}

// The default rule's bound, computed here from the simulated torques: with weight w the
// weighted sum of squares ||tau - W beta_w||^2 / sigma^2 exceeds that of the estimate with
// weight 1e-6 (consistency alone) by at most 0.0404 times the unconstrained fit's (the rms
// residual grows by at most 2 % of the unconstrained fit's), and the next larger weight of the
// ladder 1, 0.1, ..., 1e-4 exceeds it (the rule takes the largest that keeps the bound).
TEST_F(PhysicalPrior, TheDefaultWeightKeepsLinksNearTheTruthAndTheFitsCost) {
  const PhysicalFitResult reference = fit_with_weight(1e-6);
  const PhysicalFitOptions options = with_residual();
  const PhysicalFitResult fit =
      fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_, options);
  ASSERT_TRUE(fit.converged);
  EXPECT_TRUE(fit.prior_weight_automatic);
  EXPECT_GT(fit.prior_weight, 1e-6);  // the a-priori model pulls harder than the reference
  const double allowed = (1.02 * 1.02 - 1) * weighted_squares(beta_hat_);
  EXPECT_LE(weighted_squares(fit.base) - weighted_squares(reference.base), allowed * (1 + 1e-6))
      << "weight " << fit.prior_weight;
  if (fit.prior_weight < 1) {
    const PhysicalFitResult larger = fit_with_weight(10 * fit.prior_weight);
    EXPECT_GT(weighted_squares(larger.base) - weighted_squares(reference.base), allowed)
        << "weight " << fit.prior_weight;
  }
  std::cout << "default weight " << fit.prior_weight << ", relative error norm "
            << rel_error_norm(fit.base) << " (unconstrained " << rel_error_norm(beta_hat_)
            << ", consistency alone " << rel_error_norm(reference.base) << ")\n";
  EXPECT_LE(rel_error_norm(fit.base), 1.02 * rel_error_norm(beta_hat_));
  expect_links_near(robot_.tree, fit.standard, truth_);
}

TEST_F(PhysicalPrior, WithoutTheResidualTheRuleAllowsOneSigmaSquared) {
  // Without the unconstrained fit's sum of squares the rise may be 1 sigma^2, so no base
  // parameter moves by more than its standard deviation beyond consistency alone.
  const PhysicalFitResult reference = fit_with_weight(1e-6);
  const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_);
  ASSERT_TRUE(fit.converged);
  const double rise = weighted_squares(fit.base) - weighted_squares(reference.base);
  EXPECT_LE(rise, 1 + 1e-6) << "weight " << fit.prior_weight;
  for (Eigen::Index j = 0; j < beta_hat_.size(); ++j) {
    EXPECT_LE(std::abs(fit.base[j] - reference.base[j]), std_dev_[j])
        << model_->base_param_names()[static_cast<std::size_t>(j)];
  }
}

TEST_F(PhysicalPrior, ASumOfSquaresThatIsNotPositiveIsRefused) {
  for (double bad : {0.0, -1.0, std::nan("")}) {
    PhysicalFitOptions options;
    options.residual_sum_of_squares = bad;
    EXPECT_THROW(fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_, options),
                 EstimationError)
        << bad;
  }
}

TEST_F(PhysicalPrior, TheRuleTakesTheLargestWeightWithinItsBound) {
  // Smaller sums of squares given, so that the bound 0.0404 S0 bites on the ladder 1, 0.1, ...,
  // 1e-4: the rise (computed here from the torques) is within it, and the next larger weight's
  // is not; below the ladder the reference weight 1e-6 remains. A-priori values far off (masses
  // by +-60 %, centres of mass by 15 cm), so that the prior costs something.
  a_priori_ = perturbed_inertials(0.6, 0.15);
  const PhysicalFitResult reference = fit_with_weight(1e-6);
  const auto rise = [&](const PhysicalFitResult& f) {
    return weighted_squares(f.base) - weighted_squares(reference.base);
  };
  for (double allowed : {0.1, 1e-2, 1e-4}) {
    PhysicalFitOptions options;
    options.residual_sum_of_squares = allowed / (1.02 * 1.02 - 1);
    const PhysicalFitResult fit =
        fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_, options);
    ASSERT_TRUE(fit.converged);
    std::cout << "allowed rise " << allowed << ": weight " << fit.prior_weight << ", rise "
              << rise(fit) << "\n";
    EXPECT_LE(rise(fit), allowed * (1 + 1e-6)) << allowed;
    if (fit.prior_weight < 1) {
      const double next = fit.prior_weight == 1e-6 ? 1e-4 : 10 * fit.prior_weight;
      EXPECT_GT(rise(fit_with_weight(next)), allowed) << allowed;
    }
  }
}

TEST_F(PhysicalPrior, OnATruthInsideTheConsistentSetTheBaseFitStays) {
  // Bodies with 5 cm of radius of gyration added on every axis: the base parameters of the
  // default fit are the unconstrained ones to a fifth of their standard deviation. (The
  // log-det divergence acts on every direction of a body, not only on those the data leave
  // free as the local quadratic form did: at weight 1 it moves YY4R, XX6R and YY6 by 0.11 to
  // 0.17 of theirs here, against the a-priori masses 30 % off.)
  make(0.05 * 0.05, kNoise);
  const PhysicalFitResult fit =
      fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_, with_residual());
  ASSERT_TRUE(fit.converged);
  for (Eigen::Index j = 0; j < beta_hat_.size(); ++j) {
    EXPECT_LE(std::abs(fit.base[j] - beta_hat_[j]), 0.2 * std_dev_[j])
        << model_->base_param_names()[static_cast<std::size_t>(j)] << " weight "
        << fit.prior_weight;
  }
  EXPECT_LE(rel_error_norm(fit.base), 1.02 * rel_error_norm(beta_hat_));
  expect_links_near(robot_.tree, fit.standard, truth_);
}

TEST_F(PhysicalPrior, AGivenWeightIsUsedAndAnyWeightKeepsTheUnconstrainedOptimum) {
  // The prior acts only where the data do not: when the nearest standard set is already
  // consistent, the base estimate is the unconstrained one for a weight of 1 as for 1e-6.
  const std::vector<std::optional<double>> exact(truth_.data(), truth_.data() + truth_.size());
  const Eigen::VectorXd beta = K_ * truth_;
  for (double weight : {1e-6, 1.0}) {
    PhysicalFitOptions options;
    options.prior_weight = weight;
    const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta, information_, exact, options);
    EXPECT_EQ(fit.prior_weight, weight);
    EXPECT_FALSE(fit.prior_weight_automatic);
    EXPECT_LT(((fit.base - beta).cwiseQuotient(std_dev_)).cwiseAbs().maxCoeff(), 1e-3) << weight;
  }
}

TEST_F(PhysicalPrior, DriveValuesAloneAreNoAPrioriModel) {
  // Without a link's ten a-priori values the default is the small pull of weight 1e-6.
  std::vector<std::optional<double>> drives_only(a_priori_.size());
  for (std::size_t k = 0; k < drives_only.size(); ++k) {
    if (must_be_nonnegative(robot_.tree.params[k].kind))
      drives_only[k] = truth_[static_cast<Eigen::Index>(k)];
  }
  const PhysicalFitResult fit = fit_physical(robot_.tree, K_, beta_hat_, information_, drives_only);
  EXPECT_TRUE(fit.prior_weight_automatic);
  EXPECT_EQ(fit.prior_weight, 1e-6);
}

TEST_F(PhysicalPrior, TheLinkSummarySaysWhatTheDataDecided) {
  const PhysicalFitResult fit =
      fit_physical(robot_.tree, K_, beta_hat_, information_, a_priori_, with_residual());
  const std::vector<LinkSummary> links = summarise_links(robot_.tree, K_, fit, a_priori_);
  // The row space of K, computed here: a mass is decided by the data exactly when its unit
  // direction is a combination of K's rows (scaling each parameter does not change that).
  const Eigen::MatrixXd Kt = K_.transpose();
  const auto qr = Kt.colPivHouseholderQr();
  std::size_t body = 0, data_masses = 0, prior_masses = 0;
  for (const auto& index : inertial_param_indices(robot_.tree)) {
    if (index[0] < 0) continue;
    ASSERT_LT(body, links.size());
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(K_.cols(), index[9]);
    const bool in_row_space = (Kt * qr.solve(e) - e).norm() < 1e-6;
    EXPECT_EQ(links[body].mass_by == DecidedBy::kData, in_row_space) << links[body].body;
    (in_row_space ? data_masses : prior_masses) += 1;
    ASSERT_TRUE(links[body].a_priori.has_value());
    EXPECT_TRUE(links[body].far_from_a_priori.empty()) << links[body].body;
    ++body;
  }
  EXPECT_GT(prior_masses, 0u);  // a serial arm's masses are not all identifiable
}

TEST(LinkSummary, WarnsWhenALinkIsFarFromItsAPrioriValues) {
  const RobotModel robot = load_robot(test::source_path("robots/urdf/ur5.urdf"));
  const ReferenceModel model("ur5", robot.tree);
  PhysicalFitResult fit;
  fit.standard = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.tree.params.size()));
  for (std::size_t k = 0; k < robot.known_values.size(); ++k) {
    fit.standard[static_cast<Eigen::Index>(k)] = robot.known_values[k].value_or(0.5);
  }
  fit.prior_scale = Eigen::VectorXd::Ones(fit.standard.size());
  // Second moving body: 2.5 times the mass at the same centre of mass; third: the centre of
  // mass 15 cm away, mass and inertia about it unchanged.
  std::vector<std::array<int, 10>> bodies;
  for (const auto& index : inertial_param_indices(robot.tree)) {
    if (index[0] >= 0) bodies.push_back(index);
  }
  ASSERT_GE(bodies.size(), 3u);
  for (int s = 0; s < 10; ++s) fit.standard[bodies[1][s]] *= 2.5;
  double p[10];
  for (int s = 0; s < 10; ++s) p[s] = fit.standard[bodies[2][s]];
  const LinkQuantities q = link_quantities(p);
  Eigen::Matrix3d Ic;
  const auto& i = q.inertia_com;
  Ic << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
  const auto moved = body_params(q.mass, Eigen::Vector3d(q.com[0], q.com[1], q.com[2] + 0.15), Ic);
  for (int s = 0; s < 10; ++s) fit.standard[bodies[2][s]] = moved[static_cast<std::size_t>(s)];

  const auto links = summarise_links(robot.tree, regrouping_matrix(model), fit, robot.known_values);
  ASSERT_GE(links.size(), 3u);
  EXPECT_TRUE(links[0].far_from_a_priori.empty());
  ASSERT_EQ(links[1].far_from_a_priori.size(), 1u);
  EXPECT_NE(links[1].far_from_a_priori[0].find("mass 2.5 x"), std::string::npos)
      << links[1].far_from_a_priori[0];
  ASSERT_EQ(links[2].far_from_a_priori.size(), 1u);
  EXPECT_NE(links[2].far_from_a_priori[0].find("centre of mass 0.15 m"), std::string::npos)
      << links[2].far_from_a_priori[0];
}

TEST(DriveSummary, ARegroupedDriveParameterIsNotReportedAsIdentified) {
  // The TX-40 with rotor inertias: a drive parameter is decided by the data exactly when its
  // unit direction is a combination of the rows of K (computed here by QR); Ia1, about the
  // vertical first axis, only enters with ZZ1 (Gautier & Briot's ZZ1R).
  const RobotModel robot = load_robot(test::source_path("robots/tx40.yaml"));
  const ReferenceModel model("tx40", robot.tree);
  const Eigen::MatrixXd K = regrouping_matrix(model);
  PhysicalFitResult fit;
  const auto n = static_cast<Eigen::Index>(robot.tree.params.size());
  fit.standard = Eigen::VectorXd::Constant(n, 0.5);
  fit.prior_scale = Eigen::VectorXd::LinSpaced(n, 0.5, 2.0);  // any scales: the test says so
  const auto drives = summarise_drives(robot.tree, K, fit, robot.known_values);
  const Eigen::MatrixXd Kt = K.transpose();
  const auto qr = Kt.colPivHouseholderQr();
  std::size_t next = 0, data = 0, prior = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const StandardParam& param = robot.tree.params[static_cast<std::size_t>(k)];
    if (is_inertial(param.kind)) continue;
    ASSERT_LT(next, drives.size());
    const DriveSummary& drive = drives[next++];
    EXPECT_EQ(drive.name, param.name);
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, k);
    const bool in_row_space = (Kt * qr.solve(e) - e).norm() < 1e-6;
    EXPECT_EQ(drive.by == DecidedBy::kData, in_row_space) << drive.name;
    (in_row_space ? data : prior) += 1;
    if (drive.name == "Ia1") {
      EXPECT_EQ(drive.by, DecidedBy::kPrior);
      EXPECT_NE(std::find(drive.regrouped_with.begin(), drive.regrouped_with.end(), "ZZ1"),
                drive.regrouped_with.end());
      ASSERT_TRUE(drive.a_priori.has_value());
      EXPECT_EQ(*drive.a_priori, 0.362);  // robots/tx40.yaml's known: value
    }
    if (drive.name == "Fv2") {
      EXPECT_TRUE(drive.regrouped_with.empty());
    }
  }
  EXPECT_EQ(next, drives.size());
  EXPECT_GT(data, 0u);
  EXPECT_GT(prior, 0u);
}

}  // namespace
}  // namespace modelgen
