// Coulomb friction terms of a model by their parameter names, checked against the model.

#include "runtime/src/closed_loop/coulomb_friction.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace modelgen::detail {

namespace {

// "Fcm6" with prefix "Fcm" -> 5 (0-based joint or motor), or -1.
int numbered(const std::string& name, const std::string& prefix, int dof) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  int number = 0;
  for (std::size_t i = prefix.size(); i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9' || number > dof) return -1;
    number = number * 10 + (name[i] - '0');
  }
  return number >= 1 && number <= dof ? number - 1 : -1;
}

double sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

double phi(CoulombTerm::Shape shape, double v, double eps) {
  const double s = eps > 0 ? std::tanh(v / eps) : sign(v);
  switch (shape) {
    case CoulombTerm::Shape::kSign:
      return s;
    case CoulombTerm::Shape::kPositive:
      return 0.5 * (1 + s);
    case CoulombTerm::Shape::kNegative:
      return -0.5 * (1 - s);
  }
  return 0;
}

}  // namespace

std::vector<CoulombTerm> coulomb_terms(const IdentificationModel& model,
                                       const std::vector<double>& beta) {
  const int n = model.dof();
  const std::vector<std::string>& names = model.base_param_names();
  const Eigen::MatrixXd& K = model.drive_chain().motor_from_joint;
  std::vector<CoulombTerm> terms;
  std::vector<double> coulomb_only(beta.size(), 0.0);
  for (int k = 0; k < static_cast<int>(names.size()); ++k) {
    CoulombTerm term;
    term.param = k;
    term.value = beta[static_cast<std::size_t>(k)];
    int j = -1;
    if ((j = numbered(names[k], "Fcm", n)) >= 0) {
      term.c = K.row(j).transpose() / K(j, j);
      term.a = term.c;
    } else if ((j = numbered(names[k], "Fcp", n)) >= 0) {
      term.shape = CoulombTerm::Shape::kPositive;
    } else if ((j = numbered(names[k], "Fcn", n)) >= 0) {
      term.shape = CoulombTerm::Shape::kNegative;
    } else if ((j = numbered(names[k], "Fc", n)) < 0) {
      continue;
    }
    if (term.c.size() == 0) term.c = term.a = Eigen::VectorXd::Unit(n, j);
    coulomb_only[static_cast<std::size_t>(k)] = term.value;
    terms.push_back(std::move(term));
  }
  // The names are the description's convention; the model's inverse dynamics is the truth.
  // At velocities with no component at rest, the terms must give its Coulomb torque exactly.
  std::mt19937_64 engine(7);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  Eigen::VectorXd q(n), dq(n), zero = Eigen::VectorXd::Zero(n), expected(n), zero_dq(n), sum(n);
  for (int trial = 0; trial < 4; ++trial) {
    for (int i = 0; i < n; ++i) {
      q[i] = uniform(engine);
      dq[i] = uniform(engine);
    }
    model.inverse_dynamics(q.data(), dq.data(), zero.data(), coulomb_only.data(), expected.data());
    model.inverse_dynamics(q.data(), zero.data(), zero.data(), coulomb_only.data(),
                           zero_dq.data());
    expected -= zero_dq;  // anything at rest (there should be nothing)
    sum.setZero();
    for (const CoulombTerm& term : terms) {
      sum += term.value * phi(term.shape, term.c.dot(dq), 0.0) * term.a;
    }
    if ((sum - expected).norm() > 1e-9 * (1 + expected.norm())) {
      throw std::logic_error("the Coulomb friction of " + model.name() +
                             " could not be separated by parameter name (Fc, Fcp, Fcn, Fcm) "
                             "for a smooth simulation");
    }
  }
  return terms;
}

void smoothed_coulomb_torque(const std::vector<CoulombTerm>& terms, const double* dq,
                             Eigen::VectorXd& tau) {
  const Eigen::Map<const Eigen::VectorXd> velocity(dq, tau.size());
  tau.setZero();
  for (const CoulombTerm& term : terms) {
    tau += term.value * phi(term.shape, term.c.dot(velocity), term.smoothing) * term.a;
  }
}

}  // namespace modelgen::detail
