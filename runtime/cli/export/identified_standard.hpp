// The physically consistent standard parameters of an estimate (the "standard" block fit
// --physical writes into EST.json), read for `modelid export`: every standard parameter of the
// description, checked to be those of a physical robot and to give the estimate's base
// parameters.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::internal {

struct IdentifiedStandard {
  Eigen::VectorXd values;  ///< one per standard parameter, in the model's order
  std::string method;      ///< the estimate's "method", empty for hand-written files
  /// What the data decided, one line per link of the estimate's "links" and one for the
  /// drive parameters of its "drives" the data did not decide, e.g. "link 'J2': the data
  /// decided its mass, centre of mass; the a-priori model its principal moments"; empty for
  /// files without them.
  std::vector<std::string> decided;
  /// false when the estimate's "physical" block says its optimiser stopped short
  /// ("converged": false): its values are then not the fit's optimum.
  bool converged = true;
};

/// Reads the "standard" block of the estimate at `path` for `description` (the model made
/// from it is `model`). Throws InputError naming the file, line and column when: the estimate
/// belongs to another description (description_sha256 differs); it has no "standard" block (a
/// fit without --physical: the message says to refit with it); a name is not a standard
/// parameter of the description or a value is not a number; a standard parameter is missing;
/// the "parameters" are not those the standard set gives; the set breaks a physical-consistency
/// condition (physical_violations: the link and the condition are named).
IdentifiedStandard read_identified_standard(const std::string& path, const RobotModel& description,
                                            const IdentificationModel& model);

}  // namespace modelgen::internal
