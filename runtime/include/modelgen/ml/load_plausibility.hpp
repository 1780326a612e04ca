// What a maximum-likelihood fit (fit.hpp, physical_fit.hpp) decided of the load and the drive
// unknowns, in the terms of the least-squares link table (modelgen/estimation/link_summary.hpp):
// mass, centre of gravity and principal moments of the load, each drive unknown, and who set
// each. The ML problem has no prior towards a-priori values of its unknowns (the description
// gives none: a payload has no nominal inertials, friction and efficiencies no a-priori values),
// so a quantity is set by the data, by a bound of the consistent fit, or by nobody (the data
// leave a direction free: no number is reported). Also whether the load is plausible: its centre
// of gravity within the arm's reach of the payload link's frame and its mass inside the payload
// link's region when the description gives one.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/ml/fit.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// Who set a quantity: the data (every unknown it depends on identifiable and free), a bound of
/// the consistent fit (a drive unknown held on its bound, the load's principal moments on the
/// boundary of the consistent set), nobody (the data leave a direction it depends on free; the
/// value is not reported), or it was known a priori (--known).
enum class MlDecidedBy { kData, kBound, kUndetermined, kKnown };

const char* ml_decided_by_name(MlDecidedBy by);  ///< "data", "bound", "undetermined", "known"

struct MlLoadSummary {
  double mass = 0;                            ///< kg (NaN when undetermined)
  std::array<double, 3> com{};                ///< m, payload link frame
  std::array<double, 3> principal_moments{};  ///< about the centre of gravity, ascending
  MlDecidedBy mass_by = MlDecidedBy::kData, com_by = MlDecidedBy::kData,
              moments_by = MlDecidedBy::kData;
  double com_distance = 0;  ///< m from the payload link's frame origin
  double reach = 0;         ///< m, arm_reach() of the payload link
  /// With a region of the payload link in the description: the load's extent in it
  /// (region_extent of link_summary.hpp; above 1 some mass lies outside).
  std::optional<double> region_extent;
  bool region_guessed = false;
  /// The load is implausible: centre of gravity beyond the reach, mass outside the region.
  std::vector<std::string> warnings;
};

struct MlDriveSummary {
  std::string name;
  double value = 0, std_dev = 0;  ///< NaN when undetermined
  MlDecidedBy by = MlDecidedBy::kData;
};

/// The arm's reach at `body`: the summed lengths of the fixed offsets from the first moving
/// joint's frame to `body`'s frame (the longest distance the chain can put between them; the
/// base's own offset to the first joint is left out).
double arm_reach(const RigidBodyTree& tree, int body);

/// The load of `fit` (fit.has_load) summarised: `on_boundary` when the consistent fit left the
/// load's pseudo-inertia on the boundary of the cone; `reach` from arm_reach; `region` the
/// payload link's region from the description, if any. `payload_link` (1-based) names it in
/// the warnings.
MlLoadSummary summarise_ml_load(const MlFitResult& fit, bool on_boundary, double reach,
                                const std::optional<BodyRegion>& region, int payload_link);

/// One summary per unknown of `fit` that is not a load parameter, in fit.names order;
/// `at_bound` (empty, or one per unknown) marks those the consistent fit held on their bound.
std::vector<MlDriveSummary> summarise_ml_drives(const MlFitResult& fit,
                                                const std::vector<bool>& at_bound);

}  // namespace modelgen
