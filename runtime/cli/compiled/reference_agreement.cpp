// A few evaluations of both models: microseconds against the numeric reference, and a library
// made from another description, another --angle-tolerance or a stale generator shows here even
// if its table looked right.

#include "runtime/cli/compiled/reference_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace modelgen::internal {

namespace {

// Largest difference relative to the larger of 1 and the reference's largest magnitude.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double difference = 0, scale = 1;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i])) return INFINITY;
    difference = std::max(difference, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return difference / scale;
}

// State number `k` of a fixed set: every joint at a different angle, speed and acceleration.
void fixed_state(int k, int dof, std::vector<double>& q, std::vector<double>& dq,
                 std::vector<double>& ddq) {
  for (int j = 0; j < dof; ++j) {
    q[j] = std::sin(1.3 * (k + 1) + 0.7 * j) * 3.0;
    dq[j] = std::cos(0.9 * (k + 2) + 1.1 * j) * 2.0;
    ddq[j] = std::sin(2.1 * (k + 3) + 0.4 * j) * 5.0;
  }
}

}  // namespace

std::string disagreement(const IdentificationModel& loaded, const IdentificationModel& reference) {
  if (loaded.dof() != reference.dof()) return "it has another number of joints";
  if (loaded.standard_param_names() != reference.standard_param_names()) {
    return "its standard parameters differ";
  }
  if (loaded.base_param_names() != reference.base_param_names()) {
    return "its base parameters differ";
  }
  const int dof = reference.dof();
  const std::size_t base = reference.base_param_names().size();
  std::vector<double> q(dof), dq(dof), ddq(dof), beta(base);
  for (std::size_t i = 0; i < base; ++i) beta[i] = 0.5 + 0.1 * static_cast<double>(i % 7);
  for (int k = 0; k < 3; ++k) {
    fixed_state(k, dof, q, dq, ddq);
    std::vector<double> w_loaded(dof * base), w_reference(dof * base);
    loaded.regressor(q.data(), dq.data(), ddq.data(), w_loaded.data());
    reference.regressor(q.data(), dq.data(), ddq.data(), w_reference.data());
    if (relative_difference(w_loaded, w_reference) > 1e-9) return "its regressor differs";
    std::vector<double> tau_loaded(dof), tau_reference(dof);
    loaded.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau_loaded.data());
    reference.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau_reference.data());
    if (relative_difference(tau_loaded, tau_reference) > 1e-9) {
      return "its inverse dynamics differ";
    }
  }
  return "";
}

}  // namespace modelgen::internal
