// After a closed-loop fit (IDIM-IV, DIDIM): does it differ from IDIM-WLS on the same data by
// more than both estimates' standard deviations allow? Then one of them is biased, and the
// warning says which causes are likely (issue 31).
#pragma once

#include <ostream>
#include <string>

#include "modelgen/estimation/identify.hpp"

namespace modelgen::internal {

/// Above this many combined standard deviations sqrt(sd_a^2 + sd_b^2) a change of a parameter
/// between two methods is called implausible. Two estimates from the same data are positively
/// correlated, so the standard deviation of their difference is below the combined one: the
/// test is conservative (a change it reports is beyond 3 of its true sd; it misses some).
inline constexpr double kMethodChangeSigmas = 3.0;

/// One "modelid fit: warning:" line per parameter of `id` (by method `label`, "IDIM-IV" or
/// "DIDIM") that lies more than kMethodChangeSigmas combined standard deviations from the
/// IDIM-WLS estimate `wls` of the same data (same names), naming it, both values and the
/// change in combined sd; then one line with the likely causes and the options. Returns the
/// number of parameters named.
int warn_method_changes(std::ostream& err, const std::string& label, const Identification& id,
                        const Identification& wls);

}  // namespace modelgen::internal
