// Where the data reject a link's a-priori values: the base parameters the link's standard
// parameters enter whose a-priori value (the regrouping of the a-priori standard set) lies
// many standard deviations from the unconstrained estimate. A link of a consistent fit that
// moved far from its a-priori values in what the data leave free did so because of these: the
// prior spreads their disagreement over the directions no excitation separates.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

struct BaseDisagreement {
  std::string name;     ///< the base parameter
  double a_priori = 0;  ///< (K p0)_j
  double estimate = 0;  ///< beta_hat_j
  double std_dev = 0;   ///< of beta_hat_j
  /// (a_priori - estimate) / std_dev
  double z() const { return (a_priori - estimate) / std_dev; }
};

/// Per entry of `body_params` (each body's ten positions into the standard parameters, as
/// inertial_param_indices gives them; -1 entries are skipped), the base parameters j with
/// K(j, k) != 0 for one of the body's parameters k, whose a-priori value is defined (every
/// standard parameter in row j has an a-priori value) and lies more than `threshold` standard
/// deviations from beta_hat_j; largest |z| first. `K` is num_base x n, `a_priori` has n
/// entries, `beta_hat`, `std_dev` and `base_names` num_base. Coefficients of K below 1e-10 of
/// its largest are rounding, not regrouping (as in the physical fit's null space).
std::vector<std::vector<BaseDisagreement>> a_priori_disagreement(
    const std::vector<std::array<int, 10>>& body_params, const Eigen::MatrixXd& K,
    const std::vector<std::optional<double>>& a_priori, const Eigen::VectorXd& beta_hat,
    const Eigen::VectorXd& std_dev, const std::vector<std::string>& base_names, double threshold);

/// "MY5R -14.6 sd" for each entry, at most `count` of them.
std::vector<std::string> disagreement_words(const std::vector<BaseDisagreement>& list,
                                            std::size_t count);

}  // namespace modelgen
