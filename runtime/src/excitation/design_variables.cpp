// The design's variables, states and criterion of design_variables.hpp; the criterion's gradient
// is in design_gradient.cpp.

#include "runtime/src/excitation/design_variables.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include <Eigen/QR>

namespace modelgen::detail {

std::string shortest_text(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

Design::Design(const ExcitationDesignProblem& p)
    : p_(p),
      model_(*p.model),
      dof_(model_.dof()),
      L_(p.harmonics),
      per_axis_(2 * p.harmonics + 1),
      n_(static_cast<int>(p.moving.size()) * per_axis_),
      wf_(2 * std::numbers::pi / p.period),
      samples_(p.samples > 0 ? p.samples : std::max(100, 40 * p.harmonics)),
      criterion_basis_(p.period, p.harmonics, samples_),
      // 16 constraint points per period of the highest harmonic; the dense grid checks after.
      constraint_basis_(p.period, p.harmonics, 16 * p.harmonics) {
  for (int j : p.moving) {
    const JointLimits& limit = p.limits.at(static_cast<std::size_t>(j));
    // A continuous joint has no range: one wide enough never to bind (in a period the joint
    // moves at most dq * period), about 0, where any offset can be taken modulo 2 pi.
    const bool ranged = limit.q_lower && limit.q_upper;
    const double middle = ranged ? (*limit.q_lower + *limit.q_upper) / 2 : 0;
    const double half =
        ranged ? (*limit.q_upper - *limit.q_lower) / 2 : std::numbers::pi + *limit.dq * p.period;
    bounds_.push_back({middle - p.margin * half, middle + p.margin * half, p.margin * *limit.dq,
                       p.margin * *limit.ddq});
  }
  if (p.a_priori.size() > 0) {
    for (int j = 0; j < dof_; ++j) {
      const std::optional<double>& effort = p.limits[static_cast<std::size_t>(j)].effort;
      if (effort) torque_joints_.push_back(j), torque_limits_.push_back(p.margin * *effort);
    }
  }
}

// Position-form coefficients of the variables (held joints at their hold position).
void Design::coefficients(const std::vector<double>& x, Eigen::VectorXd& q0, Eigen::MatrixXd& a,
                          Eigen::MatrixXd& b) const {
  q0 = p_.hold;
  a = Eigen::MatrixXd::Zero(dof_, L_);
  b = Eigen::MatrixXd::Zero(dof_, L_);
  for (std::size_t m = 0; m < p_.moving.size(); ++m) {
    const int j = p_.moving[m];
    const double* v = x.data() + m * per_axis_;
    q0[j] = v[0];
    for (int l = 0; l < L_; ++l) a(j, l) = v[1 + l], b(j, l) = v[1 + L_ + l];
  }
}

// q, dq, ddq (samples x dof) on the criterion's instants.
void Design::states(const std::vector<double>& x, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                    Eigen::MatrixXd& ddq) const {
  states(x.data(), criterion_basis_, q, dq, ddq);
}

// q, dq, ddq (instants x dof) on the instants of `basis`.
void Design::states(const double* x, const FourierBasis& basis, Eigen::MatrixXd& q,
                    Eigen::MatrixXd& dq, Eigen::MatrixXd& ddq) const {
  const int points = static_cast<int>(basis.times.size());
  q = p_.hold.transpose().replicate(points, 1);
  dq = Eigen::MatrixXd::Zero(points, dof_);
  ddq = Eigen::MatrixXd::Zero(points, dof_);
  for (std::size_t m = 0; m < p_.moving.size(); ++m) {
    const int j = p_.moving[m];
    const double* v = x + m * per_axis_;
    for (int k = 0; k < points; ++k) {
      double qk = v[0], dqk = 0, ddqk = 0;
      for (int l = 0; l < L_; ++l) {
        const double w = (l + 1) * wf_, s = basis.sin(k, l), c = basis.cos(k, l);
        const double a = v[1 + l], b = v[1 + L_ + l];
        qk += a * s + b * c;
        dqk += w * (a * c - b * s);
        ddqk -= w * w * (a * s + b * c);
      }
      q(k, j) = qk, dq(k, j) = dqk, ddq(k, j) = ddqk;
    }
  }
}

RowMajor Design::regressor_at(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                              const Eigen::VectorXd& ddq) const {
  RowMajor W(dof_, model_.num_base_params());
  model_.regressor(q.data(), dq.data(), ddq.data(), W.data());
  return W;
}

Eigen::MatrixXd Design::stacked(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                const Eigen::MatrixXd& ddq) const {
  Eigen::MatrixXd W(samples_ * dof_, model_.num_base_params());
  for (int k = 0; k < samples_; ++k) {
    W.middleRows(k * dof_, dof_) =
        regressor_at(q.row(k).transpose(), dq.row(k).transpose(), ddq.row(k).transpose());
  }
  return W;
}

Eigen::MatrixXd Design::selected(const Eigen::MatrixXd& W) const {
  Eigen::MatrixXd out(W.rows(), static_cast<Eigen::Index>(columns_.size()));
  for (std::size_t c = 0; c < columns_.size(); ++c)
    out.col(static_cast<Eigen::Index>(c)) = W.col(columns_[c]);
  return out;
}

// The base parameters the moving axes excite: the independent columns (pivoted QR of the
// unit-norm columns) of the regressor stacked over the given random trajectories.
void Design::choose_columns(const std::vector<std::vector<double>>& trajectories) {
  Eigen::MatrixXd W(0, model_.num_base_params());
  for (const auto& x : trajectories) {
    Eigen::MatrixXd q, dq, ddq;
    states(x, q, dq, ddq);
    const Eigen::MatrixXd part = stacked(q, dq, ddq);
    Eigen::MatrixXd grown(W.rows() + part.rows(), W.cols());
    grown << W, part;
    W.swap(grown);
  }
  const Eigen::VectorXd norms = W.colwise().norm().transpose();
  std::vector<int> nonzero;
  for (Eigen::Index c = 0; c < W.cols(); ++c) {
    if (norms[c] > 1e-12 * norms.maxCoeff()) nonzero.push_back(static_cast<int>(c));
  }
  Eigen::MatrixXd scaled(W.rows(), static_cast<Eigen::Index>(nonzero.size()));
  for (std::size_t c = 0; c < nonzero.size(); ++c) {
    scaled.col(static_cast<Eigen::Index>(c)) = W.col(nonzero[c]) / norms[nonzero[c]];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  qr.setThreshold(1e-8);
  columns_.clear();
  for (Eigen::Index r = 0; r < qr.rank(); ++r) {
    columns_.push_back(nonzero[static_cast<std::size_t>(qr.colsPermutation().indices()[r])]);
  }
  std::sort(columns_.begin(), columns_.end());
}

// The fixed column scale (design_criterion.hpp): the RMS norm of each selected column over
// the given trajectories.
void Design::choose_scale(const std::vector<std::vector<double>>& trajectories) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(columns_.size()));
  for (const auto& x : trajectories) {
    Eigen::MatrixXd q, dq, ddq;
    states(x, q, dq, ddq);
    sum += selected(stacked(q, dq, ddq)).colwise().squaredNorm().transpose();
  }
  scale_ = (sum / static_cast<double>(trajectories.size())).cwiseSqrt();
  // A column no trajectory excites keeps scale 1 (it is rank-deficient anyway).
  for (Eigen::Index c = 0; c < scale_.size(); ++c) {
    if (!(scale_[c] > 0)) scale_[c] = 1;
  }
}

CriterionValue Design::criterion(const std::vector<double>& x,
                                 std::vector<double>* gradient) const {
  Eigen::MatrixXd q, dq, ddq;
  states(x, q, dq, ddq);
  const Eigen::MatrixXd W = stacked(q, dq, ddq);
  CriterionValue value = evaluate_criterion(selected(W), scale_, p_.criterion, gradient != nullptr);
  if (gradient == nullptr) return value;
  gradient->assign(static_cast<std::size_t>(n_), 0.0);
  if (std::isfinite(value.value)) criterion_gradient(q, dq, ddq, W, value, *gradient);
  return value;
}

}  // namespace modelgen::detail
