// fit --physical: the physically consistent estimate beside the unconstrained one, on the
// terminal and in EST.json (modelgen/estimation/physical.hpp).
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/estimation/link_summary.hpp"
#include "modelgen/estimation/physical.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

struct PhysicalEstimate {
  PhysicalFitResult fit;
  double prior_weight = 0;
  std::vector<std::string> standard_names;
  std::vector<LinkSummary> links;
  std::vector<DriveSummary> drives;
  double rel_error_norm = 0;  ///< of the torques with the consistent estimate, set by the caller
};

/// The consistent fit of `unconstrained` for the model described by `description`, with the
/// description's a-priori values (URDF inertials, YAML `known`) as the prior. Throws
/// std::runtime_error when the description does not match the model.
PhysicalEstimate physical_estimate(const RobotModel& description, const IdentificationModel& model,
                                   const LeastSquaresResult& unconstrained,
                                   std::optional<double> prior_weight);

/// EST.json's form of a link summary.
LinkInertial link_inertial(const LinkSummary& summary);

/// EST.json's block of the consistent fit.
PhysicalBlock physical_block(const PhysicalEstimate& physical,
                             const std::vector<EstimatedParameter>& unconstrained,
                             double unconstrained_rel_error_norm);

/// The table of both estimates, the cost of consistency and the binding constraints.
/// `residual_dof` is the unconstrained fit's equations minus parameters (the weighted sum of
/// squares over sigma^2 it reached).
void print_physical(std::ostream& out, const std::vector<std::string>& base_names,
                    const LeastSquaresResult& unconstrained, double unconstrained_rel_error_norm,
                    const PhysicalEstimate& physical, long long residual_dof);

/// A warning on `err` when the consistent fit's optimiser stopped without meeting its
/// tolerance: its numbers are then not the optimum (the note under the table said so only on
/// stdout, beside a relative error norm of 1e4 at prior weight 1e-10 on the UR5).
void warn_unconverged(std::ostream& err, const PhysicalEstimate& physical);

}  // namespace modelgen::internal
