// Weighted motor-torque residuals (tau_M measured - F) / sigma of a block of samples. The
// Jacobian is analytic: the drive model's d tau_M / d theta columns of the unknowns, and for the
// load the payload link's columns times the 10 x 10 Jacobian of standard_from_load (chain rule
// through eq. 3).

#include "runtime/src/ml/block_cost.hpp"

#include <vector>

namespace modelgen {

bool MlProblem::Impl::BlockCost::Evaluate(double const* const* parameters, double* residuals,
                                          double** jacobians) const {
  const Impl& p = problem_;
  const int n = p.model->dof(), P = p.P, U = static_cast<int>(p.unknown.size());
  const Eigen::VectorXd all = p.with_unknowns(parameters[0]);
  const Eigen::VectorXd theta = p.drive_parameters(all);
  double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
  // d standard / d load for the chain rule, once per block.
  Eigen::MatrixXd S;
  if (jacobian != nullptr && !p.payload.empty() && p.unknown_load()) {
    S = standard_from_load_jacobian(LoadParameters::from_vector(all.data() + P));
  }
  std::vector<double> tau(n), J(jacobian != nullptr ? static_cast<size_t>(n) * P : 0);
  int row = 0;
  for (Eigen::Index s = begin_; s < end_; ++s) {
    if (jacobian != nullptr) {
      p.model->torque_jacobian(s, theta.data(), tau.data(), J.data());
    } else {
      p.model->torque(s, theta.data(), tau.data());
    }
    for (const int i : p.setup.axes) {
      const double w = 1.0 / p.sigma(s, i);
      residuals[row] = (p.measured(s, i) - tau[i]) * w;
      if (jacobian != nullptr) {
        const double* dF = &J[static_cast<size_t>(i) * P];
        double* out = jacobian + static_cast<size_t>(row) * U;
        for (int u = 0; u < U; ++u) {
          const int k = p.unknown[u];
          double d = 0;
          if (k < P) {
            d = dF[k];
          } else {
            for (int m = 0; m < 10; ++m) d += dF[p.payload[m]] * S(m, k - P);
          }
          out[u] = -w * d;
        }
      }
      ++row;
    }
  }
  return true;
}

}  // namespace modelgen
