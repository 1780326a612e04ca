// Numbers modelid computes from the user's values, checked to be finite before anything is
// printed or written: a parameter of 1e308 gives torques beyond the range of a double, which
// a CSV would hold as inf and every later reader refuses, and an error table of inf says
// nothing.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen::internal {

/// "<column><j> is <value> at t = <t> s" for the first entry of `values` (samples x joints,
/// row s taken at t[s]; j 1-based) that is not finite, or empty when every entry is.
std::string first_non_finite(const Eigen::MatrixXd& values, const Eigen::VectorXd& t,
                             const std::string& column);

/// " (the largest base parameter is 'ZZ1R' = 1e+308)": the parameter of `values` (named by
/// `names`, one each) largest in magnitude, the likeliest cause of a result that overflows;
/// empty for no parameters.
std::string largest_parameter(const Eigen::VectorXd& values, const std::vector<std::string>& names,
                              const std::string& kind = "base parameter");

}  // namespace modelgen::internal
