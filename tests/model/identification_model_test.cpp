// Every compiled-in generated model and the numeric reference built from the same description
// give the same numbers through the IdentificationModel interface.

#include <gtest/gtest.h>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

struct Case {
  const char* name;
  const char* description;
};

TEST(IdentificationModel, GeneratedEqualsReferenceForEveryShippedRobot) {
  const Case cases[] = {{"tx40", "robots/tx40.yaml"},
                        {"kr150", "robots/kr150.yaml"},
                        {"ur5", "robots/urdf/ur5.urdf"},
                        {"iiwa14", "robots/urdf/kuka_iiwa14_drake.urdf"},
                        {"panda", "robots/urdf/franka_panda.urdf"},
                        {"kuka_kr150_2", "robots/urdf/kuka_kr150_2.urdf"},
                        {"panda_arm", "robots/panda_arm.yaml"},
                        {"comau_smart_six", "robots/comau_smart_six.yaml"}};
  EXPECT_EQ(internal::shipped_model_names().size(), std::size(cases));
  for (const Case& c : cases) {
    const std::unique_ptr<IdentificationModel> generated = internal::make_shipped_model(c.name);
    ASSERT_NE(generated, nullptr) << c.name;
    const modelgen::RobotModel description = modelgen::load_robot(test::source_path(c.description));
    const ReferenceModel reference(description.name, description.tree);
    EXPECT_EQ(generated->name(), reference.name());
    EXPECT_EQ(generated->standard_param_names(), reference.standard_param_names()) << c.name;
    EXPECT_EQ(generated->base_param_names(), reference.base_param_names()) << c.name;
    const int n = generated->dof(), nb = generated->num_base_params();
    test::Random random(9);
    std::vector<double> W1(n * nb), W2(n * nb), dh1(nb), dh2(nb), beta1(nb), beta2(nb);
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2),
                            ddq = random.vector(n, -5, 5);
      const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
      generated->regressor(q.data(), dq.data(), ddq.data(), W1.data());
      reference.regressor(q.data(), dq.data(), ddq.data(), W2.data());
      generated->power_regressor(q.data(), dq.data(), ddq.data(), dh1.data());
      reference.power_regressor(q.data(), dq.data(), ddq.data(), dh2.data());
      generated->base_from_standard(p.data(), beta1.data());
      reference.base_from_standard(p.data(), beta2.data());
      const auto vec = [](const std::vector<double>& v) {
        return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
      };
      EXPECT_LT(test::relative_error(vec(W1), vec(W2), 1.0), 1e-10) << c.name;
      EXPECT_LT(test::relative_error(vec(dh1), vec(dh2), 1.0), 1e-10) << c.name;
      EXPECT_LT(test::relative_error(vec(beta1), vec(beta2), 1.0), 1e-12) << c.name;
    }
  }
  EXPECT_EQ(internal::make_shipped_model("no_such_robot"), nullptr);
}

}  // namespace
}  // namespace modelgen
