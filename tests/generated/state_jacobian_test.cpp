// The checked-in inverse_dynamics_state_jacobian of one shipped robot (compiled from generated/)
// against central differences of the generated inverse_dynamics and of the numeric reference's
// inverse dynamics, on seeded random states away from the Coulomb friction jumps at dq = 0;
// its ddq block is the mass matrix (symmetric, positive definite); the float and Model forms
// agree. Linked into the same executable as numeric_diff_test.cpp.

#include <algorithm>
#include <cmath>
#include <functional>
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

// Torques as a function of the state x = [q, dq, ddq].
using TorqueFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd& x)>;

// d tau / d x by fourth-order central differences, step h in every coordinate.
Eigen::MatrixXd differences(const TorqueFunction& tau, const Eigen::VectorXd& x, double h) {
  const Eigen::Index n = tau(x).size();
  Eigen::MatrixXd J(n, x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    auto at = [&](double step) {
      Eigen::VectorXd shifted = x;
      shifted[k] += step;
      return tau(shifted);
    };
    J.col(k) = (8 * (at(h) - at(-h)) - (at(2 * h) - at(-2 * h))) / (12 * h);
  }
  return J;
}

class GeneratedStateJacobian : public testing::Test {
 protected:
  GeneratedStateJacobian()
      : description_(modelgen::load_robot(test::source_path(MODELGEN_ROBOT_DESCRIPTION))),
        reference_(description_.tree) {}

  // A random state whose joint velocities and motor velocities (K dq, for the Coulomb friction
  // of motors driving several joints) are all away from zero: |dq_i| >= 0.05 and
  // |(K dq)_m| >= 0.05 max_j |K_mj|, so the difference stencil (steps up to 2e-4 in one
  // coordinate) never crosses a velocity sign change.
  Eigen::VectorXd random_state(test::Random& random) const {
    const int n = model::kDof;
    const Eigen::Map<const RowMajor> K(model::kMotorFromJoint, n, n);
    Eigen::VectorXd x(3 * n);
    x << random.vector(n, -3.2, 3.2), random.vector(n, -3, 3), random.vector(n, -10, 10);
    for (;;) {
      for (int i = n; i < 2 * n; ++i) x[i] += x[i] < 0 ? -0.05 : 0.05;
      const Eigen::VectorXd motor = K * x.segment(n, n);
      bool away = true;
      for (int m = 0; m < n; ++m) {
        away = away && std::abs(motor[m]) >= 0.05 * K.row(m).lpNorm<Eigen::Infinity>();
      }
      if (away) return x;
      x.segment(n, n) = random.vector(n, -3, 3);
    }
  }

  RowMajor generated_jacobian(const Eigen::VectorXd& x, const std::vector<double>& beta) const {
    const int n = model::kDof;
    RowMajor J = RowMajor::Zero(n, 3 * n);  // zero entries are not written
    model::inverse_dynamics_state_jacobian(x.data(), x.data() + n, x.data() + 2 * n, beta.data(),
                                           J.data());
    return J;
  }

  modelgen::RobotModel description_;
  ReferenceDynamics reference_;
};

// max |a - b| / max(1, max |b|)
double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

TEST_F(GeneratedStateJacobian, EqualsDifferencesOfTheGeneratedInverseDynamics) {
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(606);
  std::vector<double> beta(nb);
  const TorqueFunction tau = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd t(n);
    model::inverse_dynamics(x.data(), x.data() + n, x.data() + 2 * n, beta.data(), t.data());
    return t;
  };
  double worst = 0;
  for (int s = 0; s < 2000; ++s) {
    const Eigen::VectorXd x = random_state(random);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    worst = std::max(worst,
                     relative_difference(generated_jacobian(x, beta), differences(tau, x, 1e-4)));
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": state Jacobian vs differences "
            << "of the generated inverse dynamics, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-6);
}

TEST_F(GeneratedStateJacobian, EqualsDifferencesOfTheNumericReference) {
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(707);
  std::vector<double> beta(nb);
  Eigen::VectorXd p;
  const TorqueFunction tau = [&](const Eigen::VectorXd& x) {
    return reference_.inverse_dynamics(x.head(n), x.segment(n, n), x.tail(n), p);
  };
  double worst = 0;
  for (int s = 0; s < 500; ++s) {
    const Eigen::VectorXd x = random_state(random);
    p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    worst = std::max(worst,
                     relative_difference(generated_jacobian(x, beta), differences(tau, x, 1e-4)));
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": state Jacobian vs differences "
            << "of the numeric reference, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-6);
}

TEST_F(GeneratedStateJacobian, AccelerationBlockIsTheMassMatrix) {
  // tau is linear in ddq with the joint-space inertia matrix M(q) (drive inertias included):
  // symmetric and, with physical parameters, positive definite.
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(808);
  std::vector<double> beta(nb);
  for (int s = 0; s < 1000; ++s) {
    const Eigen::VectorXd x = random_state(random);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    const Eigen::MatrixXd M = generated_jacobian(x, beta).rightCols(n);
    EXPECT_LT(relative_difference(M, M.transpose()), 1e-12);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(M).info(), Eigen::Success);
  }
}

TEST_F(GeneratedStateJacobian, FloatAndModelFormsAgree) {
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(909);
  std::vector<double> beta(nb), J2(n * 3 * n);
  std::vector<float> xf(3 * n), betaf(nb), Jf(n * 3 * n);
  for (int state = 0; state < 1000; ++state) {
    const Eigen::VectorXd x = random_state(random);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    const RowMajor J = generated_jacobian(x, beta);
    model::Model::inverse_dynamics_state_jacobian(x.data(), x.data() + n, x.data() + 2 * n,
                                                  beta.data(), J2.data());
    // The same function: the same doubles.
    EXPECT_EQ(std::vector<double>(J.data(), J.data() + J.size()), J2);
    // The float variant at the inputs rounded to float, against double at those inputs.
    Eigen::VectorXd xr(3 * n);
    std::vector<double> betar(nb);
    for (int k = 0; k < 3 * n; ++k) xf[k] = static_cast<float>(x[k]), xr[k] = xf[k];
    for (int k = 0; k < nb; ++k) betaf[k] = static_cast<float>(beta[k]), betar[k] = betaf[k];
    model::inverse_dynamics_state_jacobian(xf.data(), xf.data() + n, xf.data() + 2 * n,
                                           betaf.data(), Jf.data());
    const Eigen::MatrixXd J_float =
        Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            Jf.data(), n, 3 * n)
            .cast<double>();
    EXPECT_LT(relative_difference(J_float, generated_jacobian(xr, betar)), 1e-4);
  }
}

}  // namespace
}  // namespace modelgen
