#include "runtime/cli/reports/physical_report.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "modelgen/model/physical_consistency.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

PhysicalEstimate physical_estimate(const RobotModel& description, const IdentificationModel& model,
                                   const LeastSquaresResult& unconstrained, double prior_weight) {
  if (description.param_names() != model.standard_param_names()) {
    throw std::runtime_error("--physical: the description's standard parameters differ from "
                             "the model's; give the description file the model was made from");
  }
  PhysicalFitOptions options;
  options.prior_weight = prior_weight;
  PhysicalEstimate out;
  out.prior_weight = prior_weight;
  out.standard_names = model.standard_param_names();
  out.fit = fit_physical(description.tree, regrouping_matrix(model), unconstrained.value,
                         unconstrained.information, description.known_values, options);
  out.links = link_inertials(description.tree, out.fit.standard);
  return out;
}

std::vector<LinkInertial> link_inertials(const RigidBodyTree& tree, const Eigen::VectorXd& standard) {
  std::vector<LinkInertial> out;
  const auto indices = inertial_param_indices(tree);
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    const auto& index = indices[b];
    if (std::find(index.begin(), index.end(), -1) != index.end()) continue;
    LinkInertial link;
    link.body = tree.bodies[b].name;
    link.mass = standard[index[9]];
    const Eigen::Vector3d h(standard[index[6]], standard[index[7]], standard[index[8]]);
    Eigen::Matrix3d I;
    I << standard[index[0]], standard[index[1]], standard[index[2]], standard[index[1]],
        standard[index[3]], standard[index[4]], standard[index[2]], standard[index[4]],
        standard[index[5]];
    if (link.mass > 0) {
      const Eigen::Vector3d c = h / link.mass;
      // Parallel-axis theorem back to the centre of mass.
      const Eigen::Matrix3d Ic =
          I - link.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
      link.com = {c.x(), c.y(), c.z()};
      link.inertia_com = {Ic(0, 0), Ic(0, 1), Ic(0, 2), Ic(1, 1), Ic(1, 2), Ic(2, 2)};
    }
    out.push_back(link);
  }
  return out;
}

PhysicalBlock physical_block(const PhysicalEstimate& physical,
                             const std::vector<EstimatedParameter>& unconstrained,
                             double unconstrained_rel_error_norm) {
  PhysicalBlock block;
  block.prior_weight = physical.prior_weight;
  block.cost_increase = physical.fit.cost_increase;
  block.unconstrained_rel_error_norm = unconstrained_rel_error_norm;
  block.binding_constraints = physical.fit.active_constraints;
  block.unconstrained = unconstrained;
  for (std::size_t k = 0; k < physical.standard_names.size(); ++k) {
    block.standard.emplace_back(physical.standard_names[k],
                                physical.fit.standard[static_cast<Eigen::Index>(k)]);
  }
  block.links = physical.links;
  return block;
}

void print_physical(std::ostream& out, const std::vector<std::string>& base_names,
                    const LeastSquaresResult& unconstrained, double unconstrained_rel_error_norm,
                    const PhysicalEstimate& physical, long long residual_dof) {
  const PhysicalFitResult& fit = physical.fit;
  out << "physically consistent estimate (--physical, prior weight "
      << fixed(physical.prior_weight, 0, 3) << "):\n"
      << "  parameter   unconstrained          std    consistent          std\n";
  for (std::size_t b = 0; b < base_names.size(); ++b) {
    const auto i = static_cast<Eigen::Index>(b);
    const bool moved = std::abs(fit.base[i] - unconstrained.value[i]) > unconstrained.std_dev[i];
    out << "  " << pad(base_names[b], 9) << " " << fixed(unconstrained.value[i], 15, 6) << " "
        << fixed(unconstrained.std_dev[i], 12, 3) << " " << fixed(fit.base[i], 13, 6) << " "
        << fixed(fit.base_std_dev[i], 12, 3) << (moved ? " <" : "") << "\n";
  }
  out << "  < moved by more than one standard deviation\n";
  const double ratio = residual_dof > 0 ? fit.cost_increase / static_cast<double>(residual_dof) : 0;
  out << "  cost of consistency: the weighted sum of squares grows by "
      << fixed(fit.cost_increase, 0, 4) << " sigma^2 (" << fixed(100 * ratio, 0, 3)
      << " % of the unconstrained fit's)\n"
      << "  relative error norm of the torques " << fixed(physical.rel_error_norm, 0, 4)
      << " (unconstrained " << fixed(unconstrained_rel_error_norm, 0, 4) << ")\n";
  if (fit.active_constraints.empty()) {
    out << "  binding constraints: none (the unconstrained estimate is consistent to the "
           "data's precision)\n";
  } else {
    out << "  binding constraints:";
    for (const std::string& c : fit.active_constraints) out << "\n    " << c;
    out << "\n";
  }
  if (!fit.converged) {
    out << "  note: the optimiser stopped after " << fit.iterations
        << " Newton steps without meeting its tolerance\n";
  }
}

}  // namespace modelgen::internal
