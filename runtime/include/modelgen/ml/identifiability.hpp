// Identifiability of the unknowns of a nonlinear least-squares problem from its Jacobian
// (Swevers et al. 2002, section 4.2: all unknowns are identifiable when the Jacobian of F with
// respect to them has full rank; its condition number indicates the expected accuracy): rank,
// condition number, and the directions the data cannot see, named in words.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace modelgen {

struct Identifiability {
  int rank = 0;
  /// sigma_max / sigma_min of the column-scaled Jacobian; +inf when rank-deficient.
  double condition_number = 0;
  /// Per unknown: false when it takes part in a direction the data do not determine.
  std::vector<bool> identifiable;
  /// One sentence per undetermined direction, its dominant parameters first with their
  /// components, e.g. "load_m (0.98), load_cz (-0.15) cannot be told apart: ...", then the
  /// others it moves; empty at full rank.
  std::vector<std::string> directions;
};

/// Rank and condition number of `J` (rows x unknowns, rows >= unknowns) with every column scaled
/// to unit norm (so units do not matter), from the singular values: the rank counts those above
/// `tolerance` times the largest. Each right singular vector below that marks every parameter it
/// moves (component of magnitude >= 1e-6) not identifiable: the data do not fix its value. Its
/// sentence names the parameters with components >= 0.1 (at least the largest) with their
/// components, then the others it moves. A zero column is named as a parameter with no effect.
/// `names` has one entry per column.
Identifiability identifiability(const Eigen::MatrixXd& J, const std::vector<std::string>& names,
                                double tolerance = 1e-9);

}  // namespace modelgen
