// Renders base parameters as "ZZ1R = ZZ1 + Ia1 + YY2 + 0.07 MZ3 + ..." lines.

#include "generator/dynamics/base_report.hpp"

#include <cmath>
#include <sstream>

#include "generator/description/describe.hpp"

namespace modelgen::gen {

std::string describe_base_parameters(const RobotModel& model, const BaseParameterSet& base) {
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
  }
  if (!base.without_effect.empty()) {
    out << "standard parameters without any effect on the dynamics:";
    for (int k : base.without_effect) out << " " << model.tree.params[k].name;
    out << "\n";
  }
  return out.str();
}

}  // namespace modelgen::gen
