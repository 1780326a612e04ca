// The physically consistent fit of physical.hpp. The problem is convex: a quadratic in the
// standard parameters over a product of cones (each body's pseudo-inertia positive definite,
// rotor inertias and friction nonnegative). It is solved by the barrier method with Newton
// steps (Boyd & Vandenberghe, Convex Optimization, section 11.3), whose log det barrier is the
// natural one for the pseudo-inertia cone; 30 to 300 Newton steps on 100 unknowns. The
// log-Cholesky parametrisation gives the Jacobian for the standard deviations at the optimum.
//
// Measured before choosing, on the TX-40 tests of tests/runtime/estimation/physical_test.cpp:
// Levenberg-Marquardt on Ceres in the log-Cholesky coordinates stalls (1000 iterations without
// convergence, 5e-4 above the optimal cost when one friction bound is active), because the
// data leave many standard directions free and a free body drifts towards the boundary, where
// the logarithms flatten the cost; ADMM with eigenvalue clipping needed over 50 000 iterations
// for 1e-6 accuracy on an estimate far from consistency.

#include "modelgen/estimation/physical.hpp"

#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/src/estimation/physical_barrier.hpp"

namespace modelgen {
namespace {

using detail::BarrierOutcome;
using detail::Layout;

// Scales for the prior term: the largest reference value of the parameter's group (a body's
// inertia entries, its first moments, its mass; all drive parameters of one kind), so that a
// deviation counts relative to the size of what it belongs to, zero-valued products of inertia
// included; floored at 1e-3 of the largest group of its class (inertias, first moments,
// masses), and at what the data resolve of the parameter (the smallest sigma_j / |K_jk| over
// the base parameters j it enters), so that a parameter the data leave at nearly zero does not
// get an enormous weight.
Eigen::VectorXd prior_scales(const RigidBodyTree& tree, const Layout& layout,
                             const Eigen::VectorXd& reference, const Eigen::MatrixXd& K,
                             const Eigen::VectorXd& base_std_dev) {
  std::vector<std::vector<int>> groups[3];  // inertias, first moments, masses
  for (const auto& index : layout.body_params) {
    groups[0].push_back({index[0], index[1], index[2], index[3], index[4], index[5]});
    groups[1].push_back({index[6], index[7], index[8]});
    groups[2].push_back({index[9]});
  }
  std::vector<std::vector<int>> by_kind(static_cast<std::size_t>(ParamKind::kFcm) + 1);
  for (int k : layout.scalar_params) {
    by_kind[static_cast<std::size_t>(tree.params[static_cast<std::size_t>(k)].kind)].push_back(k);
  }
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(reference.size());
  const auto largest_of = [&](const std::vector<int>& members) {
    double largest = 0;
    for (int k : members) largest = std::max(largest, std::abs(reference[k]));
    return largest;
  };
  for (const auto& cls : groups) {
    double class_largest = 0;
    for (const auto& members : cls) class_largest = std::max(class_largest, largest_of(members));
    for (const auto& members : cls) {
      const double size = std::max(largest_of(members), 1e-3 * class_largest);
      for (int k : members) scale[k] = size > 0 ? size : 1.0;
    }
  }
  for (const auto& members : by_kind) {
    const double size = largest_of(members);
    for (int k : members) scale[k] = size > 0 ? size : 1.0;
  }
  for (Eigen::Index k = 0; k < K.cols(); ++k) {
    double resolved = std::numeric_limits<double>::infinity();
    const double column = K.col(k).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < K.rows(); ++j) {
      if (std::abs(K(j, k)) > 1e-9 * column) {
        resolved = std::min(resolved, base_std_dev[j] / std::abs(K(j, k)));
      }
    }
    if (std::isfinite(resolved)) scale[k] = std::max(scale[k], resolved);
  }
  return scale;
}

void check_sizes(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                 const Eigen::VectorXd& beta_hat, const Eigen::MatrixXd& information,
                 const std::vector<std::optional<double>>& prior) {
  const auto n = static_cast<Eigen::Index>(tree.params.size());
  if (K.cols() != n || K.rows() != beta_hat.size() || information.rows() != beta_hat.size() ||
      information.cols() != beta_hat.size() || static_cast<Eigen::Index>(prior.size()) != n) {
    throw EstimationError("physical fit: mismatched sizes (K " + std::to_string(K.rows()) + "x" +
                          std::to_string(K.cols()) + ", " + std::to_string(beta_hat.size()) +
                          " base estimates, " + std::to_string(n) + " standard parameters)");
  }
  if (!K.allFinite() || !beta_hat.allFinite() || !information.allFinite()) {
    throw EstimationError("physical fit: the estimate or its information matrix is not finite");
  }
}

// The constraints that bind the fit to the data at the optimum, per variable (a body's ten
// alike): those whose push (the barrier's dual) exceeds what the prior term alone asks of them.
// A bound that a parameter merely touches, or a body the data leave free at its floor, costs
// nothing and does not bind.
std::vector<char> binding_constraints(const Layout& layout, const Eigen::VectorXd& push,
                                      const Eigen::VectorXd& prior_pull,
                                      const Eigen::VectorXd& curvature, double tolerance) {
  // A push that moves its variable by less than a hundredth of the spread the cost allows it
  // (push / sqrt(curvature), in standard deviations) is rounding, not a constraint the data
  // meet: the barrier leaves such pushes, whose size depends on the compiler (a clang build
  // found one on a TX-40 link where g++ found none).
  const auto moves = [&](int k) { return push[k] > 1e-2 * std::sqrt(curvature[k]); };
  std::vector<char> binding(static_cast<std::size_t>(push.size()), 0);
  for (int k : layout.scalar_params) {
    binding[static_cast<std::size_t>(k)] = push[k] > 10 * prior_pull[k] + tolerance && moves(k);
  }
  for (const auto& index : layout.body_params) {
    double largest_push = 0, largest_pull = 0;
    bool moved = false;
    for (int k : index) {
      largest_push = std::max(largest_push, push[k]);
      largest_pull = std::max(largest_pull, prior_pull[k]);
      moved = moved || moves(k);
    }
    for (int k : index) {
      binding[static_cast<std::size_t>(k)] =
          largest_push > 10 * largest_pull + tolerance && moved;
    }
  }
  return binding;
}

std::vector<std::string> describe(const RigidBodyTree& tree, const Layout& layout,
                                  const std::vector<char>& binding) {
  std::vector<std::string> out;
  for (int k : layout.scalar_params) {
    if (binding[static_cast<std::size_t>(k)]) out.push_back(tree.params[static_cast<std::size_t>(k)].name + " >= 0");
  }
  for (const auto& index : layout.body_params) {
    if (!binding[static_cast<std::size_t>(index[0])]) continue;
    const int body = tree.params[static_cast<std::size_t>(index[9])].body;
    out.push_back("body '" + tree.bodies[static_cast<std::size_t>(body)].name +
                  "': mass distribution on the boundary of consistency");
  }
  return out;
}

// Standard deviations of the constrained base estimate. Without a binding constraint they are
// the unconstrained ones (diagonal of the inverse information). Otherwise the free directions
// at the optimum are the log-Cholesky parameters of the bodies not bound and the parameters
// not on a binding bound; the rest is held, and the covariance of the free ones (a
// pseudo-inverse: the data leave standard directions free) is carried to beta.
Eigen::VectorXd base_standard_deviations(const Layout& layout, const std::vector<char>& binding,
                                         const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                                         const Eigen::MatrixXd& G, const Eigen::MatrixXd& T,
                                         const Eigen::VectorXd& d,
                                         const Eigen::VectorXd& standard) {
  const Eigen::Index n = K.cols();
  if (std::find(binding.begin(), binding.end(), 1) == binding.end()) {
    const Eigen::MatrixXd covariance = (U.transpose() * U).inverse();
    return covariance.diagonal().cwiseSqrt();
  }
  std::vector<Eigen::VectorXd> columns;  // d standard / d free, one per free direction
  for (int k : layout.scalar_params) {
    if (!binding[static_cast<std::size_t>(k)]) columns.push_back(Eigen::VectorXd::Unit(n, k));
  }
  for (const auto& index : layout.body_params) {
    if (binding[static_cast<std::size_t>(index[0])]) continue;
    double p[10];
    for (int s = 0; s < 10; ++s) p[s] = standard[index[s]];
    const auto theta = log_cholesky_from_inertial(p);
    if (!theta) continue;
    using Jet = ceres::Jet<double, 10>;
    Jet t[10], q[10];
    for (int i = 0; i < 10; ++i) t[i] = Jet((*theta)[i], i);
    inertial_from_log_cholesky(t, q);
    for (int i = 0; i < 10; ++i) {
      Eigen::VectorXd column = Eigen::VectorXd::Zero(n);
      for (int s = 0; s < 10; ++s) column[index[s]] = q[s].v[i];
      columns.push_back(column);
    }
  }
  Eigen::MatrixXd dp(n, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) dp.col(static_cast<Eigen::Index>(c)) = columns[c];
  // Residual Jacobian: the base term U K dp and the prior term G (in variables) back in standard
  // coordinates: G_std = G diag(d) T^-1.
  const Eigen::MatrixXd G_standard = G * d.asDiagonal() * T.inverse();
  Eigen::MatrixXd J(U.rows() + G.rows(), dp.cols());
  J << U * K * dp, G_standard * dp;
  const Eigen::MatrixXd covariance =
      (J.transpose() * J).completeOrthogonalDecomposition().pseudoInverse();
  const Eigen::MatrixXd db = K * dp;
  return (db * covariance * db.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace

Eigen::MatrixXd regrouping_matrix(const IdentificationModel& model) {
  const int n = model.num_standard_params(), b = model.num_base_params();
  Eigen::MatrixXd K(b, n);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(n), column(b);
  for (int k = 0; k < n; ++k) {
    unit[k] = 1;
    model.base_from_standard(unit.data(), column.data());
    K.col(k) = column;
    unit[k] = 0;
  }
  return K;
}

PhysicalFitResult fit_physical(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                               const Eigen::VectorXd& beta_hat, const Eigen::MatrixXd& information,
                               const std::vector<std::optional<double>>& prior,
                               const PhysicalFitOptions& options) {
  check_sizes(tree, K, beta_hat, information, prior);
  if (!(options.prior_weight > 0) || !std::isfinite(options.prior_weight)) {
    throw EstimationError("physical fit: the prior weight must be a positive number");
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(information);
  if (llt.info() != Eigen::Success) {
    throw EstimationError("physical fit: the information matrix is not positive definite");
  }
  const Eigen::MatrixXd U = llt.matrixU();  // information = U'U
  const Layout layout = detail::make_layout(tree);
  const auto n = static_cast<Eigen::Index>(tree.params.size());
  std::vector<char> bounded(static_cast<std::size_t>(n), 0);
  for (Eigen::Index k = 0; k < n; ++k) {
    bounded[static_cast<std::size_t>(k)] =
        must_be_nonnegative(tree.params[static_cast<std::size_t>(k)].kind);
  }

  // The start: nearest the a-priori values among the standard sets that reproduce beta_hat,
  // then projected onto the consistent set, strictly inside (the barrier needs it).
  Eigen::VectorXd a_priori = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (prior[static_cast<std::size_t>(k)]) a_priori[k] = *prior[static_cast<std::size_t>(k)];
  }
  const Eigen::VectorXd nearest =
      a_priori + K.completeOrthogonalDecomposition().solve(beta_hat - K * a_priori);
  const Eigen::MatrixXd T = detail::standard_from_variables(layout, n);  // invertible, body by body
  const Eigen::MatrixXd A_x = U * K * T;
  const Eigen::VectorXd d = detail::variable_scales(layout, A_x);
  const Eigen::MatrixXd A = A_x * d.cwiseInverse().asDiagonal();
  // Each body's eigenvalue floor: 1e-8 of the largest eigenvalue of its pseudo-inertia at the
  // nearest set, a numerical device that keeps every mass positive; the data cannot tell it
  // from 0.
  std::vector<double> body_floor;
  for (const auto& index : layout.body_params) {
    double p[10];
    for (int s = 0; s < 10; ++s) p[s] = nearest[index[s]];
    const Eigen::Vector4d lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(pseudo_inertia(p)).eigenvalues();
    body_floor.push_back(1e-8 * std::max(lambda.cwiseAbs().maxCoeff(), 1e-300) * d[index[0]]);
  }
  Eigen::VectorXd y0 = T.fullPivLu().solve(nearest).cwiseProduct(d);
  std::vector<double> start_floor = body_floor;
  for (double& f : start_floor) f *= 2;
  detail::project(layout, bounded, start_floor, y0);
  for (int k : layout.scalar_params) {
    if (bounded[static_cast<std::size_t>(k)]) y0[k] = std::max(y0[k], 1e-3);
  }
  const Eigen::VectorXd start = T * y0.cwiseQuotient(d);

  // The prior term, on every parameter: sqrt(w) (p - prior) / scale, the prior being the
  // a-priori value where there is one, else the start. Without it the problem can lack a
  // minimiser (the image of the consistent set under K need not be closed: the cost can fall
  // forever as some masses grow), and the data leave standard directions free.
  Eigen::VectorXd prior_value = start;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (prior[static_cast<std::size_t>(k)]) prior_value[k] = a_priori[k];
  }
  const Eigen::VectorXd unconstrained_std_dev =
      information.inverse().diagonal().cwiseMax(0.0).cwiseSqrt();
  const Eigen::VectorXd scale =
      prior_scales(tree, layout, prior_value, K, unconstrained_std_dev);
  const Eigen::VectorXd w = std::sqrt(options.prior_weight) * scale.cwiseInverse();
  const Eigen::MatrixXd G = w.asDiagonal() * T * d.cwiseInverse().asDiagonal();
  const Eigen::VectorXd g = w.cwiseProduct(prior_value);

  const Eigen::VectorXd b = U * beta_hat;
  const BarrierOutcome solved = detail::minimise_on_consistent_set(
      A.transpose() * A + G.transpose() * G, A.transpose() * b + G.transpose() * g, layout, bounded,
      body_floor, y0, options.max_iterations);

  PhysicalFitResult result;
  result.converged = solved.converged;
  result.iterations = solved.iterations;
  result.standard = T * solved.y.cwiseQuotient(d);
  result.prior = prior_value;
  result.prior_scale = scale;
  result.base = K * result.standard;
  result.cost_increase = (U * (result.base - beta_hat)).squaredNorm();
  // A constraint that only resists the prior (its push no larger than the prior term's own
  // gradient) does not bind the fit to the data.
  const double tolerance = 1e-7 * std::max((A.transpose() * b).cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::VectorXd prior_pull = (G.transpose() * (G * solved.y - g)).cwiseAbs();
  const Eigen::VectorXd curvature =
      A.colwise().squaredNorm().transpose() + G.colwise().squaredNorm().transpose();
  const std::vector<char> binding =
      binding_constraints(layout, solved.push, prior_pull, curvature, tolerance);
  result.active_constraints = describe(tree, layout, binding);
  result.base_std_dev = base_standard_deviations(layout, binding, K, U, G, T, d, result.standard);
  return result;
}

}  // namespace modelgen
