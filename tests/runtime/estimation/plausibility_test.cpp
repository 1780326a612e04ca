// implausible_estimates() on hand-made names, values and standard deviations: which names are
// single standard parameters with a sign bound, strict bound for masses, significance from
// value + 3 std, regrouped base parameters and other quantities never flagged.

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/estimation/plausibility.hpp"

namespace modelgen {
namespace {

struct Entry {
  std::string name;
  double value, std_dev;
};

std::vector<ImplausibleEstimate> check(const std::vector<Entry>& entries, bool with_std = true) {
  std::vector<std::string> names;
  Eigen::VectorXd value(static_cast<Eigen::Index>(entries.size()));
  Eigen::VectorXd sd(value.size());
  for (std::size_t k = 0; k < entries.size(); ++k) {
    names.push_back(entries[k].name);
    value[static_cast<Eigen::Index>(k)] = entries[k].value;
    sd[static_cast<Eigen::Index>(k)] = entries[k].std_dev;
  }
  return implausible_estimates(names, value, with_std ? sd : Eigen::VectorXd());
}

TEST(ImplausibleEstimates, FlagsNegativeFrictionAndInertiaAndNonPositiveMass) {
  const std::vector<ImplausibleEstimate> found = check({
      {"Fv1", -1.0, 0.1},     // -1 + 0.3 < 0: significant
      {"Rv3", -26.6, 24.0},   // -26.6 + 72 > 0: not significant
      {"JM5", -2.0, 0.5},     // -0.5 < 0: significant
      {"M2", 0.0, 0.0},       // a mass of 0 is impossible too
      {"load_m", -1.0, 1.0},  // -1 + 3 > 0: not significant
      {"Fcp1", -0.1, NAN},    // std unknown: cannot be called significant
      {"Iam6", -1e-3, 1e-4},  // significant
      {"Fvn12", -5.0, 1.0},   // two-digit joint number; -5 + 3 < 0: significant
      {"Rc4", 3.0, 1.0},      // feasible
      {"Ia3", 0.0, 1.0},      // zero inertia is possible (no drive modelled)
      {"M3", 1e-3, 1.0},      // positive mass
  });
  ASSERT_EQ(found.size(), 8u);
  const std::vector<std::string> names = {"Fv1",    "Rv3",  "JM5",  "M2",
                                          "load_m", "Fcp1", "Iam6", "Fvn12"};
  const std::vector<bool> significant = {true, false, true, true, false, false, true, true};
  const std::vector<SignedQuantity> quantity = {SignedQuantity::kFrictionCoefficient,
                                                SignedQuantity::kFrictionCoefficient,
                                                SignedQuantity::kRotorInertia,
                                                SignedQuantity::kMass,
                                                SignedQuantity::kMass,
                                                SignedQuantity::kFrictionCoefficient,
                                                SignedQuantity::kRotorInertia,
                                                SignedQuantity::kFrictionCoefficient};
  for (std::size_t k = 0; k < found.size(); ++k) {
    EXPECT_EQ(found[k].name, names[k]);
    EXPECT_EQ(found[k].significant, significant[k]) << names[k];
    EXPECT_EQ(found[k].quantity, quantity[k]) << names[k];
  }
  EXPECT_EQ(found[1].value, -26.6);
  EXPECT_EQ(found[1].std_dev, 24.0);
}

TEST(ImplausibleEstimates, RegroupedAndOtherParametersAreNeverFlagged) {
  // Regrouped base parameters (suffix R) combine several standard parameters with coefficients
  // of either sign; inertia-tensor entries, first moments, offsets, efficiencies and Fcm (sign
  // of the gear ratio) have no sign bound checked here; names that are not stem + number are
  // not standard parameters.
  EXPECT_TRUE(check({{"Fv1R", -5, 0.1},
                     {"ZZ1R", -5, 0.1},
                     {"Ia3R", -5, 0.1},
                     {"M2R", -5, 0.1},
                     {"XX2", -5, 0.1},
                     {"MX2", -5, 0.1},
                     {"MY3", -5, 0.1},
                     {"OFF1", -5, 0.1},
                     {"Rz3", -5, 0.1},
                     {"Fcm6", -5, 0.1},
                     {"Fv", -5, 0.1},
                     {"M", -5, 0.1},
                     {"load_cx", -5, 0.1},
                     {"Fvx1", -5, 0.1},
                     {"Rc4", NAN, NAN}})
                  .empty());
}

TEST(ImplausibleEstimates, WithoutStandardDeviationsNothingIsSignificant) {
  const std::vector<ImplausibleEstimate> found = check({{"Fc2", -100, 0.0}}, false);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_FALSE(found[0].significant);
  EXPECT_TRUE(std::isnan(found[0].std_dev));
}

TEST(ImplausibleEstimates, MismatchedSizesThrow) {
  EXPECT_THROW(implausible_estimates({"Fv1", "Fv2"}, Eigen::VectorXd::Zero(1), Eigen::VectorXd()),
               std::invalid_argument);
  EXPECT_THROW(implausible_estimates({"Fv1"}, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(2)),
               std::invalid_argument);
}

}  // namespace
}  // namespace modelgen
