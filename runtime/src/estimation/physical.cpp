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
//
// The prior term and the rule for its default weight are in physical_prior.hpp; the rule
// costs up to six solves (the reference weight, then 1, 0.1, ..., 1e-4 until one keeps the
// fit's cost).

#include "modelgen/estimation/physical.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/src/estimation/guessed_regions.hpp"
#include "runtime/src/estimation/physical_barrier.hpp"
#include "runtime/src/estimation/physical_prior.hpp"
#include "runtime/src/estimation/physical_std_dev.hpp"

namespace modelgen {
namespace {

using detail::BarrierOutcome;
using detail::Layout;

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

// The bodies whose region holds at the optimum: its push on the body's variables (the
// barrier's dual) at least half the largest pull of the prior term on them. Against a prior
// of weight 1e-6 the barrier stops before the mass reaches the ellipsoid's edge (the duality
// gap is relative to the data term), so the region holds the body against the prior's pull
// without touching: it, not the prior, then decides what the data leave free. An inactive
// region's push is 1 / (t s) with s far from 0, below the pull; one that holds the data also
// pushes by more than the tolerance.
std::vector<char> regions_holding(const Layout& layout, const std::vector<double>& region_push,
                                  const Eigen::VectorXd& prior_pull, double tolerance) {
  std::vector<char> holding(layout.body_params.size(), 0);
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    double pull = 0;
    for (int k : layout.body_params[b]) pull = std::max(pull, prior_pull[k]);
    holding[b] = region_push[b] > 0 && (region_push[b] >= 0.5 * pull || region_push[b] > tolerance);
  }
  return holding;
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

namespace {

// Everything of the problem that does not depend on the prior weight.
struct Problem {
  Layout layout;
  std::vector<char> bounded;
  Eigen::MatrixXd U, T, A;  // information = U'U; standard = T variables / d; A = U K T / d
  Eigen::VectorXd d, b;     // variable scales; b = U beta_hat
  std::vector<double> body_floor;
  Eigen::VectorXd y0;                  // the start, strictly consistent
  Eigen::VectorXd prior_value, scale;  // the prior term's centre and scale per parameter
  Eigen::MatrixXd G1;                  // the quadratic prior's residual per unit weight,
  Eigen::VectorXd g1;                  // in variables: G1 y - g1 = N' L_Q (p_Q - prior_Q)
  // Per layout body with a-priori inertials, the centre of its divergence prior in the
  // variables' units (d_b P0: the divergence is the same in any unit).
  std::vector<std::optional<Eigen::Matrix4d>> centre;
  bool any_a_priori = false;           // the description gives some a-priori value
  std::vector<std::string> prior_notes;  // a-priori bodies spread for the divergence
};

// The regions the fit enforces: those of bodies without a-priori inertial values. A body with
// them is held by its prior in what the data leave free; its region (a hull of collision
// shapes, which vendors' inertials do not always fit inside) is reported, extent and warning,
// but does not pull against the vendor's values.
std::vector<std::optional<BodyRegion>> enforced_regions(
    const RigidBodyTree& tree, const std::vector<std::optional<double>>& prior,
    std::vector<std::optional<BodyRegion>> regions) {
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const auto body = static_cast<std::size_t>(tree.params[k].body);
    const bool inertial = tree.params[k].kind <= ParamKind::kM;
    if (inertial && prior[k] && body < regions.size()) regions[body].reset();
  }
  return regions;
}

Problem set_up(const RigidBodyTree& tree, const Eigen::MatrixXd& K, const Eigen::VectorXd& beta_hat,
               const Eigen::MatrixXd& information, const std::vector<std::optional<double>>& prior,
               const std::vector<std::optional<BodyRegion>>& regions) {
  Problem pb;
  const Eigen::LLT<Eigen::MatrixXd> llt(information);
  if (llt.info() != Eigen::Success) {
    throw EstimationError("physical fit: the information matrix is not positive definite");
  }
  pb.U = llt.matrixU();
  pb.layout = detail::make_layout(tree);
  detail::add_regions(tree, enforced_regions(tree, prior, regions), pb.layout);
  const auto n = static_cast<Eigen::Index>(tree.params.size());
  pb.bounded.assign(static_cast<std::size_t>(n), 0);
  for (Eigen::Index k = 0; k < n; ++k) {
    pb.bounded[static_cast<std::size_t>(k)] =
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
  pb.T = detail::standard_from_variables(pb.layout, n);  // invertible, body by body
  const Eigen::MatrixXd A_x = pb.U * K * pb.T;
  pb.d = detail::variable_scales(pb.layout, A_x);
  pb.A = A_x * pb.d.cwiseInverse().asDiagonal();
  pb.b = pb.U * beta_hat;
  // Each body's eigenvalue floor: 1e-8 of the largest eigenvalue of its pseudo-inertia at the
  // nearest set, a numerical device that keeps every mass positive; the data cannot tell it
  // from 0.
  for (const auto& index : pb.layout.body_params) {
    double p[10];
    for (int s = 0; s < 10; ++s) p[s] = nearest[index[s]];
    const Eigen::Vector4d lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(pseudo_inertia(p)).eigenvalues();
    pb.body_floor.push_back(1e-8 * std::max(lambda.cwiseAbs().maxCoeff(), 1e-300) * pb.d[index[0]]);
  }
  pb.y0 = pb.T.fullPivLu().solve(nearest).cwiseProduct(pb.d);
  std::vector<double> start_floor = pb.body_floor;
  for (double& f : start_floor) f *= 2;
  detail::project(pb.layout, pb.bounded, start_floor, pb.y0);
  for (int k : pb.layout.scalar_params) {
    if (pb.bounded[static_cast<std::size_t>(k)]) pb.y0[k] = std::max(pb.y0[k], 1e-3);
  }
  const Eigen::VectorXd start = pb.T * pb.y0.cwiseQuotient(pb.d);
  // The barrier starts inside every region; the prior's centre stays `start`, so that without
  // a-priori values the region, not a start moved into it, holds what the data leave free.
  detail::shrink_into_regions(pb.layout, pb.body_floor, pb.y0);

  // The prior term: the a-priori value where there is one, else the start. Without it the
  // problem can lack a minimiser (the image of the consistent set under K need not be closed:
  // the cost can fall forever as some masses grow), and the data leave standard directions
  // free. With a-priori values it acts only in the directions the data do not determine:
  // without constraints the base estimate stays beta_hat whatever the weight.
  pb.prior_value = start;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (prior[static_cast<std::size_t>(k)]) pb.prior_value[k] = a_priori[k];
  }
  std::vector<char> has_a_priori(static_cast<std::size_t>(n), 0);
  for (std::size_t k = 0; k < prior.size(); ++k) has_a_priori[k] = prior[k].has_value();
  for (const auto& index : pb.layout.body_params) {
    bool known = true;
    for (int k : index) known = known && has_a_priori[static_cast<std::size_t>(k)];
    pb.any_a_priori = pb.any_a_priori || known;
  }
  if (!pb.any_a_priori) {
    // Without a-priori inertials (drive values alone, or nothing) the bodies' centre is only
    // the start: a small pull on every direction, relative to group sizes floored at what the
    // data resolve, keeps the problem well posed, as before the a-priori model was the prior.
    const Eigen::VectorXd std_dev = information.inverse().diagonal().cwiseMax(0.0).cwiseSqrt();
    pb.scale = detail::prior_scales(tree, pb.layout, pb.prior_value, K, &std_dev);
    pb.G1 = pb.scale.cwiseInverse().asDiagonal() * pb.T * pb.d.cwiseInverse().asDiagonal();
    pb.g1 = pb.prior_value.cwiseQuotient(pb.scale);
    return pb;
  }
  // With a-priori values: per body that has them the log-det divergence of pseudo-inertias, on
  // every direction (its -log det keeps the body strictly inside); on the other parameters a
  // quadratic pull relative to group scales, on the directions of theirs that change no base
  // parameter (physical_prior.hpp).
  pb.scale = detail::prior_scales(tree, pb.layout, pb.prior_value, K, nullptr);
  std::vector<double> radius;
  for (const auto& index : pb.layout.body_params) {
    const auto body =
        static_cast<std::size_t>(tree.params[static_cast<std::size_t>(index[9])].body);
    radius.push_back(detail::spread_radius(
        tree, body < regions.size() ? regions[body] : std::optional<BodyRegion>{}));
  }
  const auto centres = detail::divergence_centres(pb.layout, pb.prior_value, has_a_priori, radius);
  std::vector<char> in_divergence(static_cast<std::size_t>(n), 0);
  pb.centre.assign(centres.size(), std::nullopt);
  for (std::size_t b = 0; b < centres.size(); ++b) {
    if (!centres[b]) continue;
    const auto& index = pb.layout.body_params[b];
    pb.centre[b] = pb.d[index[0]] * centres[b]->P0;
    const int body = tree.params[static_cast<std::size_t>(index[9])].body;
    if (centres[b]->thin_axes > 0) {
      const std::string& name = tree.bodies[static_cast<std::size_t>(body)].name;
      pb.prior_notes.push_back(detail::spread_note(name, *centres[b]));
    }
    for (int k : index) in_divergence[static_cast<std::size_t>(k)] = 1;
  }
  const detail::QuadraticPrior quadratic = detail::quadratic_prior(
      K, pb.T * pb.d.cwiseInverse().asDiagonal(), pb.scale, pb.prior_value, in_divergence);
  pb.G1 = quadratic.G1;
  pb.g1 = quadratic.g1;
  return pb;
}

// The prior term at y: its gradient (into `pull`) and a root R of its Hessian (R'R), the
// quadratic's G stacked with each divergence body's Cholesky factor.
Eigen::MatrixXd prior_at(const Problem& pb, const detail::ConvexTerm& divergence,
                         const Eigen::MatrixXd& G, const Eigen::VectorXd& g,
                         const Eigen::VectorXd& y, Eigen::VectorXd& pull) {
  const Eigen::Index n = y.size();
  pull = G.transpose() * (G * y - g);
  Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(n, n);
  double value = 0;
  if (divergence) divergence(y, value, &pull, &hessian);
  std::vector<Eigen::MatrixXd> blocks{G};
  for (std::size_t b = 0; b < pb.centre.size(); ++b) {
    if (!pb.centre[b]) continue;
    const auto& index = pb.layout.body_params[b];
    Eigen::Matrix<double, 10, 10> block;
    for (int e = 0; e < 10; ++e) {
      for (int f = 0; f < 10; ++f) block(e, f) = hessian(index[e], index[f]);
    }
    const Eigen::Matrix<double, 10, 10> root =
        Eigen::LLT<Eigen::Matrix<double, 10, 10>>(block).matrixU();
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(10, n);
    for (int e = 0; e < 10; ++e) {
      for (int f = 0; f < 10; ++f) rows(e, index[f]) = root(e, f);
    }
    blocks.push_back(rows);
  }
  Eigen::Index total = 0;
  for (const auto& block : blocks) total += block.rows();
  Eigen::MatrixXd R(total, n);
  total = 0;
  for (const auto& block : blocks) {
    R.middleRows(total, block.rows()) = block;
    total += block.rows();
  }
  return R;
}

PhysicalFitResult solve(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                        const Eigen::VectorXd& beta_hat, const Problem& pb, double weight,
                        int max_iterations) {
  const Eigen::MatrixXd G = std::sqrt(weight) * pb.G1;
  const Eigen::VectorXd g = std::sqrt(weight) * pb.g1;
  const bool any_divergence =
      std::any_of(pb.centre.begin(), pb.centre.end(), [](const auto& c) { return c.has_value(); });
  const detail::ConvexTerm divergence =
      any_divergence ? detail::divergence_term(pb.layout, pb.centre, weight) : detail::ConvexTerm{};
  const BarrierOutcome solved = detail::minimise_on_consistent_set(
      pb.A.transpose() * pb.A + G.transpose() * G, pb.A.transpose() * pb.b + G.transpose() * g,
      pb.layout, pb.bounded, pb.body_floor, pb.y0, max_iterations, divergence,
      any_divergence ? weight : 0);  // the divergence resolved to 1e-9 of itself

  PhysicalFitResult result;
  result.prior_weight = weight;
  result.converged = solved.converged;
  result.iterations = solved.iterations;
  result.standard = pb.T * solved.y.cwiseQuotient(pb.d);
  result.prior = pb.prior_value;
  result.prior_scale = pb.scale;
  result.prior_notes = pb.prior_notes;
  result.base = K * result.standard;
  result.cost_increase = (pb.U * (result.base - beta_hat)).squaredNorm();
  // A constraint that only resists the prior (its push no larger than the prior term's own
  // gradient) does not bind the fit to the data.
  const double tolerance = 1e-7 * std::max((pb.A.transpose() * pb.b).cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd prior_pull;
  const Eigen::MatrixXd prior_root = prior_at(pb, divergence, G, g, solved.y, prior_pull);
  prior_pull = prior_pull.cwiseAbs();
  const Eigen::VectorXd curvature =
      pb.A.colwise().squaredNorm().transpose() + prior_root.colwise().squaredNorm().transpose();
  const std::vector<char> binding =
      binding_constraints(pb.layout, solved.push, prior_pull, curvature, tolerance);
  std::vector<char> held = binding;
  const std::vector<char> holding =
      regions_holding(pb.layout, solved.region_push, prior_pull, tolerance);
  for (std::size_t b = 0; b < holding.size(); ++b) {
    if (!holding[b]) continue;
    const auto& index = pb.layout.body_params[b];
    for (int k : index) held[static_cast<std::size_t>(k)] = 1;  // sd: held like a bound body
    const int body = tree.params[static_cast<std::size_t>(index[9])].body;
    result.region_bound_bodies.push_back(body);
    result.active_constraints.push_back(
        "body '" + tree.bodies[static_cast<std::size_t>(body)].name +
        "': mass distribution held by its region (the ellipsoid from "
        "the geometry)");
  }
  const std::vector<std::string> cones = describe(tree, pb.layout, binding);
  result.active_constraints.insert(result.active_constraints.begin(), cones.begin(), cones.end());
  result.base_std_dev = detail::base_standard_deviations(pb.layout, held, K, pb.U, prior_root, pb.T,
                                                         pb.d, result.standard);
  return result;
}

}  // namespace

PhysicalFitResult detail::fit_physical_within(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                                              const Eigen::VectorXd& beta_hat,
                                              const Eigen::MatrixXd& information,
                                              const std::vector<std::optional<double>>& prior,
                                              const PhysicalFitOptions& options) {
  check_sizes(tree, K, beta_hat, information, prior);
  if (options.prior_weight &&
      (!(*options.prior_weight > 0) || !std::isfinite(*options.prior_weight))) {
    throw EstimationError("physical fit: the prior weight must be a positive number");
  }
  if (options.residual_sum_of_squares && (!(*options.residual_sum_of_squares > 0) ||
                                          !std::isfinite(*options.residual_sum_of_squares))) {
    throw EstimationError("physical fit: the residual sum of squares must be a positive number");
  }
  const Problem pb = set_up(tree, K, beta_hat, information, prior, options.regions);
  if (options.prior_weight) {
    return solve(tree, K, beta_hat, pb, *options.prior_weight, options.max_iterations);
  }
  // Without a-priori inertials the bodies' centre is only the start: the reference weight
  // alone, on every direction (set_up).
  if (!pb.any_a_priori) {
    PhysicalFitResult result =
        solve(tree, K, beta_hat, pb, detail::kReferencePriorWeight, options.max_iterations);
    result.prior_weight_automatic = true;
    return result;
  }
  // The default weight rule (physical_prior.hpp): the largest weight of the ladder whose cost
  // exceeds the reference weight's by at most kCostRiseLimit of the unconstrained fit's.
  const double allowed_rise = options.residual_sum_of_squares
                                  ? detail::kCostRiseLimit * *options.residual_sum_of_squares
                                  : detail::kCostRiseWithoutResidual;
  PhysicalFitResult reference =
      solve(tree, K, beta_hat, pb, detail::kReferencePriorWeight, options.max_iterations);
  for (double weight : detail::kPriorWeightLadder) {
    PhysicalFitResult candidate = solve(tree, K, beta_hat, pb, weight, options.max_iterations);
    if (candidate.cost_increase - reference.cost_increase <= allowed_rise) {
      candidate.prior_weight_automatic = true;
      return candidate;
    }
  }
  reference.prior_weight_automatic = true;
  return reference;
}

}  // namespace modelgen
