// Closed-form regrouping of the standard parameters for modified-DH descriptions (the rules of
// Gautier & Khalil, Khalil & Dombre ch. 14): from the last link to the first, a revolute joint
// j moves YY_j, MZ_j and M_j into link j and its antecedent, a prismatic joint moves link j's
// inertia tensor into its antecedent, and a fixed link merges whole into its antecedent. The
// coefficients are expressions of the geometric parameters d_j and r_j (alpha_j and constant
// theta_j enter as exact numbers).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/model/robot_model.hpp"
#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

struct ClosedFormRelations {
  ExprGraph graph;  ///< owns the coefficient expressions; symbols "d3", "r4", ...
  /// For each standard parameter still standing after the rules, its relation: standard index
  /// of each absorbed parameter -> coefficient expression (itself with coefficient 1).
  std::map<int, std::map<int, ExprId>> relations;
  std::map<std::string, double> geometry;  ///< values of the symbols

  double value(ExprId coefficient) const;
  /// "2*r3", "d3^2 + r3^2", "-0.5" for a coefficient.
  std::string text(ExprId coefficient) const;
};

/// The closed-form relations of an MDH description; nullopt for URDF descriptions (general
/// transforms: the numeric derivation applies alone).
std::optional<ClosedFormRelations> derive_closed_form_relations(const RobotModel& model);

}  // namespace modelgen::gen
