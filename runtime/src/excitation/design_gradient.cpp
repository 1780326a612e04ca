// The criterion's gradient in the design variables (design_variables.hpp): analytic through the
// Fourier series and the criterion (design_criterion.hpp), and through the regressor's
// derivative in the joint state x = (q, dq, ddq) at each sample k. With tau = W(x) beta and
// G_k = d value / d W_k, sum_ib G_k,ib dW_k,ib / dx = sum_t c_t^T J(x; beta_t) for any split
// G_k = sum_t c_t beta_t^T, J the model's state Jacobian d tau / dx (linear in beta): exact,
// from generated code. Two splits: the criterion's factors, G_k = W_k F diag(w) F^T (2 terms
// for cond, c_t = w_t W_k F_t, beta_t = F_t), or the rows of G_k (dof terms, c_t = e_t); the
// shorter is taken. A model whose state Jacobian is differences itself (the numeric reference:
// 6 dof inverse dynamics, each a whole regressor) gets central differences of the regressor
// instead, contracted with G_k: 5 regressor evaluations per moving joint and sample.

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "runtime/src/excitation/design_variables.hpp"

namespace modelgen::detail {

void Design::criterion_gradient(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                const Eigen::MatrixXd& ddq, const Eigen::MatrixXd& W,
                                const CriterionValue& value, std::vector<double>& gradient) const {
  const Eigen::MatrixXd by_state = model_.exact_state_jacobian()
                                       ? exact_state_gradient(q, dq, ddq, W, value)
                                       : differenced_state_gradient(q, dq, ddq, W, value);
  // Through the Fourier series: d(q, dq, ddq)_k / d(q0, a_l, b_l).
  gradient.assign(static_cast<std::size_t>(n_), 0.0);
  for (int k = 0; k < samples_; ++k) {
    for (std::size_t m = 0; m < p_.moving.size(); ++m) {
      const int j = p_.moving[m];
      const double by_q = by_state(k, j), by_dq = by_state(k, dof_ + j),
                   by_ddq = by_state(k, 2 * dof_ + j);
      double* g = gradient.data() + m * per_axis_;
      g[0] += by_q;
      for (int l = 0; l < L_; ++l) {
        const double w = (l + 1) * wf_, s = criterion_basis_.sin(k, l),
                     c = criterion_basis_.cos(k, l);
        g[1 + l] += by_q * s + by_dq * w * c - by_ddq * w * w * s;
        g[1 + L_ + l] += by_q * c - by_dq * w * s - by_ddq * w * w * c;
      }
    }
  }
}

Eigen::MatrixXd Design::exact_state_gradient(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                             const Eigen::MatrixXd& ddq, const Eigen::MatrixXd& W,
                                             const CriterionValue& value) const {
  const Eigen::Index columns = static_cast<Eigen::Index>(columns_.size());
  const bool by_factors = value.gradient_weight.size() <= dof_;
  const Eigen::Index terms = by_factors ? value.gradient_weight.size() : dof_;
  // The criterion's factors' directions as base parameters (the same at every sample), and
  // W_k F_t for their weights c_t.
  Eigen::MatrixXd directions = Eigen::MatrixXd::Zero(model_.num_base_params(), terms);
  Eigen::MatrixXd WF;
  if (by_factors) {
    for (Eigen::Index c = 0; c < columns; ++c)
      directions.row(columns_[static_cast<std::size_t>(c)]) = value.gradient_factor.row(c);
    WF = selected(W) * value.gradient_factor * value.gradient_weight.asDiagonal();
  }
  Eigen::MatrixXd by_state = Eigen::MatrixXd::Zero(samples_, 3 * dof_);
  RowMajor J(dof_, 3 * dof_);
  Eigen::VectorXd qk, dqk, ddqk;
  for (int k = 0; k < samples_; ++k) {
    qk = q.row(k).transpose(), dqk = dq.row(k).transpose(), ddqk = ddq.row(k).transpose();
    if (!by_factors) {  // the rows of G_k: beta_t = G_k,t (selected columns), c_t = e_t
      for (Eigen::Index c = 0; c < columns; ++c) {
        directions.row(columns_[static_cast<std::size_t>(c)]) =
            value.gradient.block(static_cast<Eigen::Index>(k) * dof_, c, dof_, 1).transpose();
      }
    }
    for (Eigen::Index t = 0; t < terms; ++t) {
      model_.inverse_dynamics_state_jacobian(qk.data(), dqk.data(), ddqk.data(),
                                             directions.col(t).data(), J.data());
      if (by_factors) {
        by_state.row(k).noalias() +=
            WF.block(static_cast<Eigen::Index>(k) * dof_, t, dof_, 1).transpose() * J;
      } else {
        by_state.row(k) += J.row(t);
      }
    }
  }
  return by_state;
}

Eigen::MatrixXd Design::differenced_state_gradient(const Eigen::MatrixXd& q,
                                                   const Eigen::MatrixXd& dq,
                                                   const Eigen::MatrixXd& ddq,
                                                   const Eigen::MatrixXd& W,
                                                   const CriterionValue& value) const {
  Eigen::MatrixXd by_state = Eigen::MatrixXd::Zero(samples_, 3 * dof_);
  constexpr double h = 1e-6;
  for (int k = 0; k < samples_; ++k) {
    const Eigen::MatrixXd G = value.gradient.middleRows(static_cast<Eigen::Index>(k) * dof_, dof_);
    const auto contract = [&](const RowMajor& dW) {
      double sum = 0;
      for (std::size_t c = 0; c < columns_.size(); ++c) {
        sum += G.col(static_cast<Eigen::Index>(c)).dot(dW.col(columns_[c]));
      }
      return sum;
    };
    const Eigen::VectorXd qk = q.row(k).transpose(), dqk = dq.row(k).transpose(),
                          ddqk = ddq.row(k).transpose();
    const RowMajor Wk = W.middleRows(static_cast<Eigen::Index>(k) * dof_, dof_);
    for (const int j : p_.moving) {
      Eigen::VectorXd up = qk, down = qk;
      up[j] += h, down[j] -= h;
      by_state(k, j) =
          contract(regressor_at(up, dqk, ddqk) - regressor_at(down, dqk, ddqk)) / (2 * h);
      up = dqk, down = dqk;
      up[j] += h, down[j] -= h;
      by_state(k, dof_ + j) =
          contract(regressor_at(qk, up, ddqk) - regressor_at(qk, down, ddqk)) / (2 * h);
      up = ddqk;
      up[j] += 1;  // W is linear in ddq: the unit step is exact
      by_state(k, 2 * dof_ + j) = contract(regressor_at(qk, dqk, up) - Wk);
    }
  }
  return by_state;
}

}  // namespace modelgen::detail
