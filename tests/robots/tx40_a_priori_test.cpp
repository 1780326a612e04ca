// robots/data/tx40/a_priori_links.yaml holds the TX-40's a-priori link values, converted by hand
// from the inertials of the figaroh TX40 URDF (../shared/robots-ref, skipped when absent) to the
// MDH frames of robots/tx40.yaml. Checked here against the URDF as the URDF loader reads it
// (its own rpy rotation and parallel-axis shift): the URDF's link frames and the MDH frames are
// the same body frames (forward kinematics, with the joint zeros of tx40.yaml's theta offsets),
// so the ten values of every link agree entry by entry, and both descriptions give the same
// joint torques on random states.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The description docs/real-data.md builds: tx40.yaml with the link values appended to its
// `known:` section (its last), as the data file's comment says.
RobotModel tx40_with_a_priori_links() {
  const std::string yaml = file_text(test::source_path("robots/tx40.yaml"));
  const std::string links = file_text(test::source_path("robots/data/tx40/a_priori_links.yaml"));
  const std::string indented =
      std::regex_replace(links, std::regex("^([A-Z])", std::regex::multiline), "  $1");
  return load_robot_text("tx40_a_priori.yaml", yaml + indented);
}

Eigen::Matrix3d rotation(const Frame& f) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(f.rotation.data());
}
Eigen::Vector3d translation(const Frame& f) {
  return Eigen::Vector3d(f.translation[0], f.translation[1], f.translation[2]);
}

// The standard parameter vector of `model` from its known link values, 0 elsewhere (the
// payload; drives, friction and offsets, which only tx40.yaml gives).
Eigen::VectorXd known_links(const RobotModel& model) {
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.tree.params.size()));
  for (std::size_t k = 0; k < model.known_values.size(); ++k) {
    if (model.known_values[k] && is_inertial(model.tree.params[k].kind))
      p(static_cast<Eigen::Index>(k)) = *model.known_values[k];
  }
  return p;
}

std::optional<double> known(const RobotModel& model, const std::string& name) {
  for (std::size_t k = 0; k < model.tree.params.size(); ++k) {
    if (model.tree.params[k].name == name) return model.known_values[k];
  }
  return std::nullopt;
}

class Tx40APriori : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string urdf_path = test::shared_path("robots-ref/staubli_tx40_mdh_modified.urdf");
    if (!std::filesystem::exists(urdf_path)) GTEST_SKIP() << "no TX40 URDF at " << urdf_path;
    urdf_ = load_robot(urdf_path);
    mdh_ = tx40_with_a_priori_links();
  }
  // tx40.yaml's theta offsets: the URDF's joint angle is q2 - pi/2 and q3 + pi/2.
  static Eigen::VectorXd urdf_angles(Eigen::VectorXd q) {
    q(1) -= M_PI / 2;
    q(2) += M_PI / 2;
    return q;
  }
  RobotModel urdf_, mdh_;
};

TEST_F(Tx40APriori, UrdfLinkFramesAreTheMdhFrames) {
  ASSERT_EQ(urdf_.tree.bodies.size(), 6u);  // tool0 is fixed and massless, merged into link_6
  const ReferenceDynamics a(mdh_.tree), b(urdf_.tree);
  test::Random random(40);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::VectorXd q = random.vector(6, -3.0, 3.0);
    const std::vector<Frame> fa = a.forward_kinematics(q),
                             fb = b.forward_kinematics(urdf_angles(q));
    for (int j = 0; j < 6; ++j) {
      // The URDF's base has joint 1 0.32 m above the MDH base (gravity is along z: no torque).
      const Eigen::Vector3d shift(0, 0, 0.32);
      EXPECT_LT((translation(fa[j]) + shift - translation(fb[j])).norm(), 1e-9) << "link " << j + 1;
      // Link 6's frame is turned by pi about its axis (the URDF's joint_6 rpy "pi/2 pi 0").
      const Eigen::Matrix3d turn =
          j == 5 ? Eigen::Matrix3d(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()))
                 : Eigen::Matrix3d::Identity();
      EXPECT_LT((rotation(fa[j]) * turn - rotation(fb[j])).norm(), 1e-9) << "link " << j + 1;
    }
  }
}

TEST_F(Tx40APriori, LinkValuesAreTheUrdfInertialsEntryByEntry) {
  // Same body frames (above): the ten values about the frame origin must agree; link 6, turned
  // by pi about z, is a point mass on its axis, which the turn leaves unchanged.
  for (int j = 1; j <= 6; ++j) {
    for (const char* stem : {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"}) {
      const std::string name = stem + std::to_string(j);
      const std::optional<double> here = known(mdh_, name), source = known(urdf_, name);
      ASSERT_TRUE(here && source) << name;
      EXPECT_NEAR(*here, *source, 1e-12) << name;
    }
  }
}

TEST_F(Tx40APriori, SameJointTorquesAsTheUrdf) {
  const ReferenceDynamics a(mdh_.tree), b(urdf_.tree);
  const Eigen::VectorXd pa = known_links(mdh_), pb = known_links(urdf_);
  test::Random random(41);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd q = random.vector(6, -3.0, 3.0), dq = random.vector(6, -3.0, 3.0),
                          ddq = random.vector(6, -10.0, 10.0);
    const Eigen::VectorXd tau_a = a.inverse_dynamics(q, dq, ddq, pa);
    const Eigen::VectorXd tau_b = b.inverse_dynamics(urdf_angles(q), dq, ddq, pb);
    EXPECT_LT(test::relative_error(tau_a, tau_b), 1e-12) << "trial " << trial;
  }
}

}  // namespace
}  // namespace modelgen
