// The consistent maximum-likelihood fit of physical_fit.hpp. The search runs in coordinates
// phi where every value is consistent or a bound keeps it so: the drive unknowns as themselves
// (Ceres bounds), the load as the ten log-Cholesky parameters of its standard parameters about
// the payload link's frame. Each cost block of the problem is wrapped: theta1 = g(phi), and its
// Jacobian is the block's times dg/dphi (Ceres jets through the log-Cholesky map). Unlike the
// linear physical fit (modelgen/estimation/physical.hpp, where Levenberg-Marquardt in these
// coordinates stalled on free link directions), the ML problem's unknowns are few and the data
// determine them, so the logarithms' flattening near the boundary does not stop the search.

#include "modelgen/ml/physical_fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/src/ml/physical_coordinates.hpp"
#include "runtime/src/ml/physical_search.hpp"
#include "runtime/src/ml/standard_deviations.hpp"

namespace modelgen {
namespace {

using detail::ActiveSetSearch;
using detail::Bound;
using detail::SearchState;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A load whose pseudo-inertia has its smallest eigenvalue below this fraction of its largest
// sits on the boundary of the consistent set (a degenerate shape: a point, a rod, a plate).
constexpr double kBoundaryRatio = 1e-6;

std::string text(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

// How many of the load's ten parameters are unknown.
int unknown_load_count(const MlProblem& problem) {
  const int P = problem.model().num_params();
  const std::vector<int>& indices = problem.unknown_indices();
  return static_cast<int>(
      std::count_if(indices.begin(), indices.end(), [P](int k) { return k >= P; }));
}

// The positions of the load's ten parameters among the unknowns (to_vector order), and whether
// they are all there; throws when only some are.
bool load_positions(const MlProblem& problem, std::array<int, 10>& positions) {
  const int P = problem.model().num_params();
  positions.fill(-1);
  int found = 0;
  const std::vector<int>& indices = problem.unknown_indices();
  for (std::size_t u = 0; u < indices.size(); ++u) {
    if (indices[u] < P) continue;
    positions[static_cast<std::size_t>(indices[u] - P)] = static_cast<int>(u);
    ++found;
  }
  if (found != 0 && found != 10) {
    throw EstimationError(
        "physical fit: the load's ten parameters must be all unknown or all known (its "
        "log-Cholesky parameters couple them); " +
        std::to_string(found) + " are unknown");
  }
  return found == 10;
}

// The checks of the options and the unconstrained estimate, before anything else.
void check_inputs(const MlProblem& problem, const MlFitResult& unconstrained,
                  const MlPhysicalOptions& options) {
  if (!(options.prior_weight > 0) || !std::isfinite(options.prior_weight)) {
    throw EstimationError("physical fit: the prior weight must be a positive number");
  }
  if (unconstrained.names != problem.unknown_names()) {
    throw EstimationError(
        "physical fit: the unconstrained estimate has other unknowns than the "
        "problem (fit it on the same problem)");
  }
}

// Only the load and the bounded drive parameters may be unknown.
void check_constrained(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    if (name.compare(0, 5, "load_") != 0 && detail::bound_of(name) == Bound::kNone) {
      throw EstimationError("physical fit: " + name +
                            " is unknown; only the load and the drive parameters JM, Rv, Rc, Rz "
                            "are constrained in the maximum-likelihood fit");
    }
  }
}

// Binding constraints: a drive unknown held on its bound, a load on the cone's boundary. Returns
// which unknowns are held at a bound.
std::vector<bool> binding_constraints(const MlProblem& problem, const SearchState& state,
                                      const std::vector<char>& held,
                                      std::vector<std::string>& binding, bool& load_on_boundary) {
  const std::vector<std::string>& names = problem.unknown_names();
  const Eigen::VectorXd& theta1 = state.theta1;
  const int U = static_cast<int>(theta1.size());
  std::vector<bool> at_bound(static_cast<std::size_t>(U), false);
  for (int u = 0; u < U; ++u) {
    if (!held[u]) continue;
    at_bound[static_cast<std::size_t>(u)] = true;
    const bool at_upper = state.bound[u] == Bound::kEfficiency && theta1[u] >= 1.0;
    binding.push_back(names[static_cast<std::size_t>(u)] + (at_upper ? " <= 1"
                                                            : state.bound[u] == Bound::kEfficiency
                                                                ? " > 0"
                                                                : " >= 0"));
  }
  if (state.has_load) {
    double load[10];
    for (int i = 0; i < 10; ++i) load[i] = theta1[state.load_at[i]];
    const Eigen::Vector4d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(
                                       detail::load_pseudo_inertia(load), Eigen::EigenvaluesOnly)
                                       .eigenvalues();
    if (lambda[0] < kBoundaryRatio * lambda[3]) {
      load_on_boundary = true;
      binding.push_back("load pseudo-inertia > 0");
    }
  }
  return at_bound;
}

// Standard deviations from the Jacobian at the optimum with the binding bounds held (a
// local, first-order figure: a load on the boundary gets the unconstrained local one); an
// unknown held at its bound the marginal one with the bounds released, [F^-1]_hh: the
// unconstrained covariance's part F-orthogonal to the free directions, (I - P) F^-1 (I - P)'
// on the held coordinates (the least-squares fit's rule). The local figure would be 0, and a
// clipped estimate whose truth lies on the bound spreads by 0.58 of the unconstrained sd. The
// values, rms errors and the load in its own terms.
void estimates_at_optimum(MlProblem& problem, const MlFitResult& unconstrained,
                          const SearchState& state, const std::vector<bool>& at_bound,
                          const Eigen::VectorXd& residuals, const Eigen::MatrixXd& J,
                          MlFitResult& fit) {
  const Eigen::VectorXd& theta1 = state.theta1;
  const int U = static_cast<int>(theta1.size());
  const int P = problem.model().num_params();
  std::vector<bool> keep(static_cast<std::size_t>(U));
  Eigen::Index kept = 0;
  for (int u = 0; u < U; ++u) {
    keep[static_cast<std::size_t>(u)] =
        unconstrained.identifiability.identifiable[u] && !at_bound[static_cast<std::size_t>(u)];
    kept += keep[static_cast<std::size_t>(u)] ? 1 : 0;
  }
  const double s2 = residuals.squaredNorm() /
                    static_cast<double>(std::max<Eigen::Index>(1, problem.num_residuals() - kept));
  fit.residual_std_dev = std::sqrt(s2);
  fit.std_dev = detail::standard_deviations(J, keep, s2);
  std::vector<bool> released(static_cast<std::size_t>(U));
  for (int u = 0; u < U; ++u) released[u] = unconstrained.identifiability.identifiable[u];
  const Eigen::VectorXd marginal = detail::standard_deviations(J, released, s2);
  fit.value = theta1;
  for (int u = 0; u < U; ++u) {
    if (at_bound[static_cast<std::size_t>(u)]) fit.std_dev[u] = marginal[u];
    if (!unconstrained.identifiability.identifiable[u]) fit.value[u] = kNaN;
  }
  fit.all_values = problem.with_unknowns(theta1);
  const Eigen::MatrixXd errors = problem.torque_errors(fit.all_values);
  fit.rms_error =
      (errors.colwise().squaredNorm() / static_cast<double>(errors.rows())).cwiseSqrt().transpose();
  if (state.has_load) {
    Eigen::VectorXd load = fit.all_values.segment(P, kLoadParams);
    Eigen::VectorXd load_sd(kLoadParams);
    for (int i = 0; i < 10; ++i) {
      const int u = state.load_at[i];
      load_sd[i] = fit.std_dev[u];
      if (!unconstrained.identifiability.identifiable[u]) load[i] = kNaN;
    }
    fit.has_load = true;
    fit.load = LoadParameters::from_vector(load.data());
    fit.load_std_dev = LoadParameters::from_vector(load_sd.data());
    fit.load_warnings = load_warnings(fit.load);
  }
}

}  // namespace

std::vector<std::string> ml_physical_violations(const MlProblem& problem, const MlFitResult& fit) {
  std::vector<std::string> violations;
  const std::vector<std::string>& names = problem.unknown_names();
  const std::vector<int>& indices = problem.unknown_indices();
  for (std::size_t u = 0; u < names.size(); ++u) {
    const double value = fit.all_values[indices[u]];
    switch (detail::bound_of(names[u])) {
      case Bound::kNonnegative:
        if (value < 0) violations.push_back(names[u] + " = " + text(value) + " < 0");
        break;
      case Bound::kEfficiency:
        if (!(value > 0 && value <= 1)) {
          violations.push_back(names[u] + " = " + text(value) + " outside (0, 1]");
        }
        break;
      case Bound::kNone:
        break;
    }
  }
  if (unknown_load_count(problem) > 0) {
    const int P = problem.model().num_params();
    const LoadParameters values = LoadParameters::from_vector(fit.all_values.data() + P);
    for (const std::string& warning : physical_consistency_warnings(values)) {
      violations.push_back("load: " + warning);
    }
  }
  return violations;
}

MlPhysicalResult fit_ml_physical(MlProblem& problem, const MlFitResult& unconstrained,
                                 const MlPhysicalOptions& options) {
  check_inputs(problem, unconstrained, options);
  std::array<int, 10> load_at{};
  const bool has_load = load_positions(problem, load_at);  // throws for a partly known load
  MlPhysicalResult result;
  if (ml_physical_violations(problem, unconstrained).empty()) {
    result.fit = unconstrained;
    result.unconstrained_consistent = true;
    result.unconstrained_sum_of_squares = 2 * unconstrained.final_cost;
    return result;
  }
  check_constrained(problem.unknown_names());
  SearchState state = detail::search_start(problem, unconstrained, has_load, load_at);
  const ActiveSetSearch search = detail::active_set_search(problem, unconstrained, options, state);

  MlFitResult& fit = result.fit;
  fit.names = problem.unknown_names();
  fit.initial = search.start;
  fit.identifiability = unconstrained.identifiability;
  fit.notes = unconstrained.notes;
  // Converged: the active set settled and the last search converged (or none was needed).
  fit.converged =
      search.settled && (!search.searched || search.summary.termination_type == ceres::CONVERGENCE);
  fit.iterations = search.iterations;
  fit.solve_seconds = search.solve_seconds;
  fit.solver_report =
      search.searched ? search.summary.BriefReport() : "no search: every unknown on its bound";

  const int U = problem.num_unknowns();
  const std::vector<int>& indices = problem.unknown_indices();
  Eigen::VectorXd residuals;
  Eigen::MatrixXd J;
  problem.evaluate(search.start, residuals, nullptr);
  fit.initial_cost = 0.5 * residuals.squaredNorm();
  Eigen::VectorXd unconstrained_theta1(U);
  for (int u = 0; u < U; ++u) unconstrained_theta1[u] = unconstrained.all_values[indices[u]];
  problem.evaluate(unconstrained_theta1, residuals, nullptr);
  result.unconstrained_sum_of_squares = residuals.squaredNorm();
  problem.evaluate(state.theta1, residuals, &J);
  fit.final_cost = 0.5 * residuals.squaredNorm();
  result.cost_increase = 2 * fit.final_cost - result.unconstrained_sum_of_squares;

  const std::vector<bool> at_bound =
      binding_constraints(problem, state, search.held, result.binding, result.load_on_boundary);
  result.at_bound = at_bound;
  estimates_at_optimum(problem, unconstrained, state, at_bound, residuals, J, fit);
  return result;
}

}  // namespace modelgen
