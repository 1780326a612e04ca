// Base (identifiable) parameters by the numeric method of Gautier (1991): the standard
// regressor stacked over random states, columns taken greedily in the standard order (so the
// later parameters of a link and those of outer links regroup into earlier ones, as in Khalil's
// closed-form rules), and the regrouping relations by least squares on the kept columns.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen {

struct BaseParameter {
  std::string name;        ///< the standard name, suffixed R when it absorbs others: "ZZ1R"
  int standard_index = 0;  ///< the standard parameter it is built on
  /// The regrouping relation beta = sum of coefficient * p[standard index], built-on first
  /// with coefficient 1, then the absorbed parameters in standard order.
  std::vector<std::pair<int, double>> relation;
};

struct BaseParameterSet {
  std::vector<BaseParameter> params;
  /// Standard parameters with no effect at all on the dynamics (zero regressor column).
  std::vector<int> without_effect;
  /// beta = K p: kBaseParams x kStandardParams.
  Eigen::MatrixXd K;
};

/// Derives the base parameters of `tree` (validated as ReferenceDynamics does). Deterministic
/// (fixed seed): the same tree gives the same set on every machine. Throws std::logic_error if
/// the relations fail their own check W_std p == W_base K p on fresh states.
BaseParameterSet derive_base_parameters(const RigidBodyTree& tree);

}  // namespace modelgen
