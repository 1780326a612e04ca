// A consumer of the installed package: calls the KR150 model generated at its build time, and
// loads the same description at run time through the model core (load_robot + the numeric
// reference dynamics). Prints the gravity torque of joint 2 with a unit first moment MX2 at rest,
// from both, and their difference.

#include <cmath>
#include <cstdio>

#include "kr150.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: controller KR150.yaml\n");
    return 2;
  }
  double q[modelgen::kr150::kDof] = {0, 0, 0, 0, 0, 0};
  double zero[modelgen::kr150::kDof] = {0, 0, 0, 0, 0, 0};
  double p[modelgen::kr150::kStandardParams] = {};
  double tau[modelgen::kr150::kDof];
  p[19] = 1.0;  // MX2: joint 2 carries 1 kg m along x2, horizontal at q = 0
  modelgen::kr150::inverse_dynamics_standard(q, zero, zero, p, tau);

  const modelgen::RobotModel robot = modelgen::load_robot(argv[1]);
  const modelgen::ReferenceDynamics reference(robot.tree);
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(robot.dof());
  Eigen::VectorXd p_reference = Eigen::VectorXd::Zero(reference.num_params());
  p_reference[robot.param_index("MX2")] = 1.0;
  const Eigen::VectorXd tau_reference = reference.inverse_dynamics(z, z, z, p_reference);
  std::printf("%s %.6f reference %.6f difference %.1e\n", modelgen::kr150::kStandardParamNames[19],
              tau[1], tau_reference[1], std::abs(tau[1] - tau_reference[1]));
  return 0;
}
