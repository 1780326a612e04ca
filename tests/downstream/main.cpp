// A consumer of the installed package: calls the KR150 model generated at its build time and
// links the runtime. Prints the gravity torque of joint 2 with a unit first moment MX2 at rest.

#include <cstdio>

#include "kr150.hpp"
#include "modelgen/rigid_body_tree.hpp"

int main() {
  double q[modelgen::kr150::kDof] = {0, 0, 0, 0, 0, 0};
  double zero[modelgen::kr150::kDof] = {0, 0, 0, 0, 0, 0};
  double p[modelgen::kr150::kStandardParams] = {};
  double tau[modelgen::kr150::kDof];
  p[19] = 1.0;  // MX2: joint 2 carries 1 kg m along x2, horizontal at q = 0
  modelgen::kr150::inverse_dynamics_standard(q, zero, zero, p, tau);
  modelgen::validate(modelgen::RigidBodyTree{});
  std::printf("%s %.6f\n", modelgen::kr150::kStandardParamNames[19], tau[1]);
  return 0;
}
