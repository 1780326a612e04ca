// Issue 30, the region enforced in the physically consistent fit: a four-joint URDF arm with
// collision shapes and no inertials. The truth that makes the data is each link a solid of its
// own shape (well inside its region); the torques at random states plus noise are fitted by
// least squares here. The data cannot decide every inertial parameter and there is no
// a-priori model, so the fit without regions puts some link's mass outside the ellipsoid of
// its shapes; with them every link's extent, computed here from the pseudo-inertia, is at most
// 1, the links the bound holds are named and the others are not, and the torques are predicted
// within 2 % of the unconstrained fit's error.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/estimation/link_summary.hpp"
#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/region_fit.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// Shoulder yaw, shoulder pitch, elbow pitch, wrist roll; each link a box or cylinder.
constexpr const char* kArm = R"(<?xml version="1.0"?>
<robot name="region_arm">
  <link name="base"/>
  <link name="shoulder">
    <collision><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.08" length="0.2"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><origin xyz="0.2 0 0"/><geometry><box size="0.5 0.08 0.08"/></geometry></collision>
  </link>
  <link name="fore">
    <collision><origin xyz="0.175 0 0" rpy="0 1.5707963267948966 0"/>
      <geometry><cylinder radius="0.04" length="0.4"/></geometry></collision>
  </link>
  <link name="hand">
    <collision><origin xyz="0.04 0 0"/><geometry><box size="0.08 0.1 0.06"/></geometry></collision>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="shoulder"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="shoulder"/><child link="upper"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j3" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0.4 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j4" type="revolute"><parent link="fore"/><child link="hand"/>
    <origin xyz="0.35 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
</robot>
)";

using test::body_params;
using test::extent;
using test::solid_box;
using test::solid_cylinder;

class PhysicalRegion : public testing::Test {
 protected:
  void SetUp() override {
    const std::string path = (test::test_folder("physical_region") / "arm.urdf").string();
    test::write_text(path, kArm);
    robot_ = load_robot(path);
    model_ = std::make_unique<ReferenceModel>("region_arm", robot_.tree);
    K_ = regrouping_matrix(*model_);
    const auto n = static_cast<Eigen::Index>(robot_.tree.params.size());
    truth_ = Eigen::VectorXd::Zero(n);
    const std::array<std::array<double, 10>, 4> links = {
        body_params(4.0, {0, 0, 0.1}, solid_cylinder(4.0, 0.08, 0.2, 2)),
        body_params(3.0, {0.2, 0, 0}, solid_box(3.0, {0.5, 0.08, 0.08})),
        body_params(1.5, {0.175, 0, 0}, solid_cylinder(1.5, 0.04, 0.4, 0)),
        body_params(0.5, {0.04, 0, 0}, solid_box(0.5, {0.08, 0.1, 0.06}))};
    const auto indices = inertial_param_indices(robot_.tree);
    std::mt19937 rng(30);
    std::uniform_real_distribution<double> drive(0.2, 1.0);
    for (std::size_t b = 0; b < 4; ++b) {
      for (int s = 0; s < 10; ++s) truth_[indices[b][s]] = links[b][static_cast<std::size_t>(s)];
    }
    for (Eigen::Index k = 0; k < n; ++k) {
      if (must_be_nonnegative(robot_.tree.params[static_cast<std::size_t>(k)].kind))
        truth_[k] = drive(rng);
    }
    no_prior_.assign(static_cast<std::size_t>(n), std::nullopt);
    simulate(rng, 0.02);
  }

  // Torques of the truth at random states plus noise, and their least-squares fit.
  void simulate(std::mt19937& rng, double noise_std) {
    const test::SimulatedFit fit = test::simulate_and_fit(*model_, K_, truth_, rng, noise_std);
    W_ = fit.W;
    information_ = fit.information;
    tau_ = fit.tau;
    beta_hat_ = fit.beta_hat;
  }

  double rel_error_norm(const Eigen::VectorXd& beta) const {
    return (tau_ - W_ * beta).norm() / tau_.norm();
  }

  // Per moving body, its extent in its region.
  std::vector<double> extents(const Eigen::VectorXd& standard) const {
    std::vector<double> out;
    const auto indices = inertial_param_indices(robot_.tree);
    for (std::size_t b = 0; b < indices.size(); ++b) {
      double p[10];
      for (int s = 0; s < 10; ++s) p[s] = standard[indices[b][s]];
      out.push_back(extent(p, *robot_.body_regions[b]));
    }
    return out;
  }

  RobotModel robot_;
  std::unique_ptr<ReferenceModel> model_;
  Eigen::MatrixXd K_, W_, information_;
  Eigen::VectorXd truth_, tau_, beta_hat_;
  std::vector<std::optional<double>> no_prior_;
};

TEST_F(PhysicalRegion, TheTruthLiesInsideTheRegions) {
  ASSERT_EQ(robot_.body_regions.size(), 4u);
  for (const auto& region : robot_.body_regions) {
    ASSERT_TRUE(region.has_value());
    EXPECT_FALSE(region->guessed);
  }
  for (double e : extents(truth_)) EXPECT_LT(e, 0.6);
}

TEST_F(PhysicalRegion, TheRegionKeepsEveryLinkInsideAtTheSameFit) {
  const auto t0 = std::chrono::steady_clock::now();
  const PhysicalFitResult without =
      fit_physical(robot_.tree, K_, beta_hat_, information_, no_prior_);
  const auto t1 = std::chrono::steady_clock::now();
  PhysicalFitOptions options;
  options.regions = robot_.body_regions;
  const PhysicalFitResult with =
      fit_physical(robot_.tree, K_, beta_hat_, information_, no_prior_, options);
  const auto t2 = std::chrono::steady_clock::now();
  ASSERT_TRUE(without.converged);
  ASSERT_TRUE(with.converged);
  const std::vector<double> outside = extents(without.standard), inside = extents(with.standard);
  EXPECT_GT(*std::max_element(outside.begin(), outside.end()), 1.0);
  for (std::size_t b = 0; b < inside.size(); ++b) {
    std::printf("link %zu: extent without the region %.3f, with it %.6f\n", b + 1, outside[b],
                inside[b]);
    EXPECT_LE(inside[b], 1.0 + 1e-9) << robot_.tree.bodies[b].name;
  }
  const double unconstrained = rel_error_norm(beta_hat_), constrained = rel_error_norm(with.base);
  std::printf(
      "relative error norm: unconstrained %.6f, consistent in the regions %.6f (x%.5f); "
      "fit %.3f s without the regions, %.3f s with\n",
      unconstrained, constrained, constrained / unconstrained,
      std::chrono::duration<double>(t1 - t0).count(),
      std::chrono::duration<double>(t2 - t1).count());
  EXPECT_LE(constrained, 1.02 * unconstrained);

  // The bodies the region holds against the prior's pull outwards; the summary says the bound
  // decided what the data leave free of them, and names no other link so.
  ASSERT_FALSE(with.region_bound_bodies.empty());
  const std::vector<LinkSummary> links =
      summarise_links(robot_.tree, K_, with, no_prior_, robot_.body_regions);
  ASSERT_EQ(links.size(), 4u);
  for (std::size_t b = 0; b < links.size(); ++b) {
    const bool held = std::find(with.region_bound_bodies.begin(), with.region_bound_bodies.end(),
                                static_cast<int>(b)) != with.region_bound_bodies.end();
    const bool any_bound = links[b].mass_by == DecidedBy::kBound ||
                           links[b].com_by == DecidedBy::kBound ||
                           links[b].moments_by == DecidedBy::kBound;
    const bool any_prior = links[b].mass_by == DecidedBy::kPrior ||
                           links[b].com_by == DecidedBy::kPrior ||
                           links[b].moments_by == DecidedBy::kPrior;
    std::printf("link %s: held %d, mass by %s, com by %s, moments by %s\n", links[b].body.c_str(),
                held, decided_by_name(links[b].mass_by), decided_by_name(links[b].com_by),
                decided_by_name(links[b].moments_by));
    if (held) {
      EXPECT_GT(inside[b], 0.5) << links[b].body;  // pressed towards the edge
      EXPECT_FALSE(any_prior) << links[b].body;
    } else {
      EXPECT_FALSE(any_bound) << links[b].body;
    }
    ASSERT_TRUE(links[b].region_extent.has_value());
    EXPECT_NEAR(*links[b].region_extent, inside[b], 1e-9);
  }
  bool named = false;
  for (const std::string& c : with.active_constraints) {
    named = named || c.find("held by its region") != std::string::npos;
  }
  EXPECT_TRUE(named);
}

TEST_F(PhysicalRegion, LooseRegionsKeepTheBaseFit) {
  // Regions ten times larger than the shapes': the base estimate is the one without regions
  // (the regions move only what the data leave free).
  std::vector<std::optional<BodyRegion>> loose = robot_.body_regions;
  for (auto& region : loose) {
    for (double& s : region->semi_axes) s *= 10;
  }
  PhysicalFitOptions options;
  options.regions = loose;
  options.prior_weight = 1e-6;
  PhysicalFitOptions plain;
  plain.prior_weight = 1e-6;
  const PhysicalFitResult with =
      fit_physical(robot_.tree, K_, beta_hat_, information_, no_prior_, options);
  const PhysicalFitResult without =
      fit_physical(robot_.tree, K_, beta_hat_, information_, no_prior_, plain);
  const Eigen::VectorXd sd = information_.inverse().diagonal().cwiseSqrt();
  EXPECT_LT((with.base - without.base).cwiseQuotient(sd).cwiseAbs().maxCoeff(), 1e-3);
}

}  // namespace
}  // namespace modelgen
