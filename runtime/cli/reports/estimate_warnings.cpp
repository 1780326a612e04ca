// Warnings on estimates that cannot be physical values: the check is the library's
// (modelgen/estimation/plausibility.hpp), the wording here.

#include "runtime/cli/reports/estimate_warnings.hpp"

#include "modelgen/estimation/plausibility.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

const char* quantity_text(SignedQuantity quantity) {
  switch (quantity) {
    case SignedQuantity::kFrictionCoefficient:
      return "a friction coefficient";
    case SignedQuantity::kRotorInertia:
      return "a rotor inertia";
    case SignedQuantity::kMass:
      return "a mass";
  }
  return "?";
}

}  // namespace

void warn_implausible_estimates(std::ostream& err, const std::vector<std::string>& names,
                                const Eigen::VectorXd& value, const Eigen::VectorXd& std_dev,
                                const std::string& context) {
  for (const ImplausibleEstimate& e : implausible_estimates(names, value, std_dev)) {
    const bool mass = e.quantity == SignedQuantity::kMass;
    err << "modelid fit: warning: " << context << e.name << " = " << fixed(e.value, 0, 3);
    if (!e.significant) err << " +- " << fixed(e.std_dev, 0, 2);
    err << " is " << (mass ? "not positive" : "negative");
    if (!e.significant) err << ", though not significantly (value + 3 std is feasible)";
    err << ": " << quantity_text(e.quantity)
        << " cannot be (poorly excited axis, or a model the data do not fit)\n";
  }
}

}  // namespace modelgen::internal
