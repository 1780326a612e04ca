// The numeric reference behind the IdentificationModel interface: the base regressor is the
// standard one restricted to the independent columns, and dh = dq^T W (the power balance).

#include "modelgen/model/identification_model.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

void IdentificationModel::mass_matrix(const double* q, const double* beta, double* M) const {
  const int n = dof();
  std::vector<double> zero(n, 0.0), unit(n, 0.0), at_rest(n), column(n);
  inverse_dynamics(q, zero.data(), zero.data(), beta, at_rest.data());
  for (int k = 0; k < n; ++k) {
    unit[k] = 1.0;
    inverse_dynamics(q, zero.data(), unit.data(), beta, column.data());
    unit[k] = 0.0;
    for (int i = 0; i < n; ++i) M[i * n + k] = column[i] - at_rest[i];
  }
}

void IdentificationModel::mass_matrix_and_bias(const double* q, const double* dq,
                                               const double* beta, double* M, double* h) const {
  const std::vector<double> zero(static_cast<std::size_t>(dof()), 0.0);
  mass_matrix(q, beta, M);
  inverse_dynamics(q, dq, zero.data(), beta, h);
}

void IdentificationModel::inverse_dynamics_state_jacobian(const double* q, const double* dq,
                                                          const double* ddq, const double* beta,
                                                          double* J) const {
  const int n = dof();
  std::vector<double> x(q, q + n), plus(n), minus(n);
  x.insert(x.end(), dq, dq + n);
  x.insert(x.end(), ddq, ddq + n);
  auto torque = [&](std::vector<double>& at, double* tau) {
    inverse_dynamics(at.data(), at.data() + n, at.data() + 2 * n, beta, tau);
  };
  for (int k = 0; k < 3 * n; ++k) {
    const double x_k = x[k];
    const double h = 6e-6 * std::max(1.0, std::abs(x_k));
    x[k] = x_k + h;
    torque(x, plus.data());
    x[k] = x_k - h;
    torque(x, minus.data());
    x[k] = x_k;
    // The step actually taken, (x + h) - (x - h), rounded as the inputs were.
    const double width = (x_k + h) - (x_k - h);
    for (int i = 0; i < n; ++i) J[i * 3 * n + k] = (plus[i] - minus[i]) / width;
  }
}

ReferenceModel::ReferenceModel(std::string name, RigidBodyTree tree, std::string description_sha256,
                               std::optional<DriveChain> drive)
    : name_(std::move(name)),
      sha256_(std::move(description_sha256)),
      drive_(drive ? std::move(*drive) : DriveChain::identity(tree.dof)),
      dynamics_(std::move(tree)),
      base_(derive_base_parameters(dynamics_.tree())) {
  for (const StandardParam& p : dynamics_.tree().params) standard_.push_back(p.name);
  for (const BaseParameter& b : base_.params) base_names_.push_back(b.name);
}

void ReferenceModel::regressor(const double* q, const double* dq, const double* ddq,
                               double* W) const {
  const int n = dof(), nb = num_base_params();
  const Eigen::Map<const Eigen::VectorXd> Q(q, n), DQ(dq, n), DDQ(ddq, n);
  const Eigen::MatrixXd standard = dynamics_.standard_regressor(Q, DQ, DDQ);
  for (int i = 0; i < n; ++i) {
    for (int b = 0; b < nb; ++b) W[i * nb + b] = standard(i, base_.params[b].standard_index);
  }
}

void ReferenceModel::power_regressor(const double* q, const double* dq, const double* ddq,
                                     double* dh) const {
  const int n = dof(), nb = num_base_params();
  std::vector<double> W(static_cast<std::size_t>(n) * nb);
  regressor(q, dq, ddq, W.data());
  // dq . tau = dq . (W beta): the power regressor is dq^T W (Gautier & Briot eq. 9).
  for (int b = 0; b < nb; ++b) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += dq[i] * W[i * nb + b];
    dh[b] = sum;
  }
}

void ReferenceModel::inverse_dynamics(const double* q, const double* dq, const double* ddq,
                                      const double* beta, double* tau) const {
  const int n = dof(), nb = num_base_params();
  std::vector<double> W(static_cast<std::size_t>(n) * nb);
  regressor(q, dq, ddq, W.data());
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int b = 0; b < nb; ++b) sum += W[i * nb + b] * beta[b];
    tau[i] = sum;
  }
}

void ReferenceModel::base_from_standard(const double* p_standard, double* beta) const {
  const Eigen::Map<const Eigen::VectorXd> p(p_standard, num_standard_params());
  Eigen::Map<Eigen::VectorXd>(beta, num_base_params()) = base_.K * p;
}

}  // namespace modelgen
