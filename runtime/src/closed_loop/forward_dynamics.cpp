// Forward dynamics by one mass matrix, one inverse dynamics at zero acceleration (sharing the
// joints' sines and cosines) and a Cholesky solve: for the 6-joint arms of this project cheaper
// than an articulated-body pass, since the generated functions fold the geometry in.

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
      rhs_(n_) {
  if (static_cast<int>(beta_.size()) != model.num_base_params()) {
    throw std::invalid_argument("ForwardDynamics: " + std::to_string(beta_.size()) +
                                " base parameters given, the model " + model.name() + " has " +
                                std::to_string(model.num_base_params()));
  }
}

void ForwardDynamics::accelerations(const double* q, const double* dq, const double* tau,
                                    double* ddq) {
  // M is symmetric: its row-major values read column-major are the same matrix.
  model_.mass_matrix_and_bias(q, dq, beta_.data(), M_.data(), h_.data());
  // Cholesky M = L L^T in place (lower triangle), then L y = tau - h and L^T ddq = y. By hand:
  // for the 6 to 7 joints of an arm Eigen's dynamic-size LLT cost about 2400 instructions of
  // the 5800 a call took (callgrind, TX-40); these loops take a few hundred.
  double* L = M_.data();
  const int n = n_;
  bool positive = true;
  for (int j = 0; j < n && positive; ++j) {
    double d = L[j * n + j];
    for (int k = 0; k < j; ++k) d -= L[j * n + k] * L[j * n + k];
    positive = d > 0 && std::isfinite(d);
    const double root = std::sqrt(d);
    L[j * n + j] = root;
    for (int i = j + 1; i < n; ++i) {
      double v = L[i * n + j];
      for (int k = 0; k < j; ++k) v -= L[i * n + k] * L[j * n + k];
      L[i * n + j] = v / root;
    }
  }
  if (!positive) {
    std::ostringstream where;
    where << "ForwardDynamics: the mass matrix of " << model_.name()
          << " is not positive definite at q = [";
    for (int i = 0; i < n_; ++i) where << (i ? ", " : "") << q[i];
    where << "]: the base parameters are not those of a physical robot";
    throw std::domain_error(where.str());
  }
  double* y = rhs_.data();
  for (int i = 0; i < n; ++i) {
    double v = tau[i] - h_[i];
    for (int k = 0; k < i; ++k) v -= L[i * n + k] * y[k];
    y[i] = v / L[i * n + i];
  }
  bool finite = true;
  for (int i = n; i-- > 0;) {
    double v = y[i];
    for (int k = i + 1; k < n; ++k) v -= L[k * n + i] * ddq[k];
    ddq[i] = v / L[i * n + i];
    finite = finite && std::isfinite(ddq[i]);
  }
  if (!finite) {
    throw std::domain_error("ForwardDynamics: non-finite acceleration of " + model_.name() +
                            " (a torque, position or velocity is not finite)");
  }
}

}  // namespace modelgen
