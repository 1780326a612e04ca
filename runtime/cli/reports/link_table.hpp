// fit --physical's per-link table: mass, centre of mass and principal moments, identified
// beside a-priori, and who decided each (modelgen/estimation/link_summary.hpp); and the warning
// for a link far from its a-priori values.
#pragma once

#include <iosfwd>
#include <vector>

#include "modelgen/estimation/link_summary.hpp"

namespace modelgen::internal {

/// A link whose mass reaches outside its geometric region: extent above kRegionExtentLimit
/// (1 plus rounding).
inline constexpr double kRegionExtentLimit = 1 + 1e-6;
bool outside_region(const LinkSummary& link);

/// The table, one block of three rows per link.
void print_link_table(std::ostream& out, const std::vector<LinkSummary>& links);

/// The drive parameters, one row each, saying which the regrouping left to the prior.
void print_drive_table(std::ostream& out, const std::vector<DriveSummary>& drives);

/// "modelid fit: warning: link 'NAME' is far from its a-priori values: ..." per such link.
void warn_far_links(std::ostream& err, const std::vector<LinkSummary>& links);

}  // namespace modelgen::internal
