// The reference drive model (Swevers 2002 eq. 5-12) on the KR150: torques against an independent
// computation (full reference inverse dynamics with the drive terms zeroed, then eq. 10, eq. 8
// as written, branch chosen by the sign of tau_T dq_M, and eq. 7); the analytic Jacobian against
// Ceres automatic differentiation (1e-12) and central differences (1e-8); the adapter for
// generated drive models on a stand-in; bad drive chains.

#include "modelgen/ml/drive_model.hpp"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "modelgen/model/generated_format.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

struct Kr150 {
  modelgen::RobotModel description = modelgen::load_robot(test::source_path("robots/kr150.yaml"));
  DriveChain drive() const {
    DriveChain t = DriveChain::identity(description.dof());
    t.motor_from_joint = description.drives.motor_from_joint;
    return t;
  }
};

// theta: inertial parameters from physical random values, JM, Rv, Rc in [0.5, 2], Rz in
// [0.7, 0.95].
Eigen::VectorXd random_theta(const Kr150& robot, const ReferenceDriveModel& model,
                             test::Random& random) {
  const Eigen::VectorXd p = test::random_physical_parameters(robot.description.tree, random);
  std::map<std::string, double> by_name;
  for (size_t k = 0; k < robot.description.tree.params.size(); ++k) {
    by_name[robot.description.tree.params[k].name] = p[static_cast<Eigen::Index>(k)];
  }
  Eigen::VectorXd theta(model.num_params());
  for (int k = 0; k < model.num_params(); ++k) {
    const std::string& name = model.param_names()[k];
    if (by_name.count(name) != 0) {
      theta[k] = by_name[name];
    } else if (name.compare(0, 2, "Rz") == 0) {
      theta[k] = random.uniform(0.7, 0.95);
    } else {
      theta[k] = random.uniform(0.5, 2.0);
    }
  }
  return theta;
}

struct States {
  Eigen::MatrixXd q, dq, ddq;
};

States random_states(const Kr150& robot, test::Random& random, int count) {
  States out{Eigen::MatrixXd(count, 6), Eigen::MatrixXd(count, 6), Eigen::MatrixXd(count, 6)};
  for (int s = 0; s < count; ++s) {
    const test::JointState x = test::random_state(robot.description, random);
    out.q.row(s) = x.q.transpose();
    out.dq.row(s) = x.dq.transpose();
    out.ddq.row(s) = x.ddq.transpose();
  }
  return out;
}

TEST(ReferenceDriveModel, ParameterNames) {
  const Kr150 robot;
  const ReferenceDriveModel model(robot.description.tree, robot.drive());
  const auto& names = model.param_names();
  ASSERT_EQ(model.num_params(), 70 + 24);
  EXPECT_EQ(names[0], "XX1");
  EXPECT_EQ(names[69], "M7");
  EXPECT_EQ(names[70], "JM1");
  EXPECT_EQ(names[73], "Rz1");
  EXPECT_EQ(names[93], "Rz6");
}

TEST(ReferenceDriveModel, TorqueMatchesAnIndependentComputation) {
  const Kr150 robot;
  ReferenceDriveModel model(robot.description.tree, robot.drive());
  test::Random random(11);
  const States x = random_states(robot, random, 50);
  model.set_samples(x.q, x.dq, x.ddq);
  const ReferenceDynamics full(robot.description.tree);
  const Eigen::MatrixXd K = robot.description.drives.motor_from_joint;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd theta = random_theta(robot, model, random);
    std::map<std::string, double> by_name;
    for (int k = 0; k < model.num_params(); ++k) by_name[model.param_names()[k]] = theta[k];
    Eigen::VectorXd p = Eigen::VectorXd::Zero(full.num_params());  // Ia, Fv, Fc, OFF stay 0
    for (int k = 0; k < full.num_params(); ++k) {
      const auto found = by_name.find(full.tree().params[k].name);
      if (found != by_name.end()) p[k] = found->second;
    }
    for (int s = 0; s < 50; ++s) {
      const Eigen::VectorXd tau_G = full.inverse_dynamics(
          x.q.row(s).transpose(), x.dq.row(s).transpose(), x.ddq.row(s).transpose(), p);
      const Eigen::VectorXd tau_pg = K.transpose().partialPivLu().solve(tau_G);  // eq. 10
      const Eigen::VectorXd dq_M = K * x.dq.row(s).transpose(),
                            ddq_M = K * x.ddq.row(s).transpose();
      Eigen::VectorXd tau(6);
      model.torque(s, theta.data(), tau.data());
      for (int i = 0; i < 6; ++i) {
        const std::string j = std::to_string(i + 1);
        const double Rz = by_name["Rz" + j];
        // Eq. 8 as written: tau'_G = tau_T Rz when tau_T dq_M > 0, else tau_T / Rz.
        double tau_T = tau_pg[i] / Rz;
        if (!(tau_T * dq_M[i] > 0)) tau_T = tau_pg[i] * Rz;
        const double expected = tau_T + by_name["JM" + j] * ddq_M[i] + by_name["Rv" + j] * dq_M[i] +
                                by_name["Rc" + j] * (dq_M[i] > 0 ? 1 : -1);
        EXPECT_NEAR(tau[i], expected, 1e-10 * std::max(1.0, std::abs(expected))) << s << " " << i;
      }
    }
  }
}

TEST(ReferenceDriveModel, JacobianMatchesAutodiffAndCentralDifferences) {
  const Kr150 robot;
  ReferenceDriveModel model(robot.description.tree, robot.drive());
  test::Random random(12);
  const int samples = 20;
  const States x = random_states(robot, random, samples);
  model.set_samples(x.q, x.dq, x.ddq);
  const int P = model.num_params();
  constexpr int kP = 94;
  ASSERT_EQ(P, kP);
  using Jet = ceres::Jet<double, kP>;
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd theta = random_theta(robot, model, random);
    std::vector<Jet> theta_jet(P);
    for (int k = 0; k < P; ++k) theta_jet[k] = Jet(theta[k], k);
    for (int s = 0; s < samples; ++s) {
      std::vector<double> tau(6), J(6 * P);
      model.torque_jacobian(s, theta.data(), tau.data(), J.data());
      std::vector<Jet> tau_jet(6);
      model.evaluate(s, theta_jet.data(), tau_jet.data());
      for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(tau[i], tau_jet[i].a, 1e-12 * std::max(1.0, std::abs(tau[i])));
        double row_scale = 1;
        for (int k = 0; k < P; ++k) row_scale = std::max(row_scale, std::abs(J[i * P + k]));
        for (int k = 0; k < P; ++k) {
          EXPECT_NEAR(J[i * P + k], tau_jet[i].v[k], 1e-12 * row_scale)
              << s << " " << i << " " << k;
        }
      }
      // Central differences: relative step 1e-6; eq. 8 switches only when tau'_G changes sign,
      // which random states keep far from.
      for (int k = 0; k < P; ++k) {
        const double h = 1e-6 * std::max(1.0, std::abs(theta[k]));
        Eigen::VectorXd plus = theta, minus = theta;
        plus[k] += h;
        minus[k] -= h;
        std::vector<double> fp(6), fm(6);
        model.torque(s, plus.data(), fp.data());
        model.torque(s, minus.data(), fm.data());
        for (int i = 0; i < 6; ++i) {
          const double fd = (fp[i] - fm[i]) / (2 * h);
          EXPECT_NEAR(J[i * P + k], fd, 1e-8 * std::max(1.0, std::abs(tau[i])))
              << s << " " << i << " " << model.param_names()[k];
        }
      }
    }
  }
}

// A stand-in for generated code with the drive-model interface, computed by a reference model.
// Its "drive regressor" holds the index of the sample whose q, dq, ddq it was given (-1 for an
// unknown state) and leaves every other entry unwritten; the functions given it check that
// those entries are zero (the adapter's buffer is zero-filled) and answer with the reference's
// values for that sample, NaN otherwise.
struct FakeGenerated {
  static constexpr int kFormatVersion = kGeneratedFormatVersion;
  static constexpr int kDof = 6;
  static constexpr int kDriveParams = 94;
  static constexpr int kDriveRegressorEntries = 9;  // any length: the adapter's stride
  static const ReferenceDriveModel* reference;
  static const char* const* drive_param_names() {
    static std::vector<const char*> names;
    if (names.empty()) {
      for (const std::string& name : reference->param_names()) names.push_back(name.c_str());
    }
    return names.data();
  }
  static const States* states;
  static std::vector<const double*> written;  // where drive_regressor wrote each sample's Y
  static void drive_regressor(const double* q, const double* dq, const double* ddq, double* Y) {
    written.push_back(Y);
    Y[0] = -1;
    for (Eigen::Index s = 0; s < states->q.rows(); ++s) {
      if (states->q.row(s) == Eigen::Map<const Eigen::RowVectorXd>(q, kDof) &&
          states->dq.row(s) == Eigen::Map<const Eigen::RowVectorXd>(dq, kDof) &&
          states->ddq.row(s) == Eigen::Map<const Eigen::RowVectorXd>(ddq, kDof)) {
        Y[0] = static_cast<double>(s);
      }
    }
  }
  // The sample of Y, or -1 when Y is not what drive_regressor wrote into a zeroed buffer.
  static Eigen::Index sample(const double* Y) {
    for (int k = 1; k < kDriveRegressorEntries; ++k) {
      if (Y[k] != 0) return -1;
    }
    return static_cast<Eigen::Index>(Y[0]);
  }
  static void drive_torque_given_regressor(const double* Y, const double* theta, double* tau) {
    const Eigen::Index s = sample(Y);
    if (s < 0) {
      std::fill(tau, tau + kDof, std::nan(""));
      return;
    }
    reference->torque(s, theta, tau);
  }
  static void drive_torque_jacobian_given_regressor(const double* Y, const double* theta,
                                                    double* tau_M, double* J) {
    const Eigen::Index s = sample(Y);
    if (s < 0) {
      std::fill(tau_M, tau_M + kDof, std::nan(""));
      std::fill(J, J + kDof * kDriveParams, std::nan(""));
      return;
    }
    reference->torque_jacobian(s, theta, tau_M, J);
  }
};
const ReferenceDriveModel* FakeGenerated::reference = nullptr;
const States* FakeGenerated::states = nullptr;
std::vector<const double*> FakeGenerated::written;

TEST(GeneratedDriveModel, AdapterPassesEachSamplesStateAndParameters) {
  const Kr150 robot;
  ReferenceDriveModel reference(robot.description.tree, robot.drive());
  test::Random random(13);
  const States x = random_states(robot, random, 7);
  reference.set_samples(x.q, x.dq, x.ddq);
  FakeGenerated::reference = &reference;
  FakeGenerated::states = &x;
  GeneratedDriveModel<FakeGenerated> adapter;
  EXPECT_EQ(adapter.param_names(), reference.param_names());
  FakeGenerated::written.clear();
  adapter.set_samples(x.q, x.dq, x.ddq);
  ASSERT_EQ(adapter.num_samples(), 7);
  // One packed Y per sample, kDriveRegressorEntries apart (not the dense kDof x kDriveParams).
  ASSERT_EQ(FakeGenerated::written.size(), 7u);
  for (std::size_t s = 1; s < 7; ++s) {
    EXPECT_EQ(FakeGenerated::written[s] - FakeGenerated::written[s - 1],
              FakeGenerated::kDriveRegressorEntries);
  }
  const Eigen::VectorXd theta = random_theta(robot, reference, random);
  for (int s = 0; s < 7; ++s) {
    std::vector<double> a(6), b(6), c(6), Ja(6 * 94), Jb(6 * 94);
    adapter.torque_jacobian(s, theta.data(), a.data(), Ja.data());
    adapter.torque(s, theta.data(), c.data());
    reference.torque_jacobian(s, theta.data(), b.data(), Jb.data());
    EXPECT_EQ(a, b);
    EXPECT_EQ(c, b);
    EXPECT_EQ(Ja, Jb);
  }
  EXPECT_THROW(adapter.set_samples(x.q, x.dq.topRows(3), x.ddq), std::invalid_argument);
}

TEST(ReferenceDriveModel, BadDriveChains) {
  const Kr150 robot;
  DriveChain singular = robot.drive();
  singular.motor_from_joint.row(5) = singular.motor_from_joint.row(4);
  try {
    ReferenceDriveModel model(robot.description.tree, singular);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("singular (rank 5 of 6)"), std::string::npos)
        << error.what();
  }
  DriveChain wrong = DriveChain::identity(5);
  EXPECT_THROW(ReferenceDriveModel(robot.description.tree, wrong), std::invalid_argument);
  ReferenceDriveModel model(robot.description.tree, robot.drive());
  EXPECT_THROW(model.set_samples(Eigen::MatrixXd::Zero(3, 6), Eigen::MatrixXd::Zero(3, 5),
                                 Eigen::MatrixXd::Zero(3, 6)),
               std::invalid_argument);
}

}  // namespace
}  // namespace modelgen
