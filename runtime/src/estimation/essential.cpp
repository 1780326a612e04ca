// Essential parameters by Pham & Gautier's elimination, each step refitted from the factors of
// one pass over W.

#include "modelgen/estimation/essential.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "runtime/src/estimation/reducer.hpp"

namespace modelgen {

namespace {

using detail::all_columns;
using detail::reduce_matrix;
using detail::Reducer;

// Pham & Gautier's elimination; fit(kept, kept_names) fits on a subset of the columns.
template <class Fit>
EssentialParameters eliminate(int params, const Fit& fit, const std::vector<std::string>& names,
                              double r_sigma) {
  if (!(r_sigma > 1) || !std::isfinite(r_sigma)) {
    throw EstimationError("r_sigma must be a finite ratio above 1 (Gautier & Briot use 20), not " +
                          std::to_string(r_sigma));
  }
  EssentialParameters out;
  out.kept = all_columns(params);
  while (true) {
    std::vector<std::string> kept_names;
    for (int k : out.kept) kept_names.push_back(names[static_cast<std::size_t>(k)]);
    out.fit = fit(out.kept, kept_names);
    Eigen::Index worst = 0;
    const double largest = out.fit.rel_std_dev.maxCoeff(&worst);
    const double smallest = out.fit.rel_std_dev.minCoeff();
    // <= so that exact data (every %std 0) keep every parameter: nothing is less certain.
    if (out.kept.size() == 1 || largest <= r_sigma * smallest) return out;
    out.eliminated.push_back(out.kept[static_cast<std::size_t>(worst)]);
    out.kept.erase(out.kept.begin() + worst);
  }
}

}  // namespace

EssentialParameters essential_parameters(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                                         const std::vector<int>& group,
                                         const std::vector<std::string>& names, double r_sigma) {
  if (static_cast<Eigen::Index>(names.size()) != W.cols() || W.cols() == 0) {
    throw EstimationError("essential parameters need one name per column of a non-empty W");
  }
  Reducer reducer = reduce_matrix(W, y, group, names);
  const bool weighted = !group.empty();
  return eliminate(
      reducer.params(),
      [&](const std::vector<int>& kept, const std::vector<std::string>& kept_names) {
        return reducer.solve(kept, kept_names, weighted);
      },
      names, r_sigma);
}

EssentialParameters essential_parameters(const LeastSquaresAccumulator& equations, bool weighted,
                                         const std::vector<std::string>& names, double r_sigma) {
  if (static_cast<int>(names.size()) != equations.params()) {
    throw EstimationError(
        "essential parameters need one name per column: " + std::to_string(names.size()) +
        " names for " + std::to_string(equations.params()) + " columns");
  }
  return eliminate(
      equations.params(),
      [&](const std::vector<int>& kept, const std::vector<std::string>& kept_names) {
        return equations.fit(kept, kept_names, weighted);
      },
      names, r_sigma);
}

}  // namespace modelgen
