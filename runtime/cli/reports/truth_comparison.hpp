// An estimate against a known truth (fit --truth, on simulated data): how far each parameter
// lies from it in its own standard deviations and in percent, how many lie beyond 3 standard
// deviations, and the typical error of the well-determined ones: what a user otherwise
// computes by script to judge a method on data whose truth is known.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "modelgen/io/estimate_file.hpp"

namespace modelgen::internal {

/// Beyond this many standard deviations from the truth, an estimate is counted as off (about
/// 0.3 % of unbiased Gaussian estimates are).
inline constexpr double kTruthSigmas = 3.0;

/// (value - truth) / std of `p`; none without a truth, or with a zero or non-finite std.
std::optional<double> sigmas_from_truth(const io::EstimatedParameter& p);

/// 100 (value - truth) / |truth|; none without a truth or with a zero one.
std::optional<double> percent_from_truth(const io::EstimatedParameter& p);

struct TruthComparison {
  int compared = 0;                 ///< parameters with a truth and a usable std
  std::vector<std::string> beyond;  ///< "NAME -47.2" for each beyond kTruthSigmas, worst first
  int well_determined = 0;          ///< of those, %std at most `well_determined_percent`
  double median_abs_percent = 0;    ///< median |error %| over the well-determined (truth != 0)
};

/// The comparison of `parameters` (each with its truth); `well_determined_percent` is the %std
/// below which a parameter counts as determined by the data (the table's '*' threshold).
TruthComparison compare_with_truth(const std::vector<io::EstimatedParameter>& parameters,
                                   double well_determined_percent);

/// Two lines on standard output under the parameter table: the count beyond 3 std with the
/// worst named, and the median error of the well-determined parameters.
void print_truth_comparison(const TruthComparison& comparison, double well_determined_percent);

}  // namespace modelgen::internal
