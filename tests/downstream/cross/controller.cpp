// The torque feed-forward of a controller: the generated TX-40 inverse dynamics in float.
#include "tx40.hpp"

void feed_forward(const float* q, const float* dq, const float* ddq, const float* beta,
                  float* tau) {
  modelgen::tx40::inverse_dynamics(q, dq, ddq, beta, tau);
}
