// The closed-form regrouping (Khalil's rules, coefficients as expressions of d_j, r_j) against
// the numeric reference and the numeric base-parameter derivation: the relations preserve the
// dynamics (W_std p == W_standing K_sym p on random states), and the numeric base set is the
// symbolic one with at most further regroupings near the base (K_num = Y K_sym, Y picking each
// base parameter's own relation with coefficient 1).

#include <Eigen/QR>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "generator/dynamics/closed_form_base.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

void check_agreement(const RobotModel& model) {
  const std::optional<ClosedFormRelations> closed = derive_closed_form_relations(model);
  ASSERT_TRUE(closed.has_value());
  const int np = static_cast<int>(model.tree.params.size());
  std::vector<int> standing;
  for (const auto& [k, relation] : closed->relations) standing.push_back(k);
  Eigen::MatrixXd K_sym = Eigen::MatrixXd::Zero(standing.size(), np);
  for (std::size_t s = 0; s < standing.size(); ++s) {
    for (const auto& [l, coefficient] : closed->relations.at(standing[s])) {
      K_sym(s, l) = closed->value(coefficient);
    }
  }
  // The relations keep the dynamics: tau = W p = W_standing (K_sym p).
  const ReferenceDynamics reference(model.tree);
  test::Random random(4);
  const int n = model.dof();
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::MatrixXd W = reference.standard_regressor(
        random.vector(n, -3, 3), random.vector(n, -2, 2), random.vector(n, -4, 4));
    Eigen::MatrixXd W_standing(n, standing.size());
    for (std::size_t s = 0; s < standing.size(); ++s) W_standing.col(s) = W.col(standing[s]);
    const Eigen::VectorXd p = random.vector(np, -1, 1);
    EXPECT_LT(test::relative_error(W_standing * (K_sym * p), W * p, 1.0), 1e-12) << model.name;
  }
  // The numeric base set is within the standing set, each relation its own closed-form one plus
  // combinations of standing parameters the numeric method regroups further.
  const BaseParameterSet numeric = derive_base_parameters(model.tree);
  const Eigen::MatrixXd Y = K_sym.transpose().colPivHouseholderQr().solve(numeric.K.transpose()).transpose();
  EXPECT_LT((Y * K_sym - numeric.K).cwiseAbs().maxCoeff(), 1e-9) << model.name;
  for (std::size_t b = 0; b < numeric.params.size(); ++b) {
    const auto at = std::find(standing.begin(), standing.end(), numeric.params[b].standard_index);
    ASSERT_NE(at, standing.end()) << numeric.params[b].name << " is not standing in closed form";
    EXPECT_NEAR(Y(b, at - standing.begin()), 1.0, 1e-9) << numeric.params[b].name;
  }
}

TEST(ClosedFormBase, AgreesWithNumericOnShippedMdhRobots) {
  check_agreement(load_robot(test::source_path("robots/tx40.yaml")));
  check_agreement(load_robot(test::source_path("robots/kr150.yaml")));
}

TEST(ClosedFormBase, AgreesOnPrismaticJointsTreesAndFixedFrames) {
  check_agreement(load_mdh_yaml(
      "mixed.yaml",
      "name: mixed\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0.3}\n"
      "  - {type: prismatic, alpha: -pi/2, d: 0.1, theta: pi/2, r: 0.2}\n"
      "  - {type: revolute, alpha: pi/2, d: 0.05, theta: 0, r: 0.4}\n"
      "  - {type: revolute, ant: 1, alpha: pi/3, d: 0.2, theta: 0.3, r: -0.1}\n"
      "  - {type: fixed, alpha: pi/4, d: 0.07, theta: 0.2, r: 0.15}\n"
      "  - {type: revolute, alpha: -pi/2, d: 0.12, theta: 0, r: 0.02}\n"));
}

TEST(ClosedFormBase, Tx40RelationsPrintWithSymbols) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const ClosedFormRelations closed = *derive_closed_form_relations(model);
  const int zz1 = model.param_index("ZZ1"), mz3 = model.param_index("MZ3"),
            m3 = model.param_index("M3"), xx2 = model.param_index("XX2");
  EXPECT_EQ(closed.text(closed.relations.at(zz1).at(mz3)), "2*r3");
  EXPECT_EQ(closed.text(closed.relations.at(zz1).at(m3)), "d3^2 + r3^2");
  EXPECT_EQ(closed.text(closed.relations.at(xx2).at(m3)), "-d3^2");
  EXPECT_EQ(closed.geometry.at("d3"), 0.225);
}

}  // namespace
}  // namespace modelgen::gen
