// Base parameters against independent facts: the rank of the stacked regressor from an SVD on
// other states, Khalil's closed-form regrouping of ZZ1R and XX2R for the TX-40 (Gautier &
// Briot Table I geometry), the names of Table II, and W_std p == W_base beta(p).

#include <algorithm>
#include <cctype>

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

std::vector<std::string> names(const BaseParameterSet& base) {
  std::vector<std::string> out;
  for (const BaseParameter& b : base.params) out.push_back(b.name);
  return out;
}

double coefficient(const RobotModel& model, const BaseParameter& b, const std::string& name) {
  for (const auto& [k, c] : b.relation) {
    if (model.tree.params[k].name == name) return c;
  }
  return 0.0;
}

const BaseParameter& find(const BaseParameterSet& base, const std::string& name) {
  for (const BaseParameter& b : base.params) {
    if (b.name == name) return b;
  }
  throw std::runtime_error("no base parameter " + name);
}

class ShippedRobotBase : public testing::TestWithParam<std::string> {};

TEST_P(ShippedRobotBase, CountEqualsRankAndRelationsHold) {
  const RobotModel model = load_robot(GetParam());
  const BaseParameterSet base = derive_base_parameters(model.tree);
  const ReferenceDynamics dynamics(model.tree);
  const int n = dynamics.dof(), np = dynamics.num_params();
  test::Random random(77);
  const int states = 3 * np / n + 10;
  Eigen::MatrixXd W(states * n, np);
  for (int s = 0; s < states; ++s) {
    W.middleRows(s * n, n) = dynamics.standard_regressor(
        random.vector(n, -3, 3), random.vector(n, -2, 2), random.vector(n, -4, 4));
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
  svd.setThreshold(1e-9);
  EXPECT_EQ(static_cast<int>(base.params.size()), static_cast<int>(svd.rank()));
  // W_std p == W_base (K p) for random p on these states.
  Eigen::MatrixXd W_base(W.rows(), base.params.size());
  for (std::size_t b = 0; b < base.params.size(); ++b) W_base.col(b) = W.col(base.params[b].standard_index);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd p = random.vector(np, -1, 1);
    EXPECT_LT(test::relative_error(W_base * (base.K * p), W * p), 1e-10);
  }
}

INSTANTIATE_TEST_SUITE_P(All, ShippedRobotBase, testing::ValuesIn(test::shipped_robots()),
                         test::robot_test_name);

TEST(BaseParameters, Tx40MatchesKhalilClosedForm) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const BaseParameterSet base = derive_base_parameters(model.tree);
  // Khalil & Dombre regrouping for revolute joints, Table I geometry: d3 = 0.225, r3 = 0.035,
  // r4 = 0.225. ZZ1R = ZZ1 + Ia1 + YY2 + YY3 + 2 r3 MZ3 + (d3^2 + r3^2)(M3 + ... + M7).
  const double d3 = 0.225, r3 = 0.035, r4 = 0.225;
  const BaseParameter& zz1 = find(base, "ZZ1R");
  EXPECT_EQ(coefficient(model, zz1, "ZZ1"), 1.0);
  EXPECT_EQ(coefficient(model, zz1, "Ia1"), 1.0);
  EXPECT_EQ(coefficient(model, zz1, "YY2"), 1.0);
  EXPECT_EQ(coefficient(model, zz1, "YY3"), 1.0);
  EXPECT_NEAR(coefficient(model, zz1, "MZ3"), 2 * r3, 1e-15);
  for (const char* mass : {"M3", "M4", "M5", "M6", "M7"}) {
    EXPECT_NEAR(coefficient(model, zz1, mass), d3 * d3 + r3 * r3, 1e-15) << mass;
  }
  // XX2R = XX2 - YY2 - d3^2 (M3 + ... + M7); MX2R = MX2 + d3 (M3 + ... + M7).
  const BaseParameter& xx2 = find(base, "XX2R");
  EXPECT_EQ(coefficient(model, xx2, "YY2"), -1.0);
  EXPECT_NEAR(coefficient(model, xx2, "M5"), -d3 * d3, 1e-15);
  EXPECT_NEAR(coefficient(model, find(base, "MX2R"), "M4"), d3, 1e-15);
  // ZZ3R = ZZ3 + YY4 + 2 r4 MZ4 + r4^2 (M4 + ... + M7): joint 4 is at r4 along z4.
  const BaseParameter& zz3 = find(base, "ZZ3R");
  EXPECT_NEAR(coefficient(model, zz3, "MZ4"), 2 * r4, 1e-15);
  EXPECT_NEAR(coefficient(model, zz3, "M6"), r4 * r4, 1e-15);
}

TEST(BaseParameters, GeneralSixRArmHasThirtySixInertialBaseParameters) {
  // The TX-40 of Table I alone (no payload frame, no drive model but viscous and Coulomb
  // friction): the published count for a general 6R arm is 36 base inertial parameters, and
  // SymPyBotics reports 48 with the 12 friction ones.
  const RobotModel model = load_mdh_yaml(
      "tx40_links.yaml",
      "name: tx40_links\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n"
      "  - {type: revolute, alpha: -pi/2, d: 0, theta: -pi/2, r: 0}\n"
      "  - {type: revolute, alpha: 0, d: 0.225, theta: pi/2, r: 0.035}\n"
      "  - {type: revolute, alpha: pi/2, d: 0, theta: 0, r: 0.225}\n"
      "  - {type: revolute, alpha: -pi/2, d: 0, theta: 0, r: 0}\n"
      "  - {type: revolute, alpha: pi/2, d: 0, theta: 0, r: 0}\n"
      "friction: {viscous: true, coulomb: true, offset: false}\n"
      "rotor_inertia: false\n");
  const BaseParameterSet base = derive_base_parameters(model.tree);
  int inertial = 0;
  for (const BaseParameter& b : base.params) {
    if (model.tree.params[b.standard_index].kind <= ParamKind::kM) ++inertial;
  }
  EXPECT_EQ(inertial, 36);
  EXPECT_EQ(base.params.size(), 48u);
}

TEST(BaseParameters, PandaArmHasTheFortyThreeOfGazEtAl) {
  // Gaz et al. (RA-L 2019) report 43 base inertial parameters for the Panda arm (joints 1-7).
  LoadOptions options;
  options.tip_link = "panda_link7";
  const RobotModel model = load_robot(test::source_path("robots/urdf/franka_panda.urdf"), options);
  const BaseParameterSet base = derive_base_parameters(model.tree);
  int inertial = 0;
  for (const BaseParameter& b : base.params) {
    if (model.tree.params[b.standard_index].kind <= ParamKind::kM) ++inertial;
  }
  EXPECT_EQ(inertial, 43);
}

TEST(BaseParameters, Tx40ContainsTheParametersOfTableII) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const std::vector<std::string> ours = names(derive_base_parameters(model.tree));
  // Table II of Gautier & Briot (identified essential parameters), in DESIGN.md spelling
  // (fs -> Fc, fsm -> Fcm). zz6, xy6, xz6, mx6, my6 carry an R here because the payload frame
  // 7 regroups into link 6; ia6 of the paper (motor 6 rotor, N6^2 Ja6, eq. 26) is Iam6.
  for (const char* name :
       {"ZZ1R", "Fv1", "Fc1", "XX2R", "XY2", "XZ2R", "ZZ2R", "MX2R", "Fv2", "Fc2", "XX3R", "XZ3",
        "YZ3", "ZZ3R", "MY3R", "Ia3", "Fv3", "Fc3", "XY4", "YZ4", "ZZ4R", "MX4", "Ia4", "Fv4",
        "Fc4", "YZ5", "Ia5", "Fv5", "Fc5", "XY6R", "XZ6R", "ZZ6R", "MX6R", "MY6R", "Iam6", "Fv6",
        "Fc6", "Fvm6", "Fcm6"}) {
    EXPECT_NE(std::find(ours.begin(), ours.end(), name), ours.end()) << name;
  }
  // Drive inertias of joints 1 and 2 cannot be told from ZZ1 and ZZ2 (Table II has neither).
  EXPECT_EQ(std::find(ours.begin(), ours.end(), "Ia1"), ours.end());
  EXPECT_EQ(std::find(ours.begin(), ours.end(), "Ia2"), ours.end());
}

}  // namespace
}  // namespace modelgen::gen
