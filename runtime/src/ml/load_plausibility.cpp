// The decided-by summaries and plausibility checks of load_plausibility.hpp.

#include "modelgen/ml/load_plausibility.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "modelgen/estimation/link_summary.hpp"
#include "modelgen/ml/load_parameters.hpp"

namespace modelgen {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string text(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

// Who set a quantity of the load that depends on the load parameters `which` (to_vector
// indices): known when none is an unknown, undetermined when one the data leave free.
MlDecidedBy load_decision(const MlFitResult& fit, const std::vector<int>& which) {
  bool any_unknown = false;
  for (const int k : which) {
    const auto at = std::find(fit.names.begin(), fit.names.end(), load_param_names()[k]);
    if (at == fit.names.end()) continue;
    any_unknown = true;
    if (!fit.identifiability.identifiable[static_cast<std::size_t>(at - fit.names.begin())]) {
      return MlDecidedBy::kUndetermined;
    }
  }
  return any_unknown ? MlDecidedBy::kData : MlDecidedBy::kKnown;
}

}  // namespace

const char* ml_decided_by_name(MlDecidedBy by) {
  switch (by) {
    case MlDecidedBy::kData:
      return "data";
    case MlDecidedBy::kBound:
      return "bound";
    case MlDecidedBy::kUndetermined:
      return "undetermined";
    case MlDecidedBy::kKnown:
      return "known";
  }
  return "?";
}

double arm_reach(const RigidBodyTree& tree, int body) {
  double reach = 0;
  // Up the chain to the first moving joint: its frame's own offset from the base stays out.
  for (int b = body; b >= 0; b = tree.bodies[static_cast<std::size_t>(b)].parent) {
    const Body& link = tree.bodies[static_cast<std::size_t>(b)];
    bool moving_above = false;
    for (int a = link.parent; a >= 0; a = tree.bodies[static_cast<std::size_t>(a)].parent) {
      moving_above |= tree.bodies[static_cast<std::size_t>(a)].dof_index >= 0;
    }
    if (!moving_above) break;
    const auto& t = link.fixed.translation;
    reach += std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  }
  return reach;
}

MlLoadSummary summarise_ml_load(const MlFitResult& fit, bool on_boundary, double reach,
                                const std::optional<BodyRegion>& region, int payload_link) {
  MlLoadSummary out;
  const LoadParameters& load = fit.load;
  out.reach = reach;
  out.mass_by = load_decision(fit, {0});
  out.com_by = load_decision(fit, {0, 1, 2, 3});
  out.moments_by = load_decision(fit, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  if (on_boundary && out.moments_by == MlDecidedBy::kData) out.moments_by = MlDecidedBy::kBound;
  out.mass = out.mass_by == MlDecidedBy::kUndetermined ? kNaN : load.mass;
  const bool com_known = out.com_by != MlDecidedBy::kUndetermined;
  for (int i = 0; i < 3; ++i) out.com[i] = com_known ? load.com[i] : kNaN;
  out.com_distance = Eigen::Vector3d(out.com[0], out.com[1], out.com[2]).norm();
  if (out.moments_by == MlDecidedBy::kUndetermined) {
    out.principal_moments.fill(kNaN);
  } else {
    const auto& I = load.inertia;  // xx yy zz xy xz yz, tensor entries
    Eigen::Matrix3d Ic;
    Ic << I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2];
    const Eigen::Vector3d moments =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ic, Eigen::EigenvaluesOnly).eigenvalues();
    for (int i = 0; i < 3; ++i) out.principal_moments[i] = moments[i];
  }
  if (!com_known) return out;  // nothing reported, nothing judged
  const std::string link = "link " + std::to_string(payload_link);
  if (reach > 0 && out.com_distance > reach) {
    out.warnings.push_back("the load's centre of gravity is " + text(out.com_distance) +
                           " m from " + link + "'s frame, beyond the arm's reach of " +
                           text(reach) + " m: no load this arm carries; the data do not " +
                           "determine it well (excitation, noise, a wrong payload link?)");
  }
  if (region && out.moments_by != MlDecidedBy::kUndetermined) {
    const std::array<double, 10> standard = standard_from_load(load);
    out.region_extent = region_extent(standard.data(), *region);
    out.region_guessed = region->guessed;
    if (*out.region_extent > 1) {
      out.warnings.push_back("the load reaches outside " + link + "'s region" +
                             (region->guessed ? " (a guess)" : "") + ": extent " +
                             text(*out.region_extent) + " > 1");
    }
  }
  return out;
}

std::vector<MlDriveSummary> summarise_ml_drives(const MlFitResult& fit,
                                                const std::vector<bool>& at_bound) {
  std::vector<MlDriveSummary> out;
  for (std::size_t u = 0; u < fit.names.size(); ++u) {
    if (fit.names[u].compare(0, 5, "load_") == 0) continue;
    const auto i = static_cast<Eigen::Index>(u);
    MlDriveSummary drive;
    drive.name = fit.names[u];
    drive.by = !fit.identifiability.identifiable[u] ? MlDecidedBy::kUndetermined
               : !at_bound.empty() && at_bound[u]   ? MlDecidedBy::kBound
                                                    : MlDecidedBy::kData;
    const bool reported = drive.by != MlDecidedBy::kUndetermined;
    drive.value = reported ? fit.value[i] : kNaN;
    drive.std_dev = reported ? fit.std_dev[i] : kNaN;
    out.push_back(drive);
  }
  return out;
}

}  // namespace modelgen
