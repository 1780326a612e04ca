// Estimates that no physical robot can have: negative friction coefficients or rotor
// inertias, masses that are not positive. Such a value says the data excite the parameter too
// little or the model does not fit them; this check only finds them, it constrains nothing.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

/// What kind of physical quantity a parameter name stands for, as far as its sign is concerned.
enum class SignedQuantity {
  kFrictionCoefficient,  ///< Fv, Fc, Fvp, Fvn, Fcp, Fcn, Fvm, Rv, Rc: must be >= 0
  kRotorInertia,         ///< Ia, Iam, JM: must be >= 0
  kMass,                 ///< M, load_m: must be > 0
};

/// One estimate on the impossible side of its bound.
struct ImplausibleEstimate {
  std::string name;  ///< as given, e.g. "Rv3"
  double value = 0;
  double std_dev = 0;  ///< as given; not finite when unknown
  SignedQuantity quantity = SignedQuantity::kFrictionCoefficient;
  /// True when even value + 3 std_dev is on the impossible side (a finite std_dev is needed);
  /// false when the interval value +- 3 std_dev reaches the feasible side.
  bool significant = false;
};

/// The estimates among `names` (size n) with values `value` and standard deviations `std_dev`
/// (both size n; std_dev may be empty: every std unknown) that cannot be physical values of
/// single standard parameters: friction coefficients and rotor or drive inertias below 0,
/// masses at or below 0. Names are those of DESIGN.md and of the ML drive model: stem plus
/// joint number ("Fv3", "Fcp2", "Ia4", "JM5", "Rc6", "M2") or "load_m". Any other name is not
/// checked, among them regrouped base parameters (ending in R, "Fv1R", "ZZ2R": combinations,
/// legitimately of any sign), inertia-tensor entries and first moments, offsets, efficiencies,
/// and Fcm (its sign follows the gear ratio's). Values that are not finite are skipped.
/// Returned in the order of `names`. Throws std::invalid_argument on mismatched sizes.
std::vector<ImplausibleEstimate> implausible_estimates(const std::vector<std::string>& names,
                                                       const Eigen::VectorXd& value,
                                                       const Eigen::VectorXd& std_dev);

}  // namespace modelgen
