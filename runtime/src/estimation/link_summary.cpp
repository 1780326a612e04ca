// The per-link summary of link_summary.hpp. Whether the data decided a quantity: its gradient
// in the standard parameters, scaled as the prior term scales them (D), has a negligible part
// in the null space of K D, the directions no base parameter sees.

#include "modelgen/estimation/link_summary.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "modelgen/model/physical_consistency.hpp"
#include "runtime/src/estimation/physical_prior.hpp"

namespace modelgen {
namespace {

// Null-space share above which the prior, not the data, decided a quantity.
constexpr double kPriorShare = 0.01;

DecidedBy decided_by(const Eigen::MatrixXd& N, const Eigen::VectorXd& scale,
                     const std::vector<Eigen::VectorXd>& gradients) {
  for (const Eigen::VectorXd& g : gradients) {
    const Eigen::VectorXd scaled = g.cwiseProduct(scale);
    const double length = scaled.norm();
    if (length > 0 && (N.transpose() * scaled).norm() > kPriorShare * length) {
      return DecidedBy::kPrior;
    }
  }
  return DecidedBy::kData;
}

// Gradients of the principal moments with respect to the body's ten parameters, by central
// differences with steps of 1e-6 of each parameter's prior scale (the moments are smooth away
// from repeated ones; at a repeated one either side's derivative serves the classification).
std::vector<Eigen::VectorXd> moment_gradients(const std::array<int, 10>& index,
                                              const Eigen::VectorXd& standard,
                                              const Eigen::VectorXd& scale) {
  std::vector<Eigen::VectorXd> out(3, Eigen::VectorXd::Zero(standard.size()));
  double p[10];
  for (int s = 0; s < 10; ++s) p[s] = standard[index[s]];
  for (int s = 0; s < 10; ++s) {
    const double h = 1e-6 * scale[index[s]];
    double plus[10], minus[10];
    std::copy(p, p + 10, plus);
    std::copy(p, p + 10, minus);
    plus[s] += h;
    minus[s] -= h;
    const LinkQuantities up = link_quantities(plus), down = link_quantities(minus);
    for (int i = 0; i < 3; ++i) {
      out[static_cast<std::size_t>(i)][index[s]] =
          (up.principal_moments[static_cast<std::size_t>(i)] -
           down.principal_moments[static_cast<std::size_t>(i)]) /
          (2 * h);
    }
  }
  return out;
}

}  // namespace

const char* decided_by_name(DecidedBy by) {
  switch (by) {
    case DecidedBy::kData:
      return "data";
    case DecidedBy::kBound:
      return "bound";
    case DecidedBy::kPrior:
      break;
  }
  return "prior";
}

std::vector<std::string> far_from_a_priori(const LinkQuantities& identified,
                                           const LinkQuantities& a_priori) {
  std::vector<std::string> out;
  char text[160];
  if (a_priori.mass > 0) {
    const double ratio = identified.mass / a_priori.mass;
    if (ratio > kFarMassFactor || ratio < 1 / kFarMassFactor) {
      std::snprintf(text, sizeof text, "mass %.3g x its a-priori value", ratio);
      out.emplace_back(text);
    }
    double distance = 0;
    for (int i = 0; i < 3; ++i) {
      const double d =
          identified.com[static_cast<std::size_t>(i)] - a_priori.com[static_cast<std::size_t>(i)];
      distance += d * d;
    }
    distance = std::sqrt(distance);
    if (distance > kFarComDistance) {
      std::snprintf(text, sizeof text, "centre of mass %.3g m from its a-priori position",
                    distance);
      out.emplace_back(text);
    }
  }
  return out;
}

LinkQuantities link_quantities(const double* p) {
  LinkQuantities q;
  q.mass = p[9];
  if (!(q.mass > 0)) return q;
  const Eigen::Vector3d c = Eigen::Vector3d(p[6], p[7], p[8]) / q.mass;
  Eigen::Matrix3d I;
  I << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
  // Parallel-axis theorem back to the centre of mass.
  const Eigen::Matrix3d Ic =
      I - q.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  q.com = {c.x(), c.y(), c.z()};
  q.inertia_com = {Ic(0, 0), Ic(0, 1), Ic(0, 2), Ic(1, 1), Ic(1, 2), Ic(2, 2)};
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ic, Eigen::EigenvaluesOnly).eigenvalues();
  q.principal_moments = {moments[0], moments[1], moments[2]};
  return q;
}

double region_extent(const double* p, const BodyRegion& region) {
  const double m = p[9];
  if (!(m > 0)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix3d I;
  I << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
  const Eigen::Matrix3d second = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;  // int x x' dm
  const Eigen::Vector3d h(p[6], p[7], p[8]),
      c(region.centre[0], region.centre[1], region.centre[2]);
  const Eigen::Vector3d a =
      Eigen::Vector3d(region.semi_axes[0], region.semi_axes[1], region.semi_axes[2])
          .cwiseAbs2()
          .cwiseInverse();
  // int (x - c)' A (x - c) dm, A = diag(a)
  const double spread = (a.asDiagonal() * second).trace() - 2 * c.dot(a.asDiagonal() * h) +
                        m * c.dot(a.asDiagonal() * c);
  return std::sqrt(std::max(spread, 0.0) / m);
}

std::vector<LinkSummary> summarise_links(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                                         const PhysicalFitResult& fit,
                                         const std::vector<std::optional<double>>& a_priori,
                                         const std::vector<std::optional<BodyRegion>>& regions) {
  const Eigen::MatrixXd N = detail::scaled_null_space(K, fit.prior_scale);
  const auto n = fit.standard.size();
  std::vector<LinkSummary> out;
  const auto indices = inertial_param_indices(tree);
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    const auto& index = indices[b];
    if (std::find(index.begin(), index.end(), -1) != index.end()) continue;
    LinkSummary link;
    link.body = tree.bodies[b].name;
    double p[10], known[10];
    bool all_known = true;
    for (int s = 0; s < 10; ++s) {
      p[s] = fit.standard[index[s]];
      const auto& value = a_priori[static_cast<std::size_t>(index[s])];
      all_known = all_known && value.has_value();
      known[s] = value.value_or(0.0);
    }
    link.identified = link_quantities(p);
    if (all_known) link.a_priori = link_quantities(known);
    const double m = link.identified.mass;
    link.mass_by = decided_by(N, fit.prior_scale, {Eigen::VectorXd::Unit(n, index[9])});
    if (m > 0) {
      std::vector<Eigen::VectorXd> com(3, Eigen::VectorXd::Zero(n));
      for (int i = 0; i < 3; ++i) {  // d(h_i / m) = (e_h_i - c_i e_m) / m
        com[static_cast<std::size_t>(i)][index[6 + i]] = 1 / m;
        com[static_cast<std::size_t>(i)][index[9]] = -p[6 + i] / (m * m);
      }
      link.com_by = decided_by(N, fit.prior_scale, com);
      link.moments_by =
          decided_by(N, fit.prior_scale, moment_gradients(index, fit.standard, fit.prior_scale));
    }
    // What the data leave free of a body its region holds, the region decided.
    if (std::find(fit.region_bound_bodies.begin(), fit.region_bound_bodies.end(),
                  static_cast<int>(b)) != fit.region_bound_bodies.end()) {
      for (DecidedBy* by : {&link.mass_by, &link.com_by, &link.moments_by}) {
        if (*by == DecidedBy::kPrior) *by = DecidedBy::kBound;
      }
    }
    if (link.a_priori) link.far_from_a_priori = far_from_a_priori(link.identified, *link.a_priori);
    if (b < regions.size() && regions[b]) {
      link.region_extent = region_extent(p, *regions[b]);
      link.region_guessed = regions[b]->guessed;
      link.region_at_joint = regions[b]->at_joint;
      link.region_rejected =
          std::find(fit.rejected_region_bodies.begin(), fit.rejected_region_bodies.end(),
                    static_cast<int>(b)) != fit.rejected_region_bodies.end();
    }
    out.push_back(std::move(link));
  }
  return out;
}

std::vector<DriveSummary> summarise_drives(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                                           const PhysicalFitResult& fit,
                                           const std::vector<std::optional<double>>& a_priori) {
  const Eigen::MatrixXd N = detail::scaled_null_space(K, fit.prior_scale);
  const auto n = fit.standard.size();
  // Rounding-level coefficients of the regrouping are no regrouping (as in null_space_of).
  const double small = 1e-10 * std::max(K.cwiseAbs().maxCoeff(), 1e-300);
  std::vector<DriveSummary> out;
  for (Eigen::Index k = 0; k < n; ++k) {
    const StandardParam& param = tree.params[static_cast<std::size_t>(k)];
    if (is_inertial(param.kind)) continue;
    DriveSummary drive;
    drive.name = param.name;
    drive.identified = fit.standard[k];
    drive.a_priori = a_priori[static_cast<std::size_t>(k)];
    drive.by = decided_by(N, fit.prior_scale, {Eigen::VectorXd::Unit(n, k)});
    for (Eigen::Index other = 0; other < n; ++other) {
      if (other == k) continue;
      for (Eigen::Index j = 0; j < K.rows(); ++j) {
        if (std::abs(K(j, k)) > small && std::abs(K(j, other)) > small) {
          drive.regrouped_with.push_back(tree.params[static_cast<std::size_t>(other)].name);
          break;
        }
      }
    }
    out.push_back(std::move(drive));
  }
  return out;
}

}  // namespace modelgen
