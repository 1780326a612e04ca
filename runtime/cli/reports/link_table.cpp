// The per-link table of fit --physical (link_table.hpp).

#include "runtime/cli/reports/link_table.hpp"

#include <array>
#include <ostream>
#include <string>

#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {
namespace {

std::string triple(const std::array<double, 3>& v) {
  return fixed(v[0], 10, 3) + " " + fixed(v[1], 10, 3) + " " + fixed(v[2], 10, 3);
}

void row(std::ostream& out, const std::string& what, const std::string& identified,
         const std::string& a_priori, DecidedBy by) {
  out << "    " << pad(what, 17) << " " << pad(identified, 32) << " " << pad(a_priori, 32) << " "
      << decided_by_name(by) << "\n";
}

}  // namespace

bool outside_region(const LinkSummary& link) {
  return link.region_extent && *link.region_extent > kRegionExtentLimit;
}

void print_link_table(std::ostream& out, const std::vector<LinkSummary>& links) {
  if (links.empty()) return;
  out << "  links (body frame, SI units; 'by': data = the base parameters fix it, prior = the "
         "a-priori model chose among equal fits, bound = the link's region held it):\n"
      << "    " << pad("", 17) << " " << pad("identified", 32) << " " << pad("a-priori", 32)
      << " by\n";
  for (const LinkSummary& link : links) {
    out << "  " << link.body << (link.far_from_a_priori.empty() ? "" : "  (far from a-priori)")
        << (outside_region(link) ? "  (outside its geometric region)" : "") << "\n";
    const bool known = link.a_priori.has_value();
    row(out, "mass", fixed(link.identified.mass, 10, 4),
        known ? fixed(link.a_priori->mass, 10, 4) : "-", link.mass_by);
    row(out, "centre of mass", triple(link.identified.com),
        known ? triple(link.a_priori->com) : "-", link.com_by);
    row(out, "principal moments", triple(link.identified.principal_moments),
        known ? triple(link.a_priori->principal_moments) : "-", link.moments_by);
    if (link.region_extent) {
      out << "    " << pad("region extent", 17) << " " << fixed(*link.region_extent, 10, 3)
          << "  (root mean square over the mass, in units of the ellipsoid "
          << (!link.region_guessed ? "from the geometry"
              : link.region_at_joint
                  ? "guessed: a sphere about the joint, which has no next joint or tool frame"
                  : "guessed from the segments to the next joints (no shapes or region given)")
          << (known                  ? "; not enforced: the a-priori values hold this link)\n"
              : link.region_rejected ? "; not enforced: the data reject the guess)\n"
                                     : "; at most 1, kept by the fit)\n");
    }
  }
}

void print_drive_table(std::ostream& out, const std::vector<DriveSummary>& drives) {
  if (drives.empty()) return;
  out << "  drive parameters (by: data = identified alone, prior = regrouped with others: the "
         "value is the prior's, not the data's):\n"
      << "    " << pad("", 9) << " " << pad("identified", 14) << " " << pad("a-priori", 14)
      << " by\n";
  for (const DriveSummary& drive : drives) {
    out << "    " << pad(drive.name, 9) << " " << fixed(drive.identified, 14, 5) << " "
        << (drive.a_priori ? fixed(*drive.a_priori, 14, 5) : pad("-", 14)) << " "
        << decided_by_name(drive.by);
    if (drive.by == DecidedBy::kPrior && !drive.regrouped_with.empty()) {
      out << " (regrouped with";
      for (const std::string& name : drive.regrouped_with) out << " " << name;
      out << ")";
    }
    out << "\n";
  }
}

namespace {

// Why a far link is where it is. Far by the data's decision points at the description; far in
// what the regrouping leaves to the prior (no excitation decides it alone) points at the base
// parameters in which the data reject the a-priori values: the prior spread their
// disagreement over the directions the data leave free.
std::string far_link_reason(const LinkSummary& link) {
  const bool mass_data = link.mass_by == DecidedBy::kData;
  const bool com_data = link.com_by == DecidedBy::kData;
  std::string out;
  if (mass_data && com_data) {
    out = "the data decided its mass and centre of mass";
  } else {
    out = std::string("its ") +
          (!mass_data && !com_data ? "mass and centre of mass are"
           : !mass_data            ? "mass is"
                                   : "centre of mass is") +
          " regrouped with other parameters, which no excitation separates: the prior chose " +
          (!mass_data && !com_data ? "them" : "it");
  }
  if (!link.a_priori_rejected_in.empty()) {
    out += "; the data reject the a-priori values in ";
    for (std::size_t i = 0; i < link.a_priori_rejected_in.size(); ++i) {
      out += (i ? ", " : "") + link.a_priori_rejected_in[i];
    }
  }
  return out + ": check the description's inertials";
}

}  // namespace

void warn_far_links(std::ostream& err, const std::vector<LinkSummary>& links) {
  for (const LinkSummary& link : links) {
    if (outside_region(link)) {
      err << "modelid fit: warning: link '" << link.body
          << "' reaches outside the region its geometry gives (extent "
          << fixed(*link.region_extent, 0, 3) << " of its ellipsoid; "
          << (link.a_priori ? "the region is not enforced where a-priori values are given: "
                              "check them against the geometry"
                            : "the fit did not meet its tolerance")
          << ")\n";
    }
  }
  for (const LinkSummary& link : links) {
    if (link.far_from_a_priori.empty()) continue;
    err << "modelid fit: warning: link '" << link.body << "' is far from its a-priori values: ";
    for (std::size_t i = 0; i < link.far_from_a_priori.size(); ++i) {
      err << (i ? "; " : "") << link.far_from_a_priori[i];
    }
    err << " (" << far_link_reason(link) << ")\n";
  }
}

}  // namespace modelgen::internal
