// The active-set search of physical_search.hpp: Levenberg-Marquardt (solver_setup.hpp) on the
// problem's cost blocks and the prior term in the coordinates phi, the free drive unknowns
// bounded; bounds the search ends on are held and the search repeated, held bounds whose
// gradient points inside are released.

#include "runtime/src/ml/physical_search.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/src/estimation/solver_setup.hpp"
#include "runtime/src/ml/physical_coordinates.hpp"
#include "runtime/src/ml/problem_impl.hpp"

namespace modelgen::detail {
namespace {

// An efficiency must be positive; the search keeps it above this floor so eq. 8's 1 / Rz
// stays finite.
constexpr double kEfficiencyFloor = 1e-3;
// The length (m) below which a load's centre of gravity is not told from the frame origin by
// the prior term's scale.
constexpr double kLengthScale = 0.01;

}  // namespace

// JMj, Rvj, Rcj nonnegative; Rzj an efficiency in (0, 1].
Bound bound_of(const std::string& name) {
  if (name.size() < 3 || name.find_first_not_of("0123456789", 2) != std::string::npos) {
    return Bound::kNone;
  }
  const std::string stem = name.substr(0, 2);
  if (stem == "JM" || stem == "Rv" || stem == "Rc") return Bound::kNonnegative;
  if (stem == "Rz") return Bound::kEfficiency;
  return Bound::kNone;
}

double lower_bound(Bound bound) { return bound == Bound::kEfficiency ? kEfficiencyFloor : 0.0; }

// The start: the unconstrained values (held ones included) made consistent, and the prior
// term's centre and scale per drive unknown and for the load's standard parameters.
SearchState search_start(const MlProblem& problem, const MlFitResult& unconstrained, bool has_load,
                         const std::array<int, 10>& load_at) {
  const std::vector<std::string>& names = problem.unknown_names();
  const std::vector<int>& indices = problem.unknown_indices();
  const int U = problem.num_unknowns();
  SearchState state;
  state.has_load = has_load;
  state.load_at = load_at;
  Eigen::VectorXd& theta1 = state.theta1;
  theta1.resize(U);
  for (int u = 0; u < U; ++u) theta1[u] = unconstrained.all_values[indices[u]];
  std::vector<Bound>& bound = state.bound;
  bound.resize(static_cast<std::size_t>(U));
  state.centre = Eigen::VectorXd::Zero(U);
  state.scale = Eigen::VectorXd::Ones(U);
  for (int u = 0; u < U; ++u) {
    bound[u] = bound_of(names[u]);
    if (bound[u] == Bound::kNone) continue;  // a load parameter
    theta1[u] = std::max(theta1[u], lower_bound(bound[u]));
    if (bound[u] == Bound::kEfficiency) theta1[u] = std::min(theta1[u], 1.0);
    state.centre[u] = theta1[u];
    const double sd = unconstrained.std_dev[u];
    state.scale[u] = std::max({std::abs(theta1[u]), std::isfinite(sd) ? sd : 0.0, 1e-9});
  }
  if (!has_load) return state;
  double load[10];
  for (int i = 0; i < 10; ++i) load[i] = theta1[load_at[i]];
  state.load_centre = consistent_standard(load);
  const Eigen::Matrix<double, 10, 1>& load_centre = state.load_centre;
  const auto log_cholesky = log_cholesky_from_inertial(load_centre.data());
  if (!log_cholesky) {
    throw EstimationError("physical fit: the load's start is not consistent (internal error)");
  }
  state.load_phi = *log_cholesky;
  // Scales by group, as the linear fit's: inertia entries, first moments, mass.
  // Floors from the mass and a 1 cm length, so a start at the origin (a point mass, as the
  // linear route gives a load it cannot see) does not pin the centre of gravity there.
  const double mass = std::max(std::abs(load_centre[9]), 1e-6);
  const double inertia =
      std::max(load_centre.head<6>().cwiseAbs().maxCoeff(), mass * kLengthScale * kLengthScale);
  const double moments =
      std::max(load_centre.segment<3>(6).cwiseAbs().maxCoeff(), mass * kLengthScale);
  for (int i = 0; i < 10; ++i) {
    state.load_scale[i] = i < 6 ? inertia : i < 9 ? moments : mass;
  }
  return state;
}

namespace {

// One round of the active-set search: the coordinates, their start phi, the prior's centre and
// scale per coordinate, and the bound of each free drive unknown.
struct Round {
  Coordinates coordinates;
  std::vector<double> phi, centre_values, scale_values;
  std::vector<Bound> bounds;
};

// The round's coordinates: the drive unknowns neither held nor unidentifiable, and the load.
void set_up_round(const SearchState& state, const std::vector<char>& held,
                  const MlFitResult& unconstrained, Round& round) {
  const int U = static_cast<int>(state.theta1.size());
  Coordinates& coordinates = round.coordinates;
  coordinates.U = U;
  coordinates.has_load = state.has_load;
  coordinates.load = state.load_at;
  coordinates.held = state.theta1;
  for (int u = 0; u < U; ++u) {
    // Unknowns the data do not identify stay where the unconstrained fit held them.
    if (state.bound[u] == Bound::kNone || held[u] ||
        !unconstrained.identifiability.identifiable[u]) {
      continue;
    }
    coordinates.free.push_back(u);
    round.phi.push_back(state.theta1[u]);
    round.bounds.push_back(state.bound[u]);
    round.centre_values.push_back(state.centre[u]);
    round.scale_values.push_back(state.scale[u]);
  }
  if (state.has_load) {
    for (int i = 0; i < 10; ++i) {
      round.phi.push_back(state.load_phi[i]);
      round.centre_values.push_back(state.load_centre[i]);
      round.scale_values.push_back(state.load_scale[i]);
    }
  }
}

// Levenberg-Marquardt on the round's phi: the problem's cost blocks and the prior term in the
// round's coordinates, the free drive unknowns bounded.
ceres::Solver::Summary search_round(const MlProblem& problem, const MlPhysicalOptions& options,
                                    Round& round) {
  const Coordinates& coordinates = round.coordinates;
  std::vector<double>& phi = round.phi;
  const Eigen::Map<Eigen::VectorXd> prior_centre(
      round.centre_values.data(), static_cast<Eigen::Index>(round.centre_values.size()));
  const Eigen::Map<Eigen::VectorXd> prior_scale(
      round.scale_values.data(), static_cast<Eigen::Index>(round.scale_values.size()));
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem solver_problem(problem_options);
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  for (const ceres::CostFunction* block : MlProblemAccess::cost_functions(problem)) {
    costs.push_back(std::make_unique<CostInCoordinates>(block, coordinates));
    solver_problem.AddResidualBlock(costs.back().get(), nullptr, phi.data());
  }
  costs.push_back(std::make_unique<PriorCost>(
      coordinates, prior_centre, std::sqrt(options.prior_weight) * prior_scale.cwiseInverse()));
  solver_problem.AddResidualBlock(costs.back().get(), nullptr, phi.data());
  for (std::size_t f = 0; f < coordinates.free.size(); ++f) {
    const int i = static_cast<int>(f);
    solver_problem.SetParameterLowerBound(phi.data(), i, lower_bound(round.bounds[f]));
    if (round.bounds[f] == Bound::kEfficiency) {
      solver_problem.SetParameterUpperBound(phi.data(), i, 1.0);
    }
  }
  return solve_levenberg_marquardt(solver_problem, options.max_iterations, options.threads,
                                   "physical fit");
}

// Whether the active set changed after a round that left `state` at its optimum.
bool active_set_changed(MlProblem& problem, const Round& round, const SearchState& state,
                        std::vector<char>& held) {
  const Eigen::VectorXd& theta1 = state.theta1;
  // Unknowns the search ended on a bound with are held there for the next round.
  bool changed = false;
  for (std::size_t f = 0; f < round.coordinates.free.size(); ++f) {
    const int u = round.coordinates.free[f];
    if (theta1[u] <= lower_bound(round.bounds[f]) ||
        (round.bounds[f] == Bound::kEfficiency && theta1[u] >= 1.0)) {
      held[u] = 1;
      changed = true;
    }
  }
  if (changed) return true;
  // None new: release a held one whose cost gradient points into the feasible side.
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  problem.evaluate(theta1, r, &J);
  const Eigen::VectorXd gradient = J.transpose() * r;
  for (int u = 0; u < static_cast<int>(held.size()); ++u) {
    if (!held[u]) continue;
    const bool at_upper = state.bound[u] == Bound::kEfficiency && theta1[u] >= 1.0;
    if (at_upper ? gradient[u] > 0 : gradient[u] < 0) {
      held[u] = 0;
      changed = true;
    }
  }
  return changed;
}

}  // namespace

// Active set: bounds Levenberg-Marquardt ends on are held there and the search repeated
// without them, and a held bound whose gradient points inside is released, until neither
// happens. Ceres' projected steps alone stall next to an active bound that couples with
// other unknowns (measured: 0.1 sigma^2 above the optimum, estimates off by 0.3 sd).
ActiveSetSearch active_set_search(MlProblem& problem, const MlFitResult& unconstrained,
                                  const MlPhysicalOptions& options, SearchState& state) {
  const int U = problem.num_unknowns();
  ActiveSetSearch search;
  search.held.assign(static_cast<std::size_t>(U), 0);
  for (int round_number = 0; round_number < 2 * U + 2; ++round_number) {
    Round round;
    set_up_round(state, search.held, unconstrained, round);
    if (round_number == 0) {
      search.start.resize(U);
      round.coordinates.unknowns(round.phi.data(), search.start.data(), nullptr);
    }
    // Every identifiable unknown held on its bound and no load: nothing is left to search.
    if (round.coordinates.size() == 0) {
      search.settled = true;
      break;
    }
    search.searched = true;
    search.summary = search_round(problem, options, round);
    search.iterations += static_cast<int>(search.summary.iterations.size()) - 1;
    search.solve_seconds += search.summary.minimizer_time_in_seconds;
    round.coordinates.unknowns(round.phi.data(), state.theta1.data(), nullptr);
    if (state.has_load) {
      for (int i = 0; i < 10; ++i) {
        state.load_phi[i] = round.phi[round.coordinates.load_offset() + i];
      }
    }
    if (!active_set_changed(problem, round, state, search.held)) {
      search.settled = true;
      break;
    }
  }
  return search;
}

}  // namespace modelgen::detail
