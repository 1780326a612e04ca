// Sign checks of estimates that stand for single standard parameters: friction and rotor
// inertia are dissipative/kinetic-energy coefficients, never negative; a mass is positive.

#include "modelgen/estimation/plausibility.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace modelgen {

namespace {

// The quantity of `name` when it is a stem of the table followed by a joint number only.
// Regrouped base parameters end in R (ZZ1R, Fv1R): sums of several standard parameters with
// coefficients of either sign, so their sign says nothing and they never match here.
std::optional<SignedQuantity> quantity_of(std::string_view name) {
  if (name == "load_m") return SignedQuantity::kMass;
  // Longest stems first so that "Fvp3" is not read as "Fv" + "p3" (which would not match
  // anyway, the rest must be digits). Fcm is left out: Fcm = ratio * Fc_rotor takes the gear
  // ratio's sign (modelgen/model/rigid_body_tree.hpp, CoupledMotor).
  struct Stem {
    std::string_view text;
    SignedQuantity quantity;
  };
  static constexpr std::array<Stem, 13> kStems = {{
      {"Fvp", SignedQuantity::kFrictionCoefficient},
      {"Fvn", SignedQuantity::kFrictionCoefficient},
      {"Fcp", SignedQuantity::kFrictionCoefficient},
      {"Fcn", SignedQuantity::kFrictionCoefficient},
      {"Fvm", SignedQuantity::kFrictionCoefficient},
      {"Iam", SignedQuantity::kRotorInertia},
      {"Fv", SignedQuantity::kFrictionCoefficient},
      {"Fc", SignedQuantity::kFrictionCoefficient},
      {"Rv", SignedQuantity::kFrictionCoefficient},
      {"Rc", SignedQuantity::kFrictionCoefficient},
      {"Ia", SignedQuantity::kRotorInertia},
      {"JM", SignedQuantity::kRotorInertia},
      {"M", SignedQuantity::kMass},
  }};
  for (const Stem& stem : kStems) {
    if (name.size() <= stem.text.size() || name.substr(0, stem.text.size()) != stem.text) {
      continue;
    }
    const std::string_view number = name.substr(stem.text.size());
    bool digits = true;
    for (const char c : number) digits = digits && std::isdigit(static_cast<unsigned char>(c));
    if (digits) return stem.quantity;
  }
  return std::nullopt;
}

}  // namespace

std::vector<ImplausibleEstimate> implausible_estimates(const std::vector<std::string>& names,
                                                       const Eigen::VectorXd& value,
                                                       const Eigen::VectorXd& std_dev) {
  const auto n = static_cast<Eigen::Index>(names.size());
  if (value.size() != n || (std_dev.size() != 0 && std_dev.size() != n)) {
    throw std::invalid_argument("implausible_estimates: " + std::to_string(names.size()) +
                                " names, " + std::to_string(value.size()) + " values and " +
                                std::to_string(std_dev.size()) + " standard deviations");
  }
  std::vector<ImplausibleEstimate> out;
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::string& name = names[static_cast<std::size_t>(k)];
    const std::optional<SignedQuantity> quantity = quantity_of(name);
    const double v = value[k];
    if (!quantity || !std::isfinite(v)) continue;
    const bool strict = *quantity == SignedQuantity::kMass;
    const auto impossible = [strict](double x) { return strict ? x <= 0 : x < 0; };
    if (!impossible(v)) continue;
    const double sd = std_dev.size() == 0 ? NAN : std_dev[k];
    ImplausibleEstimate e;
    e.name = name;
    e.value = v;
    e.std_dev = sd;
    e.quantity = *quantity;
    // value +- 3 std: where a normally distributed estimate lies 99.7 % of the time.
    e.significant = std::isfinite(sd) && impossible(v + 3 * std::abs(sd));
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace modelgen
