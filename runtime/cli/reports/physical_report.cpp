#include "runtime/cli/reports/physical_report.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "modelgen/estimation/a_priori_disagreement.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/reports/link_table.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// Each link with a-priori values: the base parameters it enters where the data reject them.
void attach_a_priori_disagreement(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                                  const std::vector<std::optional<double>>& a_priori,
                                  const LeastSquaresResult& unconstrained,
                                  const std::vector<std::string>& base_names,
                                  std::vector<LinkSummary>& links) {
  const auto per_body =
      a_priori_disagreement(inertial_param_indices(tree), K, a_priori, unconstrained.value,
                            unconstrained.std_dev, base_names, kRejectingSd);
  for (LinkSummary& link : links) {
    if (!link.a_priori) continue;
    for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
      if (tree.bodies[b].name == link.body) {
        link.a_priori_rejected_in = disagreement_words(per_body[b], 3);
      }
    }
  }
}

}  // namespace

PhysicalEstimate physical_estimate(const RobotModel& description, const IdentificationModel& model,
                                   const LeastSquaresResult& unconstrained,
                                   std::optional<double> prior_weight) {
  if (description.param_names() != model.standard_param_names()) {
    throw std::runtime_error("--physical: the description's standard parameters differ from "
                             "the model's; give the description file the model was made from");
  }
  PhysicalFitOptions options;
  options.prior_weight = prior_weight;
  // The default weight rule's scale: the weighted sum of squares is (equations - b) sigma^2.
  const long long residual_dof =
      unconstrained.equations - static_cast<long long>(unconstrained.value.size());
  if (residual_dof > 0) options.residual_sum_of_squares = static_cast<double>(residual_dof);
  options.regions = description.body_regions;
  PhysicalEstimate out;
  out.standard_names = model.standard_param_names();
  const Eigen::MatrixXd K = regrouping_matrix(model);
  out.fit = fit_physical(description.tree, K, unconstrained.value, unconstrained.information,
                         description.known_values, options);
  out.prior_weight = out.fit.prior_weight;
  out.links = summarise_links(description.tree, K, out.fit, description.known_values,
                              description.body_regions);
  attach_a_priori_disagreement(description.tree, K, description.known_values, unconstrained,
                               model.base_param_names(), out.links);
  out.drives = summarise_drives(description.tree, K, out.fit, description.known_values);
  return out;
}

LinkInertial link_inertial(const LinkSummary& summary) {
  LinkInertial link;
  link.body = summary.body;
  link.mass = summary.identified.mass;
  link.com = summary.identified.com;
  link.inertia_com = summary.identified.inertia_com;
  link.principal_moments = summary.identified.principal_moments;
  if (summary.a_priori) {
    link.a_priori = LinkInertial::APriori{summary.a_priori->mass, summary.a_priori->com,
                                          summary.a_priori->principal_moments};
  }
  link.mass_decided_by = decided_by_name(summary.mass_by);
  link.com_decided_by = decided_by_name(summary.com_by);
  link.moments_decided_by = decided_by_name(summary.moments_by);
  link.far_from_a_priori = summary.far_from_a_priori;
  link.a_priori_rejected_in = summary.a_priori_rejected_in;
  link.region_extent = summary.region_extent;
  return link;
}

PhysicalBlock physical_block(const PhysicalEstimate& physical,
                             const std::vector<EstimatedParameter>& unconstrained,
                             double unconstrained_rel_error_norm) {
  PhysicalBlock block;
  block.prior_weight = physical.prior_weight;
  block.prior_weight_rule = physical.fit.prior_weight_automatic ? "default" : "given";
  block.cost_increase = physical.fit.cost_increase;
  block.converged = physical.fit.converged;
  block.unconstrained_rel_error_norm = unconstrained_rel_error_norm;
  block.binding_constraints = physical.fit.active_constraints;
  block.prior_notes = physical.fit.prior_notes;
  block.unconstrained = unconstrained;
  for (std::size_t k = 0; k < physical.standard_names.size(); ++k) {
    block.standard.emplace_back(physical.standard_names[k],
                                physical.fit.standard[static_cast<Eigen::Index>(k)]);
  }
  for (const LinkSummary& link : physical.links) block.links.push_back(link_inertial(link));
  for (const DriveSummary& drive : physical.drives) {
    block.drives.push_back(DriveParameter{drive.name, drive.identified, drive.a_priori,
                                          decided_by_name(drive.by), drive.regrouped_with});
  }
  return block;
}

void print_physical(std::ostream& out, const std::vector<std::string>& base_names,
                    const LeastSquaresResult& unconstrained, double unconstrained_rel_error_norm,
                    const PhysicalEstimate& physical, long long residual_dof) {
  const PhysicalFitResult& fit = physical.fit;
  out << "physically consistent estimate (--physical, prior weight "
      << shortest(physical.prior_weight)
      << (fit.prior_weight_automatic ? " by the default rule" : "") << "):\n"
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
  print_link_table(out, physical.links);
  for (const std::string& note : fit.prior_notes) out << "  note: " << note << "\n";
  print_drive_table(out, physical.drives);
  if (!fit.converged) {
    out << "  note: the optimiser stopped after " << fit.iterations
        << " Newton steps without meeting its tolerance\n";
  }
}

void warn_unconverged(std::ostream& err, const PhysicalEstimate& physical) {
  if (physical.fit.converged) return;
  err << "modelid fit: warning: the physically consistent fit stopped after "
      << physical.fit.iterations
      << " Newton steps without meeting its tolerance: its estimate is not the optimum and may be "
         "far from it";
  // Below the reference weight the prior's pull falls under the rounding of the data term
  // (physical_barrier.cpp): on the UR5 and Panda runs 1e-8 and 1e-10 stopped so.
  if (physical.prior_weight < kReferencePriorWeight) {
    err << " (prior weight " << physical.prior_weight << ", below " << kReferencePriorWeight
        << ": too weak for the solver to resolve)";
  }
  err << "\n";
}

}  // namespace modelgen::internal
