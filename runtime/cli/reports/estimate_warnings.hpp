// The warnings modelid fit prints about estimates that cannot be physical values (negative
// friction or rotor inertia, a mass that is not positive), for the linear and the ML fits.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen::internal {

/// One "modelid fit: warning:" line on `err` per estimate implausible_estimates() finds among
/// `names`/`value`/`std_dev`; `context` (e.g. "approach 3: ") goes before the name.
void warn_implausible_estimates(std::ostream& err, const std::vector<std::string>& names,
                                const Eigen::VectorXd& value, const Eigen::VectorXd& std_dev,
                                const std::string& context = "");

}  // namespace modelgen::internal
