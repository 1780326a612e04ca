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

namespace {

// Cholesky M = L L^T in place (lower triangle of the row-major M), then L y = tau - h and
// L^T ddq = y. kN > 0 fixes the size at compile time, so the compiler unrolls the loops: for
// the TX-40 the dynamic loops took about 1200 instructions a call (callgrind), a quarter of
// the forward dynamics. Returns false when M is not positive definite; ddq is then unset.
template <int kN>
bool cholesky_solve(int dynamic_n, double* L, const double* tau, const double* h, double* y,
                    double* ddq) {
  const int n = kN > 0 ? kN : dynamic_n;
  for (int j = 0; j < n; ++j) {
    double d = L[j * n + j];
    for (int k = 0; k < j; ++k) d -= L[j * n + k] * L[j * n + k];
    if (!(d > 0) || !std::isfinite(d)) return false;
    const double root = std::sqrt(d);
    L[j * n + j] = root;
    for (int i = j + 1; i < n; ++i) {
      double v = L[i * n + j];
      for (int k = 0; k < j; ++k) v -= L[i * n + k] * L[j * n + k];
      L[i * n + j] = v / root;
    }
  }
  for (int i = 0; i < n; ++i) {
    double v = tau[i] - h[i];
    for (int k = 0; k < i; ++k) v -= L[i * n + k] * y[k];
    y[i] = v / L[i * n + i];
  }
  for (int i = n; i-- > 0;) {
    double v = y[i];
    for (int k = i + 1; k < n; ++k) v -= L[k * n + i] * ddq[k];
    ddq[i] = v / L[i * n + i];
  }
  return true;
}

}  // namespace

void ForwardDynamics::accelerations(const double* q, const double* dq, const double* tau,
                                    double* ddq) {
  // M is symmetric: its row-major values read column-major are the same matrix.
  model_.mass_matrix_and_bias(q, dq, beta_.data(), M_.data(), h_.data());
  // By hand rather than Eigen's dynamic-size LLT, which cost about 2400 of the 5800
  // instructions a call took (callgrind, TX-40); the arms of this project have 6 or 7 joints.
  double* L = M_.data();
  double* y = rhs_.data();
  const bool positive = n_ == 6   ? cholesky_solve<6>(n_, L, tau, h_.data(), y, ddq)
                        : n_ == 7 ? cholesky_solve<7>(n_, L, tau, h_.data(), y, ddq)
                                  : cholesky_solve<0>(n_, L, tau, h_.data(), y, ddq);
  if (!positive) {
    std::ostringstream where;
    where << "ForwardDynamics: the mass matrix of " << model_.name()
          << " is not positive definite at q = [";
    for (int i = 0; i < n_; ++i) where << (i ? ", " : "") << q[i];
    where << "]: the base parameters are not those of a physical robot";
    throw std::domain_error(where.str());
  }
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(ddq[i])) {
      throw std::domain_error("ForwardDynamics: non-finite acceleration of " + model_.name() +
                              " (a torque, position or velocity is not finite)");
    }
  }
}

}  // namespace modelgen
