#include "modelgen/model/physical_consistency.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "modelgen/model/number_text.hpp"

namespace modelgen {
namespace {

std::string text(double v) { return shortest_text(v); }

// The inertial conditions of one body, p in ParamKind order.
void check_body(const RigidBodyTree& tree, int body, const std::array<int, 10>& index,
                const Eigen::Matrix<double, 10, 1>& p, double relative_tolerance,
                std::vector<PhysicalViolation>& out) {
  const std::string& mass_name = tree.params[index[9]].name;
  const std::string& xx_name = tree.params[index[0]].name;
  const double m = p[9];
  if (p.cwiseAbs().maxCoeff() == 0) return;  // a massless body
  if (!(m > 0)) {
    out.push_back({body, mass_name,
                   "mass " + text(m) + " kg is not positive, while its first moments or inertia "
                   "are not all zero"});
    return;
  }
  Eigen::Matrix3d I_origin;
  I_origin << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
  const Eigen::Vector3d h(p[6], p[7], p[8]);
  // Parallel-axis theorem back to the centre of mass c = h / m.
  const Eigen::Matrix3d shift = (h.squaredNorm() * Eigen::Matrix3d::Identity() - h * h.transpose()) / m;
  const Eigen::Matrix3d I_com = I_origin - shift;
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                                      I_com, Eigen::EigenvaluesOnly)
                                      .eigenvalues();  // ascending
  const double scale = std::abs(I_origin.trace()) + shift.trace();
  const double tolerance = relative_tolerance * scale;
  const std::string listed = text(moments[0]) + ", " + text(moments[1]) + ", " + text(moments[2]);
  if (moments[0] < -tolerance) {
    out.push_back({body, xx_name,
                   "inertia about the centre of mass is not positive semidefinite: principal "
                   "moments " + listed + " kg m^2"});
  } else if (moments[0] + moments[1] < moments[2] - tolerance) {
    out.push_back({body, xx_name,
                   "principal moments of inertia about the centre of mass " + listed +
                       " kg m^2 break the triangle inequality (" + text(moments[0]) + " + " +
                       text(moments[1]) + " < " + text(moments[2]) + ")"});
  }
}

}  // namespace

bool must_be_nonnegative(ParamKind kind) {
  switch (kind) {
    case ParamKind::kIa:
    case ParamKind::kFv:
    case ParamKind::kFc:
    case ParamKind::kFvPos:
    case ParamKind::kFvNeg:
    case ParamKind::kFcPos:
    case ParamKind::kFcNeg:
    case ParamKind::kIam:
    case ParamKind::kFvm:
      return true;
    default:
      return false;
  }
}

std::vector<std::array<int, 10>> inertial_param_indices(const RigidBodyTree& tree) {
  std::vector<std::array<int, 10>> index(tree.bodies.size());
  for (auto& slots : index) slots.fill(-1);
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const StandardParam& param = tree.params[k];
    const int slot = inertial_slot(param.kind);
    if (slot >= 0 && param.body >= 0 && param.body < static_cast<int>(tree.bodies.size())) {
      index[param.body][slot] = static_cast<int>(k);
    }
  }
  return index;
}

std::vector<PhysicalViolation> physical_violations(const RigidBodyTree& tree,
                                                   const Eigen::VectorXd& standard,
                                                   double relative_tolerance) {
  if (standard.size() != static_cast<Eigen::Index>(tree.params.size())) {
    throw std::invalid_argument("physical_violations: " + std::to_string(standard.size()) +
                                " values for " + std::to_string(tree.params.size()) +
                                " standard parameters");
  }
  std::vector<PhysicalViolation> out;
  const auto index = inertial_param_indices(tree);
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    bool complete = true;
    Eigen::Matrix<double, 10, 1> p;
    for (int s = 0; s < 10; ++s) {
      if (index[b][s] < 0) {
        complete = false;
        break;
      }
      p[s] = standard[index[b][s]];
    }
    if (complete) check_body(tree, static_cast<int>(b), index[b], p, relative_tolerance, out);
  }
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const StandardParam& param = tree.params[k];
    const double v = standard[static_cast<Eigen::Index>(k)];
    if (must_be_nonnegative(param.kind) && v < 0) {
      out.push_back({param.body, param.name,
                     std::string(param_kind_stem(param.kind)) + " " + text(v) +
                         " is negative (a rotor inertia or friction coefficient is >= 0)"});
    }
  }
  return out;
}

}  // namespace modelgen
