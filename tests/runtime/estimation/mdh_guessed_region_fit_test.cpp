// Issue 30, guessed regions of an MDH YAML arm enforced in the physically consistent fit: four
// joints and a tool frame, no `region:` and no a-priori values, so every link's region is the
// loader's guess from its DH rows. The truth that makes the data is each link a solid along its
// segment (inside the guess); torques at random states plus noise are fitted by least squares
// here. Without regions the fit puts some link's mass outside its guessed region; with them every
// link's extent (computed here from the pseudo-inertia) is at most 1, so each link's centre of
// mass stays inside its region, within the region's size of the truth's, at the unconstrained
// fit's error (within 2 %).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/region_fit.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using test::body_params;
using test::solid_box;
using test::solid_cylinder;

// Shoulder yaw and pitch at one point, elbow 0.4 m along x2, wrist 0.35 m along x3, a tool
// frame 0.1 m along z4.
constexpr const char* kArm = R"(name: guessed_arm
joints:
  - {name: J1, type: revolute, alpha: 0, d: 0, theta: 0, r: 0}
  - {name: J2, type: revolute, alpha: -pi/2, d: 0, theta: 0, r: 0}
  - {name: J3, type: revolute, alpha: 0, d: 0.4, theta: 0, r: 0}
  - {name: J4, type: revolute, alpha: pi/2, d: 0.35, theta: 0, r: 0}
  - {name: tool, type: fixed, alpha: 0, d: 0, theta: 0, r: 0.1}
)";

constexpr int kBodies = 5;

TEST(MdhGuessedRegionFit, GuessedRegionsKeepEveryLinkNearTheTruth) {
  const std::string path = (test::test_folder("mdh_region_fit") / "arm.yaml").string();
  test::write_text(path, kArm);
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.body_regions.size(), static_cast<std::size_t>(kBodies));
  for (const auto& region : robot.body_regions) {
    ASSERT_TRUE(region.has_value());
    EXPECT_TRUE(region->guessed);
  }
  const ReferenceModel model("guessed_arm", robot.tree);
  const Eigen::MatrixXd K = regrouping_matrix(model);
  // Each link a solid along its segment, in its own frame.
  const std::array<std::array<double, 10>, kBodies> links = {
      body_params(4.0, {0, 0, 0}, solid_cylinder(4.0, 0.06, 0.12, 2)),
      body_params(3.0, {0.2, 0, 0}, solid_box(3.0, {0.5, 0.08, 0.08})),
      body_params(1.5, {0.175, 0, 0}, solid_cylinder(1.5, 0.04, 0.4, 0)),
      body_params(0.5, {0, 0, 0.05}, solid_box(0.5, {0.08, 0.08, 0.1})),
      body_params(0.2, {0, 0, 0.02}, solid_box(0.2, {0.05, 0.05, 0.05}))};
  const auto indices = inertial_param_indices(robot.tree);
  ASSERT_EQ(indices.size(), static_cast<std::size_t>(kBodies));
  const auto n = static_cast<Eigen::Index>(robot.tree.params.size());
  Eigen::VectorXd truth = Eigen::VectorXd::Zero(n);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> drive(0.2, 1.0);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (must_be_nonnegative(robot.tree.params[static_cast<std::size_t>(k)].kind))
      truth[k] = drive(rng);
  }
  for (std::size_t b = 0; b < indices.size(); ++b) {
    for (int s = 0; s < 10; ++s) truth[indices[b][s]] = links[b][static_cast<std::size_t>(s)];
  }
  const test::SimulatedFit data = test::simulate_and_fit(model, K, truth, rng, 0.02);

  const std::vector<std::optional<double>> no_prior(static_cast<std::size_t>(n), std::nullopt);
  const PhysicalFitResult without =
      fit_physical(robot.tree, K, data.beta_hat, data.information, no_prior);
  PhysicalFitOptions options;
  options.regions = robot.body_regions;
  const PhysicalFitResult with =
      fit_physical(robot.tree, K, data.beta_hat, data.information, no_prior, options);
  ASSERT_TRUE(without.converged);
  ASSERT_TRUE(with.converged);

  double worst_without = 0;
  for (std::size_t b = 0; b < indices.size(); ++b) {
    const BodyRegion& region = *robot.body_regions[b];
    double p_truth[10], p_without[10], p_with[10];
    for (int s = 0; s < 10; ++s) {
      p_truth[s] = truth[indices[b][s]];
      p_without[s] = without.standard[indices[b][s]];
      p_with[s] = with.standard[indices[b][s]];
    }
    const double e_truth = test::extent(p_truth, region),
                 e_without = test::extent(p_without, region), e_with = test::extent(p_with, region);
    worst_without = std::max(worst_without, e_without);
    const auto com = [](const double* p) -> Eigen::Vector3d {
      return Eigen::Vector3d(p[6], p[7], p[8]) / p[9];
    };
    const Eigen::Vector3d semi(region.semi_axes[0], region.semi_axes[1], region.semi_axes[2]);
    const double com_error = (com(p_with) - com(p_truth)).norm();
    std::printf(
        "link %zu: extent truth %.3f, without the region %.3f, with it %.6f; mass %.3f "
        "(truth %.3f, without %.3g); centre of mass %.3f m from the truth's (without %.3g)\n",
        b + 1, e_truth, e_without, e_with, p_with[9], p_truth[9], p_without[9], com_error,
        (com(p_without) - com(p_truth)).norm());
    EXPECT_LT(e_truth, 0.7) << "link " << b + 1;  // the guess holds the truth
    EXPECT_LE(e_with, 1.0 + 1e-9) << "link " << b + 1;
    // Inside the region (Jensen: the centre of mass is inside when the extent is at most 1), so
    // within the region's diameter of the truth's, which is inside too.
    EXPECT_LT(com_error, 2 * semi.maxCoeff()) << "link " << b + 1;
    if (p_with[9] > 1e-6) {
      const Eigen::Vector3d c(region.centre[0], region.centre[1], region.centre[2]);
      EXPECT_LE((com(p_with) - c).cwiseQuotient(semi).squaredNorm(), 1 + 1e-9) << "link " << b + 1;
    }
  }
  EXPECT_GT(worst_without, 1.0);
  EXPECT_TRUE(with.rejected_region_bodies.empty());  // the truth is inside: the data agree
  const double unconstrained = data.rel_error_norm(data.beta_hat);
  const double constrained = data.rel_error_norm(with.base);
  std::printf("relative error norm: unconstrained %.6f, consistent in the guessed regions %.6f\n",
              unconstrained, constrained);
  EXPECT_LE(constrained, 1.02 * unconstrained);
}

}  // namespace
}  // namespace modelgen
