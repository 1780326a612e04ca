// Renders base parameters as "ZZ1R = ZZ1 + Ia1 + YY2 + 0.07 MZ3 + ..." lines.

#include "generator/dynamics/base_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "generator/describe.hpp"

namespace modelgen::gen {

std::string describe_base_parameters(const RobotModel& model, const BaseParameterSet& base,
                                     const ClosedFormRelations* closed) {
  std::ostringstream out;
  out << "base parameters of " << model.name << ": " << base.params.size() << " of "
      << model.tree.params.size()
      << " standard (numeric derivation: independent regressor columns in standard order)\n";
  std::size_t inertial = 0;
  for (const BaseParameter& b : base.params) {
    const ParamKind kind = model.tree.params[b.standard_index].kind;
    if (kind <= ParamKind::kM) ++inertial;
  }
  out << "  " << inertial << " inertial (built on XX..M), " << base.params.size() - inertial
      << " drive (built on Ia, friction, offset, motor parameters)\n";
  std::size_t width = 0;
  for (const BaseParameter& b : base.params) width = std::max(width, b.name.size());
  for (const BaseParameter& b : base.params) {
    std::string line = "  " + b.name + std::string(width - b.name.size(), ' ') + " =";
    bool first = true;
    for (const auto& [k, c] : b.relation) {
      const std::string& name = model.tree.params[k].name;
      const double magnitude = std::abs(c);
      line += first ? (c < 0 ? " -" : "") : (c < 0 ? " - " : " + ");
      if (first) line += " ";
      line += magnitude == 1.0 ? name : format_number(magnitude) + " " + name;
      first = false;
    }
    out << line << "\n";
    if (closed == nullptr) continue;
    const auto rules = closed->relations.find(b.standard_index);
    if (rules == closed->relations.end()) continue;
    std::string symbolic = "  " + std::string(width, ' ') + " =";
    bool first_term = true;
    for (const auto& [k, c] : b.relation) {
      const std::string& name = model.tree.params[k].name;
      std::string coefficient;
      bool negative = c < 0;
      const auto rule = rules->second.find(k);
      if (rule != rules->second.end() &&
          std::abs(closed->value(rule->second) - c) <= 1e-9 * std::max(1.0, std::abs(c))) {
        coefficient = closed->text(rule->second);
        negative = !coefficient.empty() && coefficient[0] == '-' &&
                   coefficient.find_first_of("+ ", 1) == std::string::npos;
        if (negative) coefficient.erase(0, 1);
        if (coefficient.find(' ') != std::string::npos) coefficient = "(" + coefficient + ")";
        if (coefficient == "1") coefficient.clear();
      } else if (std::abs(c) != 1.0) {
        coefficient = format_number(std::abs(c));
      }
      symbolic += first_term ? (negative ? " -" : "") : (negative ? " - " : " + ");
      if (first_term) symbolic += " ";
      symbolic += coefficient.empty() ? name : coefficient + " " + name;
      first_term = false;
    }
    // Only where the rules gave a coefficient that reads differently from its number.
    if (symbolic.substr(symbolic.find('=')) != line.substr(line.find('='))) {
      out << symbolic << "\n";
    }
  }
  if (!base.without_effect.empty()) {
    out << "standard parameters without any effect on the dynamics:";
    for (int k : base.without_effect) out << " " << model.tree.params[k].name;
    out << "\n";
  }
  return out.str();
}

}  // namespace modelgen::gen
