// fit --truth: each estimate's distance from the truth, and their summary.

#include "runtime/cli/reports/truth_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>

#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

std::optional<double> sigmas_from_truth(const io::EstimatedParameter& p) {
  if (!p.truth || !(p.std_dev > 0) || !std::isfinite(p.std_dev)) return std::nullopt;
  return (p.value - *p.truth) / p.std_dev;
}

std::optional<double> percent_from_truth(const io::EstimatedParameter& p) {
  if (!p.truth || *p.truth == 0) return std::nullopt;
  return 100 * (p.value - *p.truth) / std::abs(*p.truth);
}

TruthComparison compare_with_truth(const std::vector<io::EstimatedParameter>& parameters,
                                   double well_determined_percent) {
  TruthComparison out;
  std::vector<std::pair<double, std::string>> beyond;
  std::vector<double> errors;
  for (const io::EstimatedParameter& p : parameters) {
    const std::optional<double> sigmas = sigmas_from_truth(p);
    if (!sigmas) continue;
    ++out.compared;
    if (std::abs(*sigmas) > kTruthSigmas) {
      beyond.emplace_back(*sigmas, p.name + " " + fixed(*sigmas, 0, 3));
    }
    if (!(p.rel_std_dev <= well_determined_percent)) continue;
    ++out.well_determined;
    if (const std::optional<double> percent = percent_from_truth(p)) {
      errors.push_back(std::abs(*percent));
    }
  }
  std::sort(beyond.begin(), beyond.end(),
            [](const auto& a, const auto& b) { return std::abs(a.first) > std::abs(b.first); });
  for (auto& [sigmas, text] : beyond) out.beyond.push_back(std::move(text));
  if (!errors.empty()) {
    const auto middle = errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2);
    std::nth_element(errors.begin(), middle, errors.end());
    out.median_abs_percent = *middle;
    if (errors.size() % 2 == 0) {
      out.median_abs_percent = (*middle + *std::max_element(errors.begin(), middle)) / 2;
    }
  }
  return out;
}

void print_truth_comparison(const TruthComparison& comparison, double well_determined_percent) {
  std::cout << "  against the truth: " << comparison.beyond.size() << " of " << comparison.compared
            << " parameters beyond " << fixed(kTruthSigmas, 0, 2) << " std";
  // The worst few by name: enough to see which kind of parameter is off.
  constexpr std::size_t kNamed = 8;
  for (std::size_t k = 0; k < comparison.beyond.size() && k < kNamed; ++k) {
    std::cout << (k == 0 ? " (" : ", ") << comparison.beyond[k];
  }
  if (comparison.beyond.size() > kNamed) std::cout << ", ...";
  if (!comparison.beyond.empty()) std::cout << ")";
  std::cout << "\n  median |error| " << fixed(comparison.median_abs_percent, 0, 3) << " % over the "
            << comparison.well_determined << " with %std at most "
            << fixed(well_determined_percent, 0, 3) << "\n";
}

}  // namespace modelgen::internal
