// The active-set search of the consistent maximum-likelihood fit (physical_fit.cpp): the
// bounds of the drive unknowns, the start made consistent with the prior term's centre and
// scale, and the rounds of Levenberg-Marquardt in the coordinates of physical_coordinates.hpp
// with bounds held and released until the active set settles.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <ceres/ceres.h>

#include <Eigen/Core>

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/physical_fit.hpp"
#include "modelgen/ml/problem.hpp"

namespace modelgen::detail {

enum class Bound { kNone, kNonnegative, kEfficiency };

// JMj, Rvj, Rcj nonnegative; Rzj an efficiency in (0, 1].
Bound bound_of(const std::string& name);

// The least value a search keeps an unknown with `bound` at.
double lower_bound(Bound bound);

// The state of the search: the current unknowns and the load's coordinates, with the prior
// term's centre and scale per drive unknown and for the load's standard parameters.
struct SearchState {
  bool has_load = false;
  std::array<int, 10> load_at{};
  Eigen::VectorXd theta1;  // the current unknowns
  std::vector<Bound> bound;
  Eigen::VectorXd centre, scale;
  Eigen::Matrix<double, 10, 1> load_phi, load_centre, load_scale;
};

// The start: the unconstrained values (held ones included) made consistent, and the prior
// term's centre and scale per drive unknown and for the load's standard parameters.
SearchState search_start(const MlProblem& problem, const MlFitResult& unconstrained, bool has_load,
                         const std::array<int, 10>& load_at);

// What the active-set search did.
struct ActiveSetSearch {
  std::vector<char> held;
  Eigen::VectorXd start;
  ceres::Solver::Summary summary;
  int iterations = 0;
  double solve_seconds = 0;
  bool settled = false;  // the active set stopped changing
  bool searched = false;
};

// Active set: bounds Levenberg-Marquardt ends on are held there and the search repeated
// without them, and a held bound whose gradient points inside is released, until neither
// happens. Ceres' projected steps alone stall next to an active bound that couples with
// other unknowns (measured: 0.1 sigma^2 above the optimum, estimates off by 0.3 sd).
ActiveSetSearch active_set_search(MlProblem& problem, const MlFitResult& unconstrained,
                                  const MlPhysicalOptions& options, SearchState& state);

}  // namespace modelgen::detail
