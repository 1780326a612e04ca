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

namespace modelgen {
namespace {

// Where each standard parameter lives among the optimiser's blocks.
struct Layout {
  std::vector<std::array<int, 10>> body_params;  // complete bodies: their ten standard indices
  std::vector<int> scalar_params;                // every other standard parameter
};

Layout make_layout(const RigidBodyTree& tree) {
  Layout layout;
  std::vector<char> in_body(tree.params.size(), 0);
  for (const auto& index : inertial_param_indices(tree)) {
    if (std::find(index.begin(), index.end(), -1) != index.end()) continue;
    layout.body_params.push_back(index);
    for (int k : index) in_body[static_cast<std::size_t>(k)] = 1;
  }
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    if (!in_body[k]) layout.scalar_params.push_back(static_cast<int>(k));
  }
  return layout;
}

// The optimisation variables: per complete body the ten distinct entries of its pseudo-inertia
// (off-diagonal ones times sqrt 2, so that the Euclidean norm is the Frobenius norm and the
// projection onto the consistent set clips eigenvalues), stored in that body's ten standard
// slots; every other parameter as itself. standard = T variables, T linear.
constexpr double kSqrt2 = 1.4142135623730951;
constexpr int kEntryRow[10] = {0, 0, 0, 1, 1, 2, 0, 1, 2, 3};
constexpr int kEntryCol[10] = {0, 1, 2, 1, 2, 2, 3, 3, 3, 3};

Eigen::Matrix4d pseudo_inertia_of_entries(const double* x) {
  Eigen::Matrix4d P;
  for (int e = 0; e < 10; ++e) {
    const double v = kEntryRow[e] == kEntryCol[e] ? x[e] : x[e] / kSqrt2;
    P(kEntryRow[e], kEntryCol[e]) = P(kEntryCol[e], kEntryRow[e]) = v;
  }
  return P;
}

void entries_of_pseudo_inertia(const Eigen::Matrix4d& P, double* x) {
  for (int e = 0; e < 10; ++e) {
    x[e] = P(kEntryRow[e], kEntryCol[e]) * (kEntryRow[e] == kEntryCol[e] ? 1.0 : kSqrt2);
  }
}

Eigen::MatrixXd standard_from_variables(const Layout& layout, Eigen::Index n) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int k : layout.scalar_params) T(k, k) = 1;
  for (const auto& index : layout.body_params) {
    for (int e = 0; e < 10; ++e) {
      double x[10] = {}, p[10];
      x[e] = 1;
      const Eigen::Matrix4d P = pseudo_inertia_of_entries(x);
      inertial_from_pseudo_inertia(P, p);
      for (int s = 0; s < 10; ++s) T(index[s], index[e]) = p[s];
    }
  }
  return T;
}

// Projection onto the consistent set (in the variables, scaled per body by one factor, which
// leaves the cone unchanged): each pseudo-inertia's eigenvalues raised to at least its body's
// floor (strictly positive definite: a mass, and a log-Cholesky factor, for every body),
// bounded parameters to at least 0.
void project(const Layout& layout, const std::vector<char>& bounded,
             const std::vector<double>& body_floor, Eigen::VectorXd& x) {
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto& index = layout.body_params[b];
    double entries[10];
    for (int e = 0; e < 10; ++e) entries[e] = x[index[e]];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(pseudo_inertia_of_entries(entries));
    const Eigen::Vector4d clipped = eig.eigenvalues().cwiseMax(body_floor[b]);
    entries_of_pseudo_inertia(
        eig.eigenvectors() * clipped.asDiagonal() * eig.eigenvectors().transpose(), entries);
    for (int e = 0; e < 10; ++e) x[index[e]] = entries[e];
  }
  for (int k : layout.scalar_params) {
    if (bounded[static_cast<std::size_t>(k)]) x[k] = std::max(x[k], 0.0);
  }
}

// One scale per body (its variables' largest column norm in A) and per scalar, so that the
// penalty rho weighs every block alike.
Eigen::VectorXd variable_scales(const Layout& layout, const Eigen::MatrixXd& A) {
  Eigen::VectorXd d = A.colwise().norm().transpose();
  for (const auto& index : layout.body_params) {
    double largest = 0;
    for (int k : index) largest = std::max(largest, d[k]);
    for (int k : index) d[k] = largest;
  }
  // Variables the data barely see (rounding in K, or no effect at all) keep a scale of the
  // order of the others, not one that would blow up their prior term.
  const double floor = std::max(1e-6 * d.maxCoeff(), 1e-300);
  return d.cwiseMax(floor);
}

// The basis of the variables: P = sum_e x_e E_e over a body's ten entries.
std::array<Eigen::Matrix4d, 10> entry_basis() {
  std::array<Eigen::Matrix4d, 10> E;
  for (int e = 0; e < 10; ++e) {
    double x[10] = {};
    x[e] = 1;
    E[static_cast<std::size_t>(e)] = pseudo_inertia_of_entries(x);
  }
  return E;
}

// The log barrier of the consistent set, -sum log det(P_b - floor_b 1) - sum log y_k over the
// bounded parameters, with its gradient and Hessian; false when y is not strictly inside.
bool barrier(const Layout& layout, const std::vector<char>& bounded,
             const std::vector<double>& body_floor, const Eigen::VectorXd& y, double& value,
             Eigen::VectorXd* gradient, Eigen::MatrixXd* hessian) {
  static const std::array<Eigen::Matrix4d, 10> E = entry_basis();
  value = 0;
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto& index = layout.body_params[b];
    double entries[10];
    for (int e = 0; e < 10; ++e) entries[e] = y[index[e]];
    const Eigen::Matrix4d S =
        pseudo_inertia_of_entries(entries) - body_floor[b] * Eigen::Matrix4d::Identity();
    const Eigen::LLT<Eigen::Matrix4d> llt(S);
    if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0)) return false;
    value -= 2 * llt.matrixLLT().diagonal().array().log().sum();
    if (gradient == nullptr) continue;
    const Eigen::Matrix4d S_inverse = llt.solve(Eigen::Matrix4d::Identity());
    std::array<Eigen::Matrix4d, 10> SE;
    for (int e = 0; e < 10; ++e) SE[e] = S_inverse * E[e];
    for (int e = 0; e < 10; ++e) {
      (*gradient)[index[e]] -= SE[e].trace();
      for (int f = 0; f <= e; ++f) {
        const double h = (SE[e] * SE[f]).trace();  // d2(-log det S) = tr(S^-1 E_e S^-1 E_f)
        (*hessian)(index[e], index[f]) += h;
        if (f != e) (*hessian)(index[f], index[e]) += h;
      }
    }
  }
  for (int k : layout.scalar_params) {
    if (!bounded[static_cast<std::size_t>(k)]) continue;
    if (!(y[k] > 0)) return false;
    value -= std::log(y[k]);
    if (gradient == nullptr) continue;
    (*gradient)[k] -= 1 / y[k];
    (*hessian)(k, k) += 1 / (y[k] * y[k]);
  }
  return true;
}

// min 1/2 y'Hy - h'y over the consistent set by the barrier method (Boyd & Vandenberghe,
// Convex Optimization, algorithm 11.1: Newton's method with backtracking on
// t f + barrier, t growing tenfold, until the duality gap m / t is negligible).
struct BarrierOutcome {
  Eigen::VectorXd y;
  Eigen::VectorXd push;  // per variable, how hard its constraint pushes at the end (duals)
  int iterations = 0;
  bool converged = false;
};

BarrierOutcome minimise_on_consistent_set(const Eigen::MatrixXd& H, const Eigen::VectorXd& h,
                                          const Layout& layout, const std::vector<char>& bounded,
                                          const std::vector<double>& body_floor,
                                          Eigen::VectorXd y, int max_iterations) {
  const Eigen::Index n = y.size();
  double m = 4.0 * static_cast<double>(layout.body_params.size());
  for (int k : layout.scalar_params) m += bounded[static_cast<std::size_t>(k)] ? 1 : 0;
  const auto objective = [&](const Eigen::VectorXd& v) { return 0.5 * v.dot(H * v) - h.dot(v); };
  const double size = std::max({1.0, std::abs(objective(y)), h.cwiseAbs().maxCoeff()});
  BarrierOutcome out;
  double t = m / size;
  for (int outer = 0; outer < 40 && out.iterations < max_iterations; ++outer) {
    for (int inner = 0; inner < 200 && out.iterations < max_iterations; ++inner) {
      double value = 0;
      Eigen::VectorXd gradient = t * (H * y - h);
      Eigen::MatrixXd hessian = t * H;
      barrier(layout, bounded, body_floor, y, value, &gradient, &hessian);
      const Eigen::VectorXd step = -hessian.ldlt().solve(gradient);
      const double decrement = -gradient.dot(step);
      ++out.iterations;
      if (!(decrement > 2e-14)) break;
      const double phi = t * objective(y) + value;
      double s = 1;
      for (int halving = 0; halving < 80; ++halving, s *= 0.5) {
        const Eigen::VectorXd trial = y + s * step;
        double trial_value = 0;
        if (barrier(layout, bounded, body_floor, trial, trial_value, nullptr, nullptr) &&
            t * objective(trial) + trial_value <= phi - 0.25 * s * decrement) {
          break;
        }
      }
      y += s * step;
      if (decrement < 1e-10) break;
    }
    if (m / t < 1e-13 * size) {
      out.converged = true;
      break;
    }
    t *= 10;
  }
  // The duals: the barrier's gradient over t (for a body the largest entry of its block).
  double value = 0;
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(n, n);
  barrier(layout, bounded, body_floor, y, value, &gradient, &hessian);
  out.push = gradient.cwiseAbs() / t;
  for (const auto& index : layout.body_params) {
    double largest = 0;
    for (int k : index) largest = std::max(largest, out.push[k]);
    for (int k : index) out.push[k] = largest;
  }
  out.y = y;
  return out;
}

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
  const Layout layout = make_layout(tree);
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
  const Eigen::MatrixXd T = standard_from_variables(layout, n);  // invertible, body by body
  const Eigen::MatrixXd A_x = U * K * T;
  const Eigen::VectorXd d = variable_scales(layout, A_x);
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
  project(layout, bounded, start_floor, y0);
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
  const BarrierOutcome solved = minimise_on_consistent_set(
      A.transpose() * A + G.transpose() * G, A.transpose() * b + G.transpose() * g, layout,
      bounded, body_floor, y0, options.max_iterations);

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
