// Implausible changes between a closed-loop estimate and IDIM-WLS on the same records.

#include "runtime/cli/reports/method_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

// Parameters named one per line at most; the count says how many more.
constexpr std::size_t kListed = 10;

}  // namespace

int warn_method_changes(std::ostream& err, const std::string& label, const Identification& id,
                        const Identification& wls) {
  if (id.names != wls.names) return 0;
  struct Change {
    Eigen::Index index;
    double sigmas;
  };
  std::vector<Change> changes;
  const Eigen::VectorXd& a = id.fit.value;
  const Eigen::VectorXd& b = wls.fit.value;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double combined = std::hypot(id.fit.std_dev[i], wls.fit.std_dev[i]);
    const double change = std::abs(a[i] - b[i]);
    if (combined > 0 && change > kMethodChangeSigmas * combined) {
      changes.push_back({i, change / combined});
    }
  }
  // The largest first; a long list says no more than its head.
  std::sort(changes.begin(), changes.end(),
            [](const Change& x, const Change& y) { return x.sigmas > y.sigmas; });
  for (std::size_t k = 0; k < changes.size() && k < kListed; ++k) {
    const Eigen::Index i = changes[k].index;
    err << "modelid fit: warning: " << id.names[static_cast<std::size_t>(i)] << " = "
        << fixed(a[i], 0, 4) << " by " << label << " but " << fixed(b[i], 0, 4)
        << " by IDIM-WLS on the same data: " << fixed(changes[k].sigmas, 0, 3)
        << " combined standard deviations apart\n";
  }
  if (changes.empty()) return 0;
  err << "modelid fit: warning: " << changes.size() << " parameter(s)"
      << (changes.size() > kListed ? " (the " + std::to_string(kListed) + " largest named)" : "")
      << " change by more than " << kMethodChangeSigmas << " sqrt(sd_" << label
      << "^2 + sd_WLS^2) (conservative: the two "
      << "estimates are correlated). Likely: IDIM-WLS is biased by noise in dq and ddq (errors "
         "in the variables: lower --cutoff or raise --decimate) or by the closed loop, whose "
         "regressor correlates with the torque noise; then "
      << label << " is the one to keep. Or " << label
      << " simulates the robot poorly (a --controller that is not the record's, "
         "--torque-hold, a drive or friction the model lacks; its relative error norm "
      << fixed(id.torque_rel_error_norm, 0, 4) << " against "
      << fixed(wls.torque_rel_error_norm, 0, 4) << " for IDIM-WLS"
      << (label == "DIDIM" ? ", DIDIM's on the simulated states" : "")
      << "); then check the controller and the residual warnings\n";
  return static_cast<int>(changes.size());
}

}  // namespace modelgen::internal
