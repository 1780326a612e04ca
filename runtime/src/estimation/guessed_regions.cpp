// The test of guessed regions (guessed_regions.hpp) around the physical fit of physical.cpp.

#include "runtime/src/estimation/guessed_regions.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace modelgen {

double detail::chi_square_999(int dof) {
  const double k = std::max(dof, 1);
  constexpr double kZ = 3.0902;  // the standard normal's 99.9 % point
  const double c = 2 / (9 * k);
  return k * std::pow(1 - c + kZ * std::sqrt(c), 3);
}

PhysicalFitResult fit_physical(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                               const Eigen::VectorXd& beta_hat, const Eigen::MatrixXd& information,
                               const std::vector<std::optional<double>>& prior,
                               const PhysicalFitOptions& options) {
  PhysicalFitResult with =
      detail::fit_physical_within(tree, K, beta_hat, information, prior, options);
  // The guessed regions that hold at the optimum; without any, nothing to test.
  std::vector<int> guessed_holding;
  for (int body : with.region_bound_bodies) {
    const auto b = static_cast<std::size_t>(body);
    if (b < options.regions.size() && options.regions[b] && options.regions[b]->guessed) {
      guessed_holding.push_back(body);
    }
  }
  if (guessed_holding.empty()) return with;
  PhysicalFitOptions without_guesses = options;
  std::vector<int> dropped;  // every guess goes: one the data reject casts doubt on the rule
  for (std::size_t b = 0; b < without_guesses.regions.size(); ++b) {
    auto& region = without_guesses.regions[b];
    if (region && region->guessed) {
      region.reset();
      dropped.push_back(static_cast<int>(b));
    }
  }
  PhysicalFitResult without =
      detail::fit_physical_within(tree, K, beta_hat, information, prior, without_guesses);
  const double rise = with.cost_increase - without.cost_increase;
  const double bound = detail::chi_square_999(static_cast<int>(guessed_holding.size()));
  if (rise <= bound) return with;
  std::ostringstream says;
  says.precision(3);
  says << "guessed regions of";
  for (int body : guessed_holding)
    says << " '" << tree.bodies[static_cast<std::size_t>(body)].name << "'";
  says << " not enforced: the data reject them (they raise the weighted sum of squares by " << rise
       << " sigma^2, above the 99.9 % bound " << bound << " for " << guessed_holding.size()
       << " constraints); no guessed region is enforced; give `region:` where a link's geometry is "
          "known";
  without.active_constraints.push_back(says.str());
  without.rejected_region_bodies = dropped;
  without.rejected_region_cost = rise;
  return without;
}

}  // namespace modelgen
