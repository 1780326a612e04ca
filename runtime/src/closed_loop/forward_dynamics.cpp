// Forward dynamics by one mass matrix and one inverse dynamics at zero acceleration (a compiled-in
// generated model gives both from one function, mass_matrix_and_bias, its M by composite rigid
// bodies) and an LDL^T solve: for the 6-joint arms of this project cheaper than an
// articulated-body pass, since the generated functions fold the geometry in (issue 28: 10-12x
// fewer instructions than KDL's ChainFdSolver_RNE, tests/benchmarks/README.md).

#include "modelgen/closed_loop/forward_dynamics.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace modelgen {

ForwardDynamics::ForwardDynamics(const IdentificationModel& model, std::vector<double> beta)
    : model_(model), beta_(std::move(beta)), n_(model.dof()), M_(n_, n_), h_(n_), rhs_(2 * n_) {
  if (static_cast<int>(beta_.size()) != model.num_base_params()) {
    throw std::invalid_argument("ForwardDynamics: " + std::to_string(beta_.size()) +
                                " base parameters given, the model " + model.name() + " has " +
                                std::to_string(model.num_base_params()));
  }
}

namespace {

// M = L D L^T in place (unit lower L below the diagonal of the row-major M, D on it; Golub &
// Van Loan alg. 4.1.2 without square roots), then L z = tau - h, D y = z, L^T ddq = y. kN > 0
// fixes the size at compile time and the pragmas unroll the loops at the project's -O2 too:
// for the TX-40 the loops of a Cholesky with square roots took about 970 instructions a call
// (callgrind), a quarter of the forward dynamics. Returns false when M is not positive
// definite; ddq is then unset.
template <int kN>
bool ldlt_solve(int dynamic_n, double* M, const double* tau, const double* h, double* z,
                double* ddq) {
  const int n = kN > 0 ? kN : dynamic_n;
  double inverse_d[kN > 0 ? kN : 1];
  double* inv = kN > 0 ? inverse_d : z + n;  // the dynamic size uses the second half of z
#pragma GCC unroll 8
  for (int j = 0; j < n; ++j) {
    // w_k = L_jk d_k, kept in row j's upper half (M's upper triangle is not read again).
    double d = M[j * n + j];
#pragma GCC unroll 8
    for (int k = 0; k < j; ++k) {
      const double w = M[j * n + k] * M[k * n + k];
      M[k * n + j] = w;
      d -= w * M[j * n + k];
    }
    if (!(d > 0) || !std::isfinite(d)) return false;
    M[j * n + j] = d;
    inv[j] = 1.0 / d;
#pragma GCC unroll 8
    for (int i = j + 1; i < n; ++i) {
      double v = M[i * n + j];
#pragma GCC unroll 8
      for (int k = 0; k < j; ++k) v -= M[i * n + k] * M[k * n + j];
      M[i * n + j] = v * inv[j];
    }
  }
#pragma GCC unroll 8
  for (int i = 0; i < n; ++i) {
    double v = tau[i] - h[i];
#pragma GCC unroll 8
    for (int k = 0; k < i; ++k) v -= M[i * n + k] * z[k];
    z[i] = v;
  }
#pragma GCC unroll 8
  for (int i = n - 1; i >= 0; --i) {
    double v = z[i] * inv[i];
#pragma GCC unroll 8
    for (int k = i + 1; k < n; ++k) v -= M[k * n + i] * ddq[k];
    ddq[i] = v;
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
  double* z = rhs_.data();
  const bool positive = n_ == 6   ? ldlt_solve<6>(n_, M_.data(), tau, h_.data(), z, ddq)
                        : n_ == 7 ? ldlt_solve<7>(n_, M_.data(), tau, h_.data(), z, ddq)
                                  : ldlt_solve<0>(n_, M_.data(), tau, h_.data(), z, ddq);
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
