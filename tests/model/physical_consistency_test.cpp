// The pseudo-inertia and its log-Cholesky parametrisation against bodies built from point
// masses (whose second moment is a plain sum), and the consistency check against bodies whose
// physics is known: point masses and rods (equalities), broken triangle inequalities, negative
// masses and friction.

#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

struct PointMasses {
  std::vector<double> mass;
  std::vector<Eigen::Vector3d> position;
};

PointMasses random_point_masses(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> m(0.1, 5.0), x(-0.5, 0.5);
  PointMasses out;
  for (int i = 0; i < n; ++i) {
    out.mass.push_back(m(rng));
    out.position.emplace_back(x(rng), x(rng), x(rng));
  }
  return out;
}

// The ten inertial parameters of point masses, from the definitions: I_O = sum m (|r|^2 1 - r r').
Eigen::Matrix<double, 10, 1> inertial_of(const PointMasses& body) {
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  double m = 0;
  for (std::size_t i = 0; i < body.mass.size(); ++i) {
    const Eigen::Vector3d& r = body.position[i];
    I += body.mass[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    h += body.mass[i] * r;
    m += body.mass[i];
  }
  Eigen::Matrix<double, 10, 1> p;
  p << I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), h.x(), h.y(), h.z(), m;
  return p;
}

TEST(PseudoInertia, IsTheSecondMomentOfPointMasses) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const PointMasses body = random_point_masses(rng, 1 + trial % 6);
    Eigen::Matrix4d expected = Eigen::Matrix4d::Zero();
    for (std::size_t i = 0; i < body.mass.size(); ++i) {
      Eigen::Vector4d r;
      r << body.position[i], 1.0;
      expected += body.mass[i] * r * r.transpose();  // P = integral of [r; 1][r; 1]' dm
    }
    const Eigen::Matrix<double, 10, 1> p = inertial_of(body);
    EXPECT_LT((pseudo_inertia(p.data()) - expected).norm(), 1e-12 * expected.norm());
    Eigen::Matrix<double, 10, 1> back;
    inertial_from_pseudo_inertia(expected, back.data());
    EXPECT_LT((back - p).norm(), 1e-12 * p.norm());
  }
}

TEST(LogCholesky, RoundTripsAndCoversConsistentBodies) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix<double, 10, 1> theta;
    for (int k = 0; k < 10; ++k) theta[k] = n(rng);
    Eigen::Matrix<double, 10, 1> p;
    inertial_from_log_cholesky(theta.data(), p.data());
    // Every theta is a consistent body: its pseudo-inertia has a Cholesky factor.
    EXPECT_EQ(Eigen::LLT<Eigen::Matrix4d>(pseudo_inertia(p.data())).info(), Eigen::Success);
    const auto recovered = log_cholesky_from_inertial(p.data());
    ASSERT_TRUE(recovered.has_value());
    EXPECT_LT((*recovered - theta).norm(), 1e-9 * (1 + theta.norm())) << trial;
  }
  // Every body of four or more point masses in general position is some theta, and back.
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix<double, 10, 1> p = inertial_of(random_point_masses(rng, 4 + trial % 5));
    const auto theta = log_cholesky_from_inertial(p.data());
    ASSERT_TRUE(theta.has_value());
    Eigen::Matrix<double, 10, 1> again;
    inertial_from_log_cholesky(theta->data(), again.data());
    EXPECT_LT((again - p).norm(), 1e-12 * p.norm());
  }
  // An impossible body (negative mass) has none.
  Eigen::Matrix<double, 10, 1> negative_mass;
  negative_mass << 1, 0, 0, 1, 0, 1, 0, 0, 0, -1;
  EXPECT_FALSE(log_cholesky_from_inertial(negative_mass.data()).has_value());
}

class PhysicalViolations : public testing::Test {
 protected:
  void SetUp() override {
    model_ = load_robot(test::source_path("robots/tx40.yaml"));
    standard_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model_.tree.params.size()));
  }
  void set_body(int body, const Eigen::Matrix<double, 10, 1>& p) {
    const auto index = inertial_param_indices(model_.tree);
    for (int s = 0; s < 10; ++s) standard_[index[body][s]] = p[s];
  }
  RobotModel model_;
  Eigen::VectorXd standard_;
};

TEST_F(PhysicalViolations, AcceptPointMassesRodsAndMasslessBodies) {
  std::mt19937 rng(3);
  for (int b = 0; b < static_cast<int>(model_.tree.bodies.size()); ++b) {
    set_body(b, inertial_of(random_point_masses(rng, 1 + b)));  // 1 mass: a point, 2: a rod
  }
  EXPECT_TRUE(physical_violations(model_.tree, standard_).empty());
  set_body(2, Eigen::Matrix<double, 10, 1>::Zero());
  EXPECT_TRUE(physical_violations(model_.tree, standard_).empty());
}

TEST_F(PhysicalViolations, NameTheBodyAndTheCondition) {
  Eigen::Matrix<double, 10, 1> p;
  // Principal moments 1, 1, 3 about the centre of mass at the origin: 1 + 1 < 3.
  p << 1, 0, 0, 1, 0, 3, 0, 0, 0, 2;
  set_body(0, p);
  // A mass of -1 kg.
  p << 1, 0, 0, 1, 0, 1, 0, 0, 0, -1;
  set_body(3, p);
  // Positive definite about the origin but not about the centre of mass (0, 0, 1): the
  // parallel-axis term m c^2 = 2 exceeds XX = 1 (the KR150 link 4 of the old true.json).
  p << 1, 0, 0, 1, 0, 1, 0, 0, 2, 2;
  set_body(4, p);
  standard_[model_.param_index("Fv2")] = -0.5;
  const auto found = physical_violations(model_.tree, standard_);
  ASSERT_EQ(found.size(), 4u);
  EXPECT_EQ(found[0].parameter, "XX1");
  EXPECT_NE(found[0].condition.find("triangle inequality (1 + 1 < 3)"), std::string::npos)
      << found[0].condition;
  EXPECT_EQ(found[1].parameter, "M4");
  EXPECT_NE(found[1].condition.find("mass -1 kg is not positive"), std::string::npos);
  EXPECT_EQ(found[2].parameter, "XX5");
  EXPECT_NE(found[2].condition.find("not positive semidefinite"), std::string::npos);
  EXPECT_EQ(found[3].parameter, "Fv2");
  EXPECT_EQ(found[3].body, model_.tree.params[model_.param_index("Fv2")].body);
}

TEST_F(PhysicalViolations, RefuseMismatchedSizes) {
  EXPECT_THROW(physical_violations(model_.tree, Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

}  // namespace
}  // namespace modelgen
