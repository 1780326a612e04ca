// What `modelid fit --method ml` prints and writes: one approach in detail, or the approaches
// side by side as Swevers et al. 2002 compare them (Table 2: load estimates and their errors,
// Table 3: rms actuator torque errors), and EST.json.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <ostream>
#include <string>

#include <Eigen/Core>

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/linear_route.hpp"
#include "modelgen/ml/load_plausibility.hpp"
#include "modelgen/ml/physical_fit.hpp"

namespace modelgen::internal {

/// What fit --physical adds to an approach: the unconstrained estimate, what was wrong with it,
/// and what consistency cost.
struct MlPhysicalRun {
  double prior_weight = 0;
  MlFitResult unconstrained;
  std::vector<std::string> violations;  ///< of the unconstrained estimate
  MlPhysicalResult result;              ///< result.fit is MlRun::fit
  double seconds = 0;                   ///< wall time of the constrained search
};

/// One approach's result.
struct MlRun {
  int approach = 0;     ///< 1, 2 or 3 (section 4)
  MlFitResult fit;      ///< approach 1: LinearRoute::fit; with --physical the consistent fit
  double seconds = 0;   ///< wall time of the fit
  std::string summary;  ///< one line on how it was obtained
  std::optional<MlPhysicalRun> physical;  ///< with --physical
  /// Who decided the load (when it is unknown) and the drive unknowns, and whether the load is
  /// plausible (modelgen/ml/load_plausibility.hpp).
  std::optional<MlLoadSummary> load_summary;
  std::vector<MlDriveSummary> drives;
  /// Measured minus modelled motor torques at `fit`'s values (MlProblem::torque_errors: samples
  /// of all experiments x dof, 0 on the motors not fitted), for the residual check.
  Eigen::MatrixXd torque_errors;
};

/// Exact values by ml_param_names() name (load_m, Rv3, ...) from --truth; empty without it.
using MlTruth = std::map<std::string, double>;

/// One approach: identifiability, the load (centre of gravity in mm), the drive parameters with
/// standard deviations, "not identifiable" where there is no number, the exact value and error
/// where `truth` has one, the rms torque errors per fitted motor.
void print_ml_run(std::ostream& out, const MlRun& run, int payload_link, const MlTruth& truth);

/// The runs side by side: load and drive parameter estimates +- standard deviation (Table 2,
/// with an exact column and a table of errors when `truth` is given), rms torque errors per
/// fitted motor (Table 3), rank, iterations and time.
void print_ml_comparison(std::ostream& out, const std::vector<MlRun>& runs, int payload_link,
                         const MlTruth& truth);

/// Warnings on `err` for the run's estimates that cannot be physical values (negative Rv, Rc,
/// JM; a load mass that is not positive), each line naming the approach when `name_approach`.
void warn_implausible_ml_estimates(std::ostream& err, const MlRun& run, bool name_approach);

/// With --physical: per run, what the unconstrained estimate violated, the cost of consistency
/// (eq. 18's weighted sum of squares, noise variances as units) and the binding constraints.
void print_ml_physical(std::ostream& out, const std::vector<MlRun>& runs);

/// EST.json's description of one run: method, load with std and warnings, the other unknowns,
/// rms per axis, identifiability, iterations, seconds; with --physical the consistent estimate
/// and a "physical" block (prior weight, cost increase, binding constraints, the unconstrained
/// estimate's violations and the unconstrained estimate itself).
nlohmann::json ml_run_json(const MlRun& run);

}  // namespace modelgen::internal
