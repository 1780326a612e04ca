// Forward dynamics by one mass matrix, one inverse dynamics at zero acceleration and a
// Cholesky solve: for the 6-joint arms of this project cheaper than an articulated-body pass,
// since the generated functions share the sines and cosines and fold the geometry in.

#include "modelgen/closed_loop/forward_dynamics.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace modelgen {

ForwardDynamics::ForwardDynamics(const IdentificationModel& model, std::vector<double> beta)
    : model_(model),
      beta_(std::move(beta)),
      n_(model.dof()),
      M_(n_, n_),
      h_(n_),
      zero_(Eigen::VectorXd::Zero(n_)),
      rhs_(n_),
      llt_(n_) {
  if (static_cast<int>(beta_.size()) != model.num_base_params()) {
    throw std::invalid_argument("ForwardDynamics: " + std::to_string(beta_.size()) +
                                " base parameters given, the model " + model.name() + " has " +
                                std::to_string(model.num_base_params()));
  }
}

void ForwardDynamics::accelerations(const double* q, const double* dq, const double* tau,
                                    double* ddq) {
  // M is symmetric: its row-major values read column-major are the same matrix.
  model_.mass_matrix(q, beta_.data(), M_.data());
  model_.inverse_dynamics(q, dq, zero_.data(), beta_.data(), h_.data());
  llt_.compute(M_);
  if (llt_.info() != Eigen::Success) {
    std::ostringstream where;
    where << "ForwardDynamics: the mass matrix of " << model_.name()
          << " is not positive definite at q = [";
    for (int i = 0; i < n_; ++i) where << (i ? ", " : "") << q[i];
    where << "]: the base parameters are not those of a physical robot";
    throw std::domain_error(where.str());
  }
  for (int i = 0; i < n_; ++i) rhs_[i] = tau[i] - h_[i];
  Eigen::Map<Eigen::VectorXd> out(ddq, n_);
  out = llt_.solve(rhs_);
  if (!out.allFinite()) {
    throw std::domain_error("ForwardDynamics: non-finite acceleration of " + model_.name() +
                            " (a torque, position or velocity is not finite)");
  }
}

}  // namespace modelgen
