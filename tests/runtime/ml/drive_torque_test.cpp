// The generated Swevers drive model F (eq. 12) of the KR150 (coupled wrist, V of eq. 11) and
// the TX-40 (gear ratios, coupled axes 5-6), compiled from generated/, against a numeric model
// written here: the reference standard regressor times p (eq. 1), then eq. 10, 8 and 7 by hand
// in Eigen, with eq. 8 as its two branches (and their mean at the switch). Its Jacobians against
// central differences of the generated drive_torque, against ceres::Jet automatic
// differentiation of the same numeric model templated on the scalar, and (state Jacobian)
// against central differences of the numeric model on the reference inverse dynamics.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ceres/jet.h>
#include <gtest/gtest.h>
#include <Eigen/Core>
#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include "kr150.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"
#include "tx40.hpp"

namespace modelgen {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <class T>
using Vector = Eigen::Matrix<T, Eigen::Dynamic, 1>;

struct Kr150 {
  using Model = ::modelgen::kr150::Model;
  static constexpr const char* kDescription = "robots/kr150.yaml";
  static constexpr const char* kManifest = "generated/kr150/kr150.json";
  static void drive_torque_float(const float* q, const float* dq, const float* ddq,
                                 const float* theta, float* tau_M) {
    ::modelgen::kr150::drive_torque(q, dq, ddq, theta, tau_M);
  }
  static void drive_torque_jacobian_float(const float* q, const float* dq, const float* ddq,
                                          const float* theta, float* tau_M, float* J) {
    ::modelgen::kr150::drive_torque_jacobian(q, dq, ddq, theta, tau_M, J);
  }
  static void drive_torque_state_jacobian_float(const float* q, const float* dq, const float* ddq,
                                                const float* theta, float* J) {
    ::modelgen::kr150::drive_torque_state_jacobian(q, dq, ddq, theta, J);
  }
  static void drive_regressor_float(const float* q, const float* dq, const float* ddq, float* Y) {
    ::modelgen::kr150::drive_regressor(q, dq, ddq, Y);
  }
  static void drive_torque_jacobian_given_regressor_float(const float* Y, const float* theta,
                                                          float* tau_M, float* J) {
    ::modelgen::kr150::drive_torque_jacobian_given_regressor(Y, theta, tau_M, J);
  }
};

struct Tx40 {
  using Model = ::modelgen::tx40::Model;
  static constexpr const char* kDescription = "robots/tx40.yaml";
  static constexpr const char* kManifest = "generated/tx40/tx40.json";
  static void drive_torque_float(const float* q, const float* dq, const float* ddq,
                                 const float* theta, float* tau_M) {
    ::modelgen::tx40::drive_torque(q, dq, ddq, theta, tau_M);
  }
  static void drive_torque_jacobian_float(const float* q, const float* dq, const float* ddq,
                                          const float* theta, float* tau_M, float* J) {
    ::modelgen::tx40::drive_torque_jacobian(q, dq, ddq, theta, tau_M, J);
  }
  static void drive_torque_state_jacobian_float(const float* q, const float* dq, const float* ddq,
                                                const float* theta, float* J) {
    ::modelgen::tx40::drive_torque_state_jacobian(q, dq, ddq, theta, J);
  }
  static void drive_regressor_float(const float* q, const float* dq, const float* ddq, float* Y) {
    ::modelgen::tx40::drive_regressor(q, dq, ddq, Y);
  }
  static void drive_torque_jacobian_given_regressor_float(const float* Y, const float* theta,
                                                          float* tau_M, float* J) {
    ::modelgen::tx40::drive_torque_jacobian_given_regressor(Y, theta, tau_M, J);
  }
};

// Eq. 7-10 on given rigid-body torques tau_G, templated for ceres::Jet. `drive` holds per joint
// JM, Rv, Rc, Rz (4 dof entries). Eq. 8 is taken as written, branch by branch.
template <class T>
Vector<T> motor_torques(const Eigen::MatrixXd& K, const Vector<T>& dq, const Vector<T>& ddq,
                        const Vector<T>& tau_G, const Vector<T>& drive, std::vector<int>* branch) {
  const Eigen::Index n = K.rows();
  const Eigen::MatrixXd K_inv_T = K.inverse().transpose();
  // Eq. 10: tau'_G = V^T tau_G with V = K^-1; eq. 9: motor motion.
  const Vector<T> tau_out = K_inv_T.cast<T>() * tau_G;
  const Vector<T> dq_M = K.cast<T>() * dq;
  const Vector<T> ddq_M = K.cast<T>() * ddq;
  Vector<T> tau_M(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const T& JM = drive[4 * i];
    const T& Rv = drive[4 * i + 1];
    const T& Rc = drive[4 * i + 2];
    const T& Rz = drive[4 * i + 3];
    // Eq. 8 solved for its input tau_T: motor driving (power > 0) or driven (power < 0).
    const T power = tau_out[i] * dq_M[i];
    T tau_T;
    int b = 0;
    if (power > T(0)) {
      tau_T = tau_out[i] / Rz;
      b = 1;
    } else if (power < T(0)) {
      tau_T = tau_out[i] * Rz;
      b = -1;
    } else {
      tau_T = (tau_out[i] / Rz + tau_out[i] * Rz) / T(2);
    }
    if (branch != nullptr) (*branch)[i] = b;
    const double sign = dq_M[i] > T(0) ? 1.0 : (dq_M[i] < T(0) ? -1.0 : 0.0);
    tau_M[i] = tau_T + JM * ddq_M[i] + Rv * dq_M[i] + Rc * T(sign);
  }
  return tau_M;
}

template <class Robot>
class DriveTorque : public testing::Test {
 protected:
  using Model = typename Robot::Model;
  static constexpr int n = Model::kDof;
  static constexpr int m = Model::kDriveParams;

  DriveTorque()
      : description_(modelgen::load_robot(test::source_path(Robot::kDescription))),
        reference_(description_.tree),
        K_(Eigen::Map<const RowMajor>(Model::motor_from_joint(), n, n)) {
    // theta's layout as documented: inertial standard parameters in tree order, then per
    // joint JM, Rv, Rc, Rz.
    for (std::size_t k = 0; k < description_.tree.params.size(); ++k) {
      if (is_inertial(description_.tree.params[k].kind)) inertial_.push_back(static_cast<int>(k));
    }
  }

  // The documented names, built from the description alone.
  std::vector<std::string> expected_names() const {
    std::vector<std::string> names;
    for (int k : inertial_) names.push_back(description_.tree.params[k].name);
    for (int i = 0; i < n; ++i) {
      for (std::size_t b = 0; b < description_.tree.bodies.size(); ++b) {
        if (description_.tree.bodies[b].dof_index != i) continue;
        for (const char* stem : {"JM", "Rv", "Rc", "Rz"}) {
          names.push_back(stem + std::to_string(b + 1));
        }
      }
    }
    return names;
  }

  // A physically consistent theta: random link inertials, rotor inertia, friction, efficiency.
  Eigen::VectorXd random_theta(test::Random& random) const {
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    Eigen::VectorXd theta(m);
    for (std::size_t k = 0; k < inertial_.size(); ++k) theta[k] = p[inertial_[k]];
    for (int i = 0; i < n; ++i) {
      const Eigen::Index at = static_cast<Eigen::Index>(inertial_.size()) + 4 * i;
      theta[at] = random.uniform(0.05, 2.0);      // JM
      theta[at + 1] = random.uniform(0.1, 5.0);   // Rv
      theta[at + 2] = random.uniform(0.5, 20);    // Rc
      theta[at + 3] = random.uniform(0.6, 0.98);  // Rz
    }
    return theta;
  }

  // The standard parameter vector of theta's inertial part, drive terms zero.
  Eigen::VectorXd standard(const Eigen::VectorXd& theta) const {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(reference_.num_params());
    for (std::size_t k = 0; k < inertial_.size(); ++k) p[inertial_[k]] = theta[k];
    return p;
  }

  Eigen::VectorXd drive_part(const Eigen::VectorXd& theta) const { return theta.tail(4 * n); }

  // The numeric model: reference regressor times p, then eq. 10, 8, 7.
  Eigen::VectorXd numeric(const Eigen::VectorXd& x, const Eigen::VectorXd& theta,
                          std::vector<int>* branch = nullptr) const {
    const Eigen::VectorXd tau_G =
        reference_.standard_regressor(x.head(n), x.segment(n, n), x.tail(n)) * standard(theta);
    return motor_torques<double>(K_, x.segment(n, n), x.tail(n), tau_G, drive_part(theta), branch);
  }

  Eigen::VectorXd generated(const Eigen::VectorXd& x, const Eigen::VectorXd& theta) const {
    Eigen::VectorXd tau(n);
    Model::drive_torque(x.data(), x.data() + n, x.data() + 2 * n, theta.data(), tau.data());
    return tau;
  }

  // d tau_M / d theta; `tau`, when not null, receives the torques the same call writes.
  RowMajor theta_jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& theta,
                          Eigen::VectorXd* tau = nullptr) const {
    RowMajor J = RowMajor::Zero(n, m);  // zero entries are not written
    Eigen::VectorXd tau_M(n);
    Model::drive_torque_jacobian(x.data(), x.data() + n, x.data() + 2 * n, theta.data(),
                                 tau_M.data(), J.data());
    if (tau != nullptr) *tau = tau_M;
    return J;
  }

  // The drive regressor Y of state x, dense (kDof x kDriveParams): drive_regressor's packed Y,
  // written into a zeroed buffer as a caller binding samples prepares it, placed by
  // kDriveRegressorIndex.
  RowMajor regressor(const Eigen::VectorXd& x) const {
    std::vector<double> packed(Model::kDriveRegressorEntries, 0.0);
    Model::drive_regressor(x.data(), x.data() + n, x.data() + 2 * n, packed.data());
    return unpacked(packed.data());
  }
  template <class T>
  using RowMajorOf = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  template <class T>
  static RowMajorOf<T> unpacked(const T* packed) {
    RowMajorOf<T> Y = RowMajorOf<T>::Zero(n, m);
    for (int p = 0; p < Model::kDriveRegressorEntries; ++p) {
      Y.data()[Model::drive_regressor_index()[p]] = packed[p];
    }
    return Y;
  }
  // The packed form of a dense Y, as the _given_regressor functions read it.
  static std::vector<double> packed(const RowMajor& Y) {
    std::vector<double> packed(Model::kDriveRegressorEntries);
    for (int p = 0; p < Model::kDriveRegressorEntries; ++p) {
      packed[p] = Y.data()[Model::drive_regressor_index()[p]];
    }
    return packed;
  }

  Eigen::VectorXd given_regressor(const RowMajor& Y, const Eigen::VectorXd& theta) const {
    Eigen::VectorXd tau = Eigen::VectorXd::Constant(n, std::nan(""));
    Model::drive_torque_given_regressor(packed(Y).data(), theta.data(), tau.data());
    return tau;
  }

  // d tau_M / d theta from Y into a zeroed J; `tau` (NaN-filled before the call) receives the
  // torques of the same call.
  RowMajor jacobian_given_regressor(const RowMajor& Y, const Eigen::VectorXd& theta,
                                    Eigen::VectorXd* tau = nullptr) const {
    RowMajor J = RowMajor::Zero(n, m);
    Eigen::VectorXd tau_M = Eigen::VectorXd::Constant(n, std::nan(""));
    Model::drive_torque_jacobian_given_regressor(packed(Y).data(), theta.data(), tau_M.data(),
                                                 J.data());
    if (tau != nullptr) *tau = tau_M;
    return J;
  }

  // ceres::Jet derivatives of the numeric model (reference regressor, eq. 7-10 by hand in
  // motor_torques) with respect to theta; `tau` receives its values.
  template <int kParams>
  RowMajor jet_jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& theta,
                        Eigen::VectorXd* tau = nullptr) const {
    using Jet = ceres::Jet<double, kParams>;
    Vector<Jet> theta_jet(m);
    for (int k = 0; k < m; ++k) theta_jet[k] = Jet(theta[k], k);
    // tau_G = W p is linear in the inertial parameters: Jets through the numeric regressor.
    const RowMajor W = reference_.standard_regressor(x.head(n), x.segment(n, n), x.tail(n));
    Vector<Jet> p(reference_.num_params());
    for (Eigen::Index k = 0; k < p.size(); ++k) p[k] = Jet(0.0);
    for (std::size_t k = 0; k < inertial_.size(); ++k) p[inertial_[k]] = theta_jet[k];
    const Vector<Jet> tau_G = W.cast<Jet>() * p;
    const Vector<Jet> tau_M =
        motor_torques<Jet>(K_, x.segment(n, n).cast<Jet>(), x.tail(n).cast<Jet>(), tau_G,
                           theta_jet.tail(4 * n), nullptr);
    RowMajor J(n, m);
    for (int i = 0; i < n; ++i) J.row(i) = tau_M[i].v.transpose();
    if (tau != nullptr) {
      tau->resize(n);
      for (int i = 0; i < n; ++i) (*tau)[i] = tau_M[i].a;
    }
    return J;
  }

  RowMajor state_jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& theta) const {
    RowMajor J = RowMajor::Zero(n, 3 * n);  // zero entries are not written
    Model::drive_torque_state_jacobian(x.data(), x.data() + n, x.data() + 2 * n, theta.data(),
                                       J.data());
    return J;
  }

  Eigen::VectorXd random_state(test::Random& random) const {
    Eigen::VectorXd x(3 * n);
    x << random.vector(n, -3.2, 3.2), random.vector(n, -3, 3), random.vector(n, -10, 10);
    return x;
  }

  // The sign pattern of the motor velocities and of the power flows tau'_G dq_M (generated
  // rigid-body torques: only a guard), -1/0/+1 per joint.
  std::vector<int> switches(const Eigen::VectorXd& x, const Eigen::VectorXd& theta) const {
    const Eigen::VectorXd p = standard(theta);
    Eigen::VectorXd tau_G(n);
    Model::base_from_standard(p.data(), beta_.data());
    Model::inverse_dynamics(x.data(), x.data() + n, x.data() + 2 * n, beta_.data(), tau_G.data());
    const Eigen::VectorXd tau_out = K_.inverse().transpose() * tau_G;
    const Eigen::VectorXd dq_M = K_ * x.segment(n, n);
    std::vector<int> pattern;
    for (int i = 0; i < n; ++i) {
      pattern.push_back(dq_M[i] > 0 ? 1 : -1);
      pattern.push_back(tau_out[i] * dq_M[i] > 0 ? 1 : -1);
    }
    return pattern;
  }

  // A state whose motor velocities and power flows keep their signs within a difference
  // stencil of half-width `reach` in every state coordinate, with every motor velocity at least
  // 0.05 (rad/s on the link side) times its row of K from zero.
  Eigen::VectorXd smooth_state(test::Random& random, const Eigen::VectorXd& theta,
                               double reach) const {
    for (;;) {
      Eigen::VectorXd x = random_state(random);
      const Eigen::VectorXd dq_M = K_ * x.segment(n, n);
      bool away = true;
      for (int i = 0; i < n; ++i) {
        away = away && std::abs(dq_M[i]) >= 0.05 * K_.row(i).lpNorm<Eigen::Infinity>();
      }
      if (!away) continue;
      const std::vector<int> here = switches(x, theta);
      for (int k = 0; k < 3 * n && away; ++k) {
        for (double step : {-reach, reach}) {
          Eigen::VectorXd shifted = x;
          shifted[k] += step;
          away = away && switches(shifted, theta) == here;
        }
      }
      if (away) return x;
    }
  }

  modelgen::RobotModel description_;
  ReferenceDynamics reference_;
  Eigen::MatrixXd K_;
  std::vector<int> inertial_;
  mutable std::vector<double> beta_ = std::vector<double>(Model::kBaseParams);
};

// max |a - b| / max(1, max |b|)
double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

// d f / d x by fourth-order central differences, step h[k] in coordinate k.
Eigen::MatrixXd differences(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                            const Eigen::VectorXd& x, const Eigen::VectorXd& h) {
  const Eigen::Index rows = f(x).size();
  Eigen::MatrixXd J(rows, x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    auto at = [&](double step) {
      Eigen::VectorXd shifted = x;
      shifted[k] += step;
      return f(shifted);
    };
    J.col(k) = (8 * (at(h[k]) - at(-h[k])) - (at(2 * h[k]) - at(-2 * h[k]))) / (12 * h[k]);
  }
  return J;
}

using Robots = testing::Types<Kr150, Tx40>;
TYPED_TEST_SUITE(DriveTorque, Robots);

TYPED_TEST(DriveTorque, ParameterNamesFollowTheDocumentedOrder) {
  using Model = typename TypeParam::Model;
  const std::vector<std::string> expected = this->expected_names();
  ASSERT_EQ(static_cast<int>(expected.size()), Model::kDriveParams);
  for (int k = 0; k < Model::kDriveParams; ++k) {
    EXPECT_EQ(Model::drive_param_names()[k], expected[k]) << "theta[" << k << "]";
  }
}

TYPED_TEST(DriveTorque, ManifestListsTheSameParameters) {
  using Model = typename TypeParam::Model;
  std::ifstream file(test::source_path(TypeParam::kManifest));
  std::stringstream text;
  text << file.rdbuf();
  const nlohmann::json manifest = nlohmann::json::parse(text.str());
  const std::vector<std::string> names = manifest.at("drive_parameters");
  ASSERT_EQ(static_cast<int>(names.size()), Model::kDriveParams);
  for (int k = 0; k < Model::kDriveParams; ++k) EXPECT_EQ(names[k], Model::drive_param_names()[k]);
}

// The packed layout: increasing dense indices, the manifest's too, and tight: each packed entry
// is non-zero at some random state unless the manifest lists it as never written. (That no
// dense entry left out is ever non-zero is DriveRegressorIsTheJacobianAtUnitEfficiency's
// comparison with the numeric model.)
TYPED_TEST(DriveTorque, PackedIndexMatchesTheManifestAndIsTight) {
  using Model = typename TypeParam::Model;
  constexpr int n = TestFixture::n, m = TestFixture::m;
  std::ifstream file(test::source_path(TypeParam::kManifest));
  std::stringstream text;
  text << file.rdbuf();
  const nlohmann::json manifest = nlohmann::json::parse(text.str());
  const std::vector<int> index = manifest.at("drive_regressor_index");
  ASSERT_EQ(static_cast<int>(index.size()), Model::kDriveRegressorEntries);
  ASSERT_LT(Model::kDriveRegressorEntries, n * m);
  for (int p = 0; p < Model::kDriveRegressorEntries; ++p) {
    EXPECT_EQ(Model::drive_regressor_index()[p], index[p]) << "p = " << p;
    EXPECT_GE(index[p], p == 0 ? 0 : index[p - 1] + 1) << "p = " << p;
    EXPECT_LT(index[p], n * m);
  }
  std::vector<int> unwritten;
  for (const nlohmann::json& function : manifest.at("functions")) {
    if (function.at("name") == "drive_regressor" && function.contains("unwritten")) {
      unwritten = function.at("unwritten").at("Y").get<std::vector<int>>();
    }
  }
  std::vector<bool> seen(Model::kDriveRegressorEntries, false);
  test::Random random(2402);
  for (int s = 0; s < 20; ++s) {
    const Eigen::VectorXd x = this->random_state(random);
    std::vector<double> Y(Model::kDriveRegressorEntries, 0.0);
    Model::drive_regressor(x.data(), x.data() + n, x.data() + 2 * n, Y.data());
    for (int p = 0; p < Model::kDriveRegressorEntries; ++p) seen[p] = seen[p] || Y[p] != 0.0;
  }
  for (int p = 0; p < Model::kDriveRegressorEntries; ++p) {
    const bool never_written = std::find(unwritten.begin(), unwritten.end(), p) != unwritten.end();
    EXPECT_NE(seen[p], never_written) << "packed entry " << p << " (dense " << index[p] << ")";
  }
}

TYPED_TEST(DriveTorque, EqualsTheNumericModelOnBothEfficiencyBranches) {
  constexpr int n = TestFixture::n;
  test::Random random(1201);
  std::vector<int> driving(n, 0), driven(n, 0), branch(n);
  double worst = 0;
  for (int s = 0; s < 1000; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->random_state(random);
    const Eigen::VectorXd expected = this->numeric(x, theta, &branch);
    worst = std::max(worst, test::relative_error(this->generated(x, theta), expected, 1.0));
    for (int i = 0; i < n; ++i) {
      driving[i] += branch[i] > 0;
      driven[i] += branch[i] < 0;
    }
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": drive_torque vs numeric model, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-12);
  for (int i = 0; i < n; ++i) {
    EXPECT_GT(driving[i], 100) << "joint " << i + 1 << ": motor-driving branch of eq. 8";
    EXPECT_GT(driven[i], 100) << "joint " << i + 1 << ": driven branch of eq. 8";
  }
}

// drive_torque_jacobian writes the residual's torques with the Jacobian (one call per sample
// in a least-squares fit): they are drive_torque's, and the numeric model's.
TYPED_TEST(DriveTorque, JacobianCallWritesTheTorquesOfTheNumericModel) {
  test::Random random(1377);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-3);
    Eigen::VectorXd tau;
    this->theta_jacobian(x, theta, &tau);
    const Eigen::VectorXd expected = this->numeric(x, theta);
    worst = std::max(worst, (tau - expected).norm() / expected.norm());
    EXPECT_LT((tau - this->generated(x, theta)).norm(), 1e-12 * expected.norm());
  }
  EXPECT_LT(worst, 1e-12);
}

TYPED_TEST(DriveTorque, UsesTheMeanOfBothBranchesAtTheSwitch) {
  constexpr int n = TestFixture::n;
  test::Random random(1301);
  std::vector<int> branch(n);
  // At rest the power flow is zero on every joint: tau_T = tau'_G (1/Rz + Rz) / 2, no friction.
  for (int s = 0; s < 20; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    Eigen::VectorXd x = this->random_state(random);
    x.segment(n, n).setZero();
    const Eigen::VectorXd expected = this->numeric(x, theta, &branch);
    EXPECT_EQ(std::count(branch.begin(), branch.end(), 0), n);
    EXPECT_LT(test::relative_error(this->generated(x, theta), expected, 1.0), 1e-12);
  }
}

TYPED_TEST(DriveTorque, FloatVariantAgreesWithDouble) {
  constexpr int n = TestFixture::n;
  test::Random random(1401);
  double worst = 0;
  for (int s = 0; s < 200; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-3);
    const Eigen::VectorXf xf = x.cast<float>(), thetaf = theta.cast<float>();
    Eigen::VectorXf tau(n);
    TypeParam::drive_torque_float(xf.data(), xf.data() + n, xf.data() + 2 * n, thetaf.data(),
                                  tau.data());
    worst =
        std::max(worst, test::relative_error(tau.cast<double>(), this->generated(x, theta), 1.0));
  }
  EXPECT_LT(worst, 1e-4);
}

TYPED_TEST(DriveTorque, FloatJacobiansAgreeWithDouble) {
  constexpr int n = TestFixture::n, m = TestFixture::m;
  using RowMajorF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  test::Random random(1451);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-3);
    const Eigen::VectorXf xf = x.cast<float>(), thetaf = theta.cast<float>();
    RowMajorF J = RowMajorF::Zero(n, m), S = RowMajorF::Zero(n, 3 * n);  // zeros unwritten
    Eigen::VectorXf tau(n);
    TypeParam::drive_torque_jacobian_float(xf.data(), xf.data() + n, xf.data() + 2 * n,
                                           thetaf.data(), tau.data(), J.data());
    TypeParam::drive_torque_state_jacobian_float(xf.data(), xf.data() + n, xf.data() + 2 * n,
                                                 thetaf.data(), S.data());
    worst = std::max(worst, relative_difference(J.cast<double>(), this->theta_jacobian(x, theta)));
    worst = std::max(worst, relative_difference(S.cast<double>(), this->state_jacobian(x, theta)));
  }
  EXPECT_LT(worst, 1e-4);
}

TYPED_TEST(DriveTorque, ParameterJacobianEqualsJetDerivativesOfTheNumericModel) {
  constexpr int n = TestFixture::n, m = TestFixture::m;
  using Jet = ceres::Jet<double, m>;
  test::Random random(1501);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-6);
    // tau_G = W p is linear in the inertial parameters: Jets through the numeric regressor.
    Vector<Jet> theta_jet(m);
    for (int k = 0; k < m; ++k) theta_jet[k] = Jet(theta[k], k);
    const RowMajor W = this->reference_.standard_regressor(x.head(n), x.segment(n, n), x.tail(n));
    Vector<Jet> p(this->reference_.num_params());
    for (Eigen::Index k = 0; k < p.size(); ++k) p[k] = Jet(0.0);
    for (std::size_t k = 0; k < this->inertial_.size(); ++k) p[this->inertial_[k]] = theta_jet[k];
    const Vector<Jet> tau_G = W.cast<Jet>() * p;
    const Vector<Jet> tau_M =
        motor_torques<Jet>(this->K_, x.segment(n, n).cast<Jet>(), x.tail(n).cast<Jet>(), tau_G,
                           theta_jet.tail(4 * n), nullptr);
    Eigen::MatrixXd expected(n, m);
    for (int i = 0; i < n; ++i) expected.row(i) = tau_M[i].v.transpose();
    worst = std::max(worst, relative_difference(this->theta_jacobian(x, theta), expected));
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": d tau_M / d theta vs ceres::Jet, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-12);
}

// With every efficiency Rz = 1 the drive model is linear in the other parameters, and Y is
// its regressor: Y equals the Jet derivatives of the numeric model there, Rz columns zero.
TYPED_TEST(DriveTorque, DriveRegressorIsTheJacobianAtUnitEfficiency) {
  constexpr int n = TestFixture::n, m = TestFixture::m;
  test::Random random(2101);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    Eigen::VectorXd theta = this->random_theta(random);
    for (int i = 0; i < n; ++i) theta[m - 4 * n + 4 * i + 3] = 1.0;  // Rz
    const Eigen::VectorXd x = this->random_state(random);
    const RowMajor Y = this->regressor(x);
    ASSERT_TRUE(Y.allFinite());
    Eigen::VectorXd tau;
    RowMajor expected = this->template jet_jacobian<m>(x, theta, &tau);
    for (int i = 0; i < n; ++i) expected.col(m - 4 * n + 4 * i + 3).setZero();
    worst = std::max(worst, relative_difference(Y, expected));
    // tau_M = Y theta at unit efficiency (the numeric model's value).
    EXPECT_LT(test::relative_error(Y * theta, tau, 1.0), 1e-12);
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": drive_regressor vs ceres::Jet at Rz = 1, worst relative difference " << worst
            << "\n";
  EXPECT_LT(worst, 1e-12);
}

// The torques from a sample's Y are the numeric model's (and drive_torque's) on both branches
// of eq. 8.
TYPED_TEST(DriveTorque, GivenRegressorEqualsTheNumericModel) {
  constexpr int n = TestFixture::n;
  test::Random random(2201);
  std::vector<int> driving(n, 0), driven(n, 0), branch(n);
  double worst = 0;
  for (int s = 0; s < 1000; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->random_state(random);
    const Eigen::VectorXd tau = this->given_regressor(this->regressor(x), theta);
    ASSERT_TRUE(tau.allFinite()) << "tau_M is not written";
    const Eigen::VectorXd expected = this->numeric(x, theta, &branch);
    worst = std::max(worst, test::relative_error(tau, expected, 1.0));
    EXPECT_LT(test::relative_error(tau, this->generated(x, theta), 1.0), 1e-12);
    for (int i = 0; i < n; ++i) {
      driving[i] += branch[i] > 0;
      driven[i] += branch[i] < 0;
    }
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": drive_torque_given_regressor vs numeric model, worst relative difference "
            << worst << "\n";
  EXPECT_LT(worst, 1e-12);
  for (int i = 0; i < n; ++i) {
    EXPECT_GT(driving[i], 100) << "joint " << i + 1 << ": motor-driving branch of eq. 8";
    EXPECT_GT(driven[i], 100) << "joint " << i + 1 << ": driven branch of eq. 8";
  }
}

// tau_M and J from a sample's Y against ceres::Jet derivatives of the numeric model and against
// drive_torque_jacobian on the state.
TYPED_TEST(DriveTorque, JacobianGivenRegressorEqualsJetDerivativesOfTheNumericModel) {
  constexpr int m = TestFixture::m;
  test::Random random(2301);
  double worst = 0, worst_tau = 0, worst_state_call = 0;
  for (int s = 0; s < 200; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-6);
    Eigen::VectorXd tau, tau_jet, tau_state;
    const RowMajor J = this->jacobian_given_regressor(this->regressor(x), theta, &tau);
    const RowMajor expected = this->template jet_jacobian<m>(x, theta, &tau_jet);
    ASSERT_TRUE(J.allFinite() && tau.allFinite());
    worst = std::max(worst, relative_difference(J, expected));
    worst_tau = std::max(worst_tau, test::relative_error(tau, tau_jet, 1.0));
    const RowMajor J_state = this->theta_jacobian(x, theta, &tau_state);
    worst_state_call = std::max({worst_state_call, relative_difference(J, J_state),
                                 test::relative_error(tau, tau_state, 1.0)});
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": drive_torque_jacobian_given_regressor vs ceres::Jet, worst relative difference "
            << worst << " (tau_M " << worst_tau << "); vs drive_torque_jacobian "
            << worst_state_call << "\n";
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_tau, 1e-12);
  EXPECT_LT(worst_state_call, 1e-12);
}

TYPED_TEST(DriveTorque, FloatGivenRegressorAgreesWithDouble) {
  constexpr int n = TestFixture::n, m = TestFixture::m;
  using RowMajorF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  test::Random random(2401);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-3);
    const Eigen::VectorXf xf = x.cast<float>(), thetaf = theta.cast<float>();
    std::vector<float> Y(TypeParam::Model::kDriveRegressorEntries, 0.0f);  // zeros are not written
    RowMajorF J = RowMajorF::Zero(n, m);
    Eigen::VectorXf tau(n);
    TypeParam::drive_regressor_float(xf.data(), xf.data() + n, xf.data() + 2 * n, Y.data());
    TypeParam::drive_torque_jacobian_given_regressor_float(Y.data(), thetaf.data(), tau.data(),
                                                           J.data());
    const Eigen::MatrixXd unpacked = TestFixture::unpacked(Y.data()).template cast<double>();
    worst = std::max(worst, relative_difference(unpacked, this->regressor(x)));
    worst = std::max(worst, relative_difference(J.cast<double>(), this->theta_jacobian(x, theta)));
  }
  EXPECT_LT(worst, 1e-4);
}

TYPED_TEST(DriveTorque, ParameterJacobianEqualsDifferencesOfTheGeneratedModel) {
  test::Random random(1601);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-6);
    const Eigen::VectorXd h = 1e-4 * theta.cwiseAbs().cwiseMax(1e-3);
    const auto f = [&](const Eigen::VectorXd& t) { return this->generated(x, t); };
    worst = std::max(worst,
                     relative_difference(this->theta_jacobian(x, theta), differences(f, theta, h)));
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": d tau_M / d theta vs differences, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-7);
}

TYPED_TEST(DriveTorque, StateJacobianEqualsDifferencesOfTheGeneratedModel) {
  constexpr int n = TestFixture::n;
  test::Random random(1701);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 2e-4);
    const auto f = [&](const Eigen::VectorXd& y) { return this->generated(y, theta); };
    worst = std::max(
        worst, relative_difference(this->state_jacobian(x, theta),
                                   differences(f, x, Eigen::VectorXd::Constant(3 * n, 1e-4))));
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": d tau_M / d x vs differences, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-7);
}

TYPED_TEST(DriveTorque, StateJacobianEqualsDifferencesOfTheNumericModel) {
  constexpr int n = TestFixture::n;
  test::Random random(1801);
  double worst = 0;
  for (int s = 0; s < 20; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 2e-4);
    // The reference inverse dynamics on p (no regressor): an independent rigid-body part.
    const Eigen::VectorXd p = this->standard(theta);
    const auto f = [&](const Eigen::VectorXd& y) {
      const Eigen::VectorXd tau_G =
          this->reference_.inverse_dynamics(y.head(n), y.segment(n, n), y.tail(n), p);
      return motor_torques<double>(this->K_, y.segment(n, n), y.tail(n), tau_G,
                                   this->drive_part(theta), nullptr);
    };
    worst = std::max(
        worst, relative_difference(this->state_jacobian(x, theta),
                                   differences(f, x, Eigen::VectorXd::Constant(3 * n, 1e-4))));
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": d tau_M / d x vs differences of the numeric model, worst relative difference "
            << worst << "\n";
  EXPECT_LT(worst, 1e-7);
}

TYPED_TEST(DriveTorque, StateJacobianEqualsJetDerivativesThroughTheRigidBodyJacobian) {
  using Model = typename TypeParam::Model;
  constexpr int n = TestFixture::n;
  using Jet = ceres::Jet<double, 3 * n>;
  test::Random random(1901);
  std::vector<double> beta(Model::kBaseParams);
  double worst = 0;
  for (int s = 0; s < 100; ++s) {
    const Eigen::VectorXd theta = this->random_theta(random);
    const Eigen::VectorXd x = this->smooth_state(random, theta, 1e-6);
    // tau_G with its state derivative from the (separately tested) generated rigid-body state
    // Jacobian; eq. 7-10 are differentiated by the Jets.
    const Eigen::VectorXd p = this->standard(theta);
    Model::base_from_standard(p.data(), beta.data());
    RowMajor dtau_G = RowMajor::Zero(n, 3 * n);  // zero entries are not written
    Model::inverse_dynamics_state_jacobian(x.data(), x.data() + n, x.data() + 2 * n, beta.data(),
                                           dtau_G.data());
    const Eigen::VectorXd tau_G_value =
        this->reference_.inverse_dynamics(x.head(n), x.segment(n, n), x.tail(n), p);
    Vector<Jet> tau_G(n), dq(n), ddq(n);
    for (int i = 0; i < n; ++i) {
      tau_G[i] = Jet(tau_G_value[i]);
      tau_G[i].v = dtau_G.row(i).transpose();
      dq[i] = Jet(x[n + i], n + i);
      ddq[i] = Jet(x[2 * n + i], 2 * n + i);
    }
    const Vector<Jet> drive = this->drive_part(theta).template cast<Jet>();
    const Vector<Jet> tau_M = motor_torques<Jet>(this->K_, dq, ddq, tau_G, drive, nullptr);
    Eigen::MatrixXd expected(n, 3 * n);
    for (int i = 0; i < n; ++i) expected.row(i) = tau_M[i].v.transpose();
    worst = std::max(worst, relative_difference(this->state_jacobian(x, theta), expected));
  }
  std::cout << "[ DRIVE    ] " << TypeParam::kDescription
            << ": d tau_M / d x vs ceres::Jet, worst relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-10);
}

}  // namespace
}  // namespace modelgen
