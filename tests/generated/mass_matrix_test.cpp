// The checked-in mass_matrix of one shipped robot (compiled from generated/) against the
// numeric reference's M(q) on 10 000 seeded random states: column k is the reference inverse
// dynamics at zero velocity, zero gravity and unit acceleration e_k, minus the same at zero
// acceleration. At rest the friction terms are zero (sign(0) = 0, viscous terms vanish with
// dq), so that difference removes exactly the torque offsets and leaves M e_k. Linked into the
// same executable as numeric_diff_test.cpp.

#include <algorithm>
#include <iostream>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include MODELGEN_ROBOT_HEADER
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace model = ::modelgen::MODELGEN_ROBOT_NAMESPACE;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowMajorFloat = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Random states per comparison; fewer in the sanitizer build (tests/CMakeLists.txt).
#ifdef MODELGEN_TEST_STATES
constexpr int kStates = MODELGEN_TEST_STATES;
#else
constexpr int kStates = 10000;
#endif

RigidBodyTree without_gravity(RigidBodyTree tree) {
  tree.gravity = {0, 0, 0};
  return tree;
}

class GeneratedMassMatrix : public testing::Test {
 protected:
  GeneratedMassMatrix()
      : description_(load_robot(test::source_path(MODELGEN_ROBOT_DESCRIPTION))),
        reference_(without_gravity(description_.tree)) {}

  Eigen::MatrixXd reference_mass_matrix(const Eigen::VectorXd& q, const Eigen::VectorXd& p) const {
    const int n = model::kDof;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    const Eigen::VectorXd at_rest = reference_.inverse_dynamics(q, zero, zero, p);
    Eigen::MatrixXd M(n, n);
    for (int k = 0; k < n; ++k) {
      M.col(k) = reference_.inverse_dynamics(q, zero, Eigen::VectorXd::Unit(n, k), p) - at_rest;
    }
    return M;
  }

  RobotModel description_;
  ReferenceDynamics reference_;  // without gravity
};

TEST_F(GeneratedMassMatrix, EqualsTheReferenceOnRandomStates) {
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(4242);
  std::vector<double> beta(nb), s(n), c(n);
  // Zeroed once: generated functions leave the entries that are zero for every input unwritten.
  RowMajor M = RowMajor::Zero(n, n), M_sincos = M, M_struct = M;
  double worst = 0;
  for (int state = 0; state < kStates; ++state) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    model::mass_matrix(q.data(), beta.data(), M.data());
    const Eigen::MatrixXd expected = reference_mass_matrix(q, p);
    const double scale = std::max(1.0, expected.lpNorm<Eigen::Infinity>());
    worst = std::max(worst, (M - expected).lpNorm<Eigen::Infinity>() / scale);
    // The variant and the Model struct run the same statements: the same doubles.
    model::joint_sincos(q.data(), s.data(), c.data());
    model::mass_matrix_sincos(q.data(), s.data(), c.data(), beta.data(), M_sincos.data());
    model::Model::mass_matrix(q.data(), beta.data(), M_struct.data());
    EXPECT_EQ(M, M_sincos);
    EXPECT_EQ(M, M_struct);
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": worst relative difference "
            << "of the mass matrix " << worst << " over " << kStates << " states\n";
  EXPECT_LT(worst, 1e-12);
}

// mass_matrix_and_bias, forward dynamics' one call: M as the reference's columns above, and h
// the reference's inverse dynamics (with gravity, friction and offsets) at zero acceleration,
// on states with velocities of both signs.
TEST_F(GeneratedMassMatrix, AndBiasEqualTheReferenceOnRandomStates) {
  const int n = model::kDof, nb = model::kBaseParams;
  const ReferenceDynamics with_gravity(description_.tree);
  test::Random random(2828);
  std::vector<double> beta(nb);
  RowMajor M = RowMajor::Zero(n, n);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(n);
  double worst_M = 0, worst_h = 0;
  for (int state = 0; state < kStates; ++state) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2);
    const Eigen::VectorXd dq = random.vector(n, -3, 3);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    model::mass_matrix_and_bias(q.data(), dq.data(), beta.data(), M.data(), h.data());
    const Eigen::MatrixXd expected_M = reference_mass_matrix(q, p);
    const Eigen::VectorXd expected_h =
        with_gravity.inverse_dynamics(q, dq, Eigen::VectorXd::Zero(n), p);
    worst_M = std::max(worst_M, (M - expected_M).lpNorm<Eigen::Infinity>() /
                                    std::max(1.0, expected_M.lpNorm<Eigen::Infinity>()));
    worst_h = std::max(worst_h, (h - expected_h).lpNorm<Eigen::Infinity>() /
                                    std::max(1.0, expected_h.lpNorm<Eigen::Infinity>()));
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": mass_matrix_and_bias, worst "
            << "relative difference of M " << worst_M << ", of h " << worst_h << "\n";
  EXPECT_LT(worst_M, 1e-12);
  EXPECT_LT(worst_h, 1e-12);
}

TEST_F(GeneratedMassMatrix, IsSymmetricPositiveDefiniteAndFloatAgrees) {
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(77);
  std::vector<double> beta(nb);
  std::vector<float> qf(n), betaf(nb), Mf(n * n);
  RowMajor M = RowMajor::Zero(n, n);  // zeroed once: zero entries are not written
  for (int state = 0; state < 1000; ++state) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    model::mass_matrix(q.data(), beta.data(), M.data());
    const double scale = M.lpNorm<Eigen::Infinity>();
    EXPECT_LT((M - M.transpose()).lpNorm<Eigen::Infinity>(), 1e-12 * scale);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(M).info(), Eigen::Success) << "not positive definite";
    for (int i = 0; i < n; ++i) qf[i] = static_cast<float>(q[i]);
    for (int b = 0; b < nb; ++b) betaf[b] = static_cast<float>(beta[b]);
    model::mass_matrix(qf.data(), betaf.data(), Mf.data());
    const RowMajor M_float = Eigen::Map<const RowMajorFloat>(Mf.data(), n, n).cast<double>();
    EXPECT_LT((M_float - M).lpNorm<Eigen::Infinity>(), 1e-3 * scale);
  }
}

}  // namespace
}  // namespace modelgen
