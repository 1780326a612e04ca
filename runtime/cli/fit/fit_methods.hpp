// The methods of modelid fit, one entry each: the --method value, the name printed and written
// into EST.json, and what it is (fit_options.cpp). Which options a method uses is said by the
// options' own entries in fit's table.
#pragma once

#include <string>
#include <vector>

namespace modelgen::internal {

struct FitMethod {
  std::string name;     ///< --method value ("wls")
  std::string label;    ///< printed and written ("IDIM-WLS")
  std::string summary;  ///< for --help
};

/// Every method, in the order --help lists them.
const std::vector<FitMethod>& fit_methods();

/// The entry of a method the command line accepted.
const FitMethod& fit_method(const std::string& name);

}  // namespace modelgen::internal
