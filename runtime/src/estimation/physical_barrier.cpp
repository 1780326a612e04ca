// The barrier method of physical_barrier.hpp: the log det barrier of each body's pseudo-inertia
// cone and the log barrier of the bounded parameters, with gradient and Hessian in closed form
// (d2(-log det S) = tr(S^-1 E_e S^-1 E_f)), and Newton's method with backtracking on
// t f + barrier (Boyd & Vandenberghe, algorithm 11.1). A region adds -log r'x, r'x = tr(P Q):
// gradient -r / r'x, Hessian r r' / (r'x)^2.

#include "runtime/src/estimation/physical_barrier.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"

namespace modelgen::detail {
namespace {

constexpr double kSqrt2 = 1.4142135623730951;
constexpr int kEntryRow[10] = {0, 0, 0, 1, 1, 2, 0, 1, 2, 3};
constexpr int kEntryCol[10] = {0, 1, 2, 1, 2, 2, 3, 3, 3, 3};
// With a convex term of weight w (the divergence prior) the barrier starts at t = 1e-6 / w at
// the least and stops at a duality gap of 1e-9 w (minimise_on_consistent_set).
constexpr double kStartPerWeight = 1e-6;
constexpr double kGapPerWeight = 1e-9;

void entries_of_pseudo_inertia(const Eigen::Matrix4d& P, double* x) {
  for (int e = 0; e < 10; ++e) {
    x[e] = P(kEntryRow[e], kEntryCol[e]) * (kEntryRow[e] == kEntryCol[e] ? 1.0 : kSqrt2);
  }
}

// The log barrier of the regions, -sum log tr(P_b Q_b) over the bodies that have one, added to
// value, gradient and Hessian; false when a body is not strictly inside its region.
bool region_barrier(const Layout& layout, const Eigen::VectorXd& y, double& value,
                    Eigen::VectorXd* gradient, Eigen::MatrixXd* hessian) {
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    if (b >= layout.region_row.size() || !layout.region_row[b]) continue;
    const auto& index = layout.body_params[b];
    const auto& r = *layout.region_row[b];
    double inside = 0;
    for (int e = 0; e < 10; ++e) inside += r[static_cast<std::size_t>(e)] * y[index[e]];
    if (!(inside > 0)) return false;
    value -= std::log(inside);
    if (gradient == nullptr) continue;
    for (int e = 0; e < 10; ++e) {
      const double re = r[static_cast<std::size_t>(e)];
      (*gradient)[index[e]] -= re / inside;
      for (int f = 0; f < 10; ++f) {
        (*hessian)(index[e], index[f]) += re * r[static_cast<std::size_t>(f)] / (inside * inside);
      }
    }
  }
  return true;
}

// The log barrier of the consistent set, -sum log det(P_b - floor_b 1) - sum log y_k over the
// bounded parameters, with its gradient and Hessian; false when y is not strictly inside.
bool cone_barrier(const Layout& layout, const std::vector<char>& bounded,
                  const std::vector<double>& body_floor, const Eigen::VectorXd& y, double& value,
                  Eigen::VectorXd* gradient, Eigen::MatrixXd* hessian) {
  const std::array<Eigen::Matrix4d, 10>& E = entry_basis();
  value = 0;
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto& index = layout.body_params[b];
    double entries[10];
    for (int e = 0; e < 10; ++e) entries[e] = y[index[e]];
    const Eigen::Matrix4d S =
        pseudo_inertia_of_entries(entries) - body_floor[b] * Eigen::Matrix4d::Identity();
    const Eigen::LLT<Eigen::Matrix4d> llt(S);
    if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0)) return false;
    value -= 2 * llt.matrixLLT().diagonal().array().log().sum();
    if (gradient == nullptr) continue;
    const Eigen::Matrix4d S_inverse = llt.solve(Eigen::Matrix4d::Identity());
    std::array<Eigen::Matrix4d, 10> SE;
    for (int e = 0; e < 10; ++e) SE[e] = S_inverse * E[e];
    for (int e = 0; e < 10; ++e) {
      (*gradient)[index[e]] -= SE[e].trace();
      for (int f = 0; f <= e; ++f) {
        const double h = (SE[e] * SE[f]).trace();  // d2(-log det S) = tr(S^-1 E_e S^-1 E_f)
        (*hessian)(index[e], index[f]) += h;
        if (f != e) (*hessian)(index[f], index[e]) += h;
      }
    }
  }
  for (int k : layout.scalar_params) {
    if (!bounded[static_cast<std::size_t>(k)]) continue;
    if (!(y[k] > 0)) return false;
    value -= std::log(y[k]);
    if (gradient == nullptr) continue;
    (*gradient)[k] -= 1 / y[k];
    (*hessian)(k, k) += 1 / (y[k] * y[k]);
  }
  return true;
}

bool barrier(const Layout& layout, const std::vector<char>& bounded,
             const std::vector<double>& body_floor, const Eigen::VectorXd& y, double& value,
             Eigen::VectorXd* gradient, Eigen::MatrixXd* hessian) {
  return cone_barrier(layout, bounded, body_floor, y, value, gradient, hessian) &&
         region_barrier(layout, y, value, gradient, hessian);
}

}  // namespace

// The optimisation variables: per complete body the ten distinct entries of its pseudo-inertia
// (off-diagonal ones times sqrt 2, so that the Euclidean norm is the Frobenius norm and the
// projection onto the consistent set clips eigenvalues), stored in that body's ten standard
// slots; every other parameter as itself. standard = T variables, T linear.
Eigen::Matrix4d pseudo_inertia_of_entries(const double* x) {
  Eigen::Matrix4d P;
  for (int e = 0; e < 10; ++e) {
    const double v = kEntryRow[e] == kEntryCol[e] ? x[e] : x[e] / kSqrt2;
    P(kEntryRow[e], kEntryCol[e]) = P(kEntryCol[e], kEntryRow[e]) = v;
  }
  return P;
}

const std::array<Eigen::Matrix4d, 10>& entry_basis() {
  static const std::array<Eigen::Matrix4d, 10> E = [] {
    std::array<Eigen::Matrix4d, 10> basis;
    for (int e = 0; e < 10; ++e) {
      double x[10] = {};
      x[e] = 1;
      basis[static_cast<std::size_t>(e)] = pseudo_inertia_of_entries(x);
    }
    return basis;
  }();
  return E;
}

Layout make_layout(const RigidBodyTree& tree) {
  Layout layout;
  std::vector<char> in_body(tree.params.size(), 0);
  for (const auto& index : inertial_param_indices(tree)) {
    if (std::find(index.begin(), index.end(), -1) != index.end()) continue;
    layout.body_params.push_back(index);
    for (int k : index) in_body[static_cast<std::size_t>(k)] = 1;
  }
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    if (!in_body[k]) layout.scalar_params.push_back(static_cast<int>(k));
  }
  return layout;
}

Eigen::Matrix4d region_matrix(const BodyRegion& region) {
  const Eigen::Vector3d c(region.centre[0], region.centre[1], region.centre[2]);
  const Eigen::Vector3d a =
      Eigen::Vector3d(region.semi_axes[0], region.semi_axes[1], region.semi_axes[2])
          .cwiseAbs2()
          .cwiseInverse();
  Eigen::Matrix4d Q;
  Q.topLeftCorner<3, 3>() = -Eigen::Matrix3d(a.asDiagonal());
  Q.topRightCorner<3, 1>() = a.cwiseProduct(c);
  Q.bottomLeftCorner<1, 3>() = a.cwiseProduct(c).transpose();
  Q(3, 3) = 1 - c.dot(a.cwiseProduct(c));
  return Q;
}

void add_regions(const RigidBodyTree& tree, const std::vector<std::optional<BodyRegion>>& regions,
                 Layout& layout) {
  const std::array<Eigen::Matrix4d, 10>& E = entry_basis();
  layout.region.assign(layout.body_params.size(), std::nullopt);
  layout.region_row.assign(layout.body_params.size(), std::nullopt);
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto body = static_cast<std::size_t>(
        tree.params[static_cast<std::size_t>(layout.body_params[b][9])].body);
    if (body >= regions.size() || !regions[body]) continue;
    layout.region[b] = regions[body];
    const Eigen::Matrix4d Q = region_matrix(*regions[body]);
    std::array<double, 10> row;
    for (int e = 0; e < 10; ++e) row[static_cast<std::size_t>(e)] = (E[e] * Q).trace();
    layout.region_row[b] = row;
  }
}

void shrink_into_regions(const Layout& layout, const std::vector<double>& body_floor,
                         Eigen::VectorXd& x) {
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    if (b >= layout.region.size() || !layout.region[b]) continue;
    const auto& index = layout.body_params[b];
    double entries[10];
    for (int e = 0; e < 10; ++e) entries[e] = x[index[e]];
    const Eigen::Matrix4d P = pseudo_inertia_of_entries(entries);
    const Eigen::Matrix4d Q = region_matrix(*layout.region[b]);
    if ((P * Q).trace() > 0.19 * P(3, 3)) continue;  // rms extent below 0.9: inside
    // Above twice the floor P is positive semidefinite (project); its distribution M shrunk
    // by alpha about the centre c, S = [alpha 1, (1 - alpha) c; 0, 1], has alpha times its
    // rms extent.
    const double floor = 2 * body_floor[b];
    const Eigen::Matrix4d M = P - floor * Eigen::Matrix4d::Identity();
    const double extent = M(3, 3) > 0 ? std::sqrt(std::max(1 - (M * Q).trace() / M(3, 3), 0.0)) : 0;
    const Eigen::Vector3d c(layout.region[b]->centre[0], layout.region[b]->centre[1],
                            layout.region[b]->centre[2]);
    Eigen::Matrix4d shrunk = P;
    for (double alpha = extent > 0.5 ? 0.5 / extent : 1; alpha > 1e-6; alpha *= 0.5) {
      Eigen::Matrix4d S = Eigen::Matrix4d::Identity();
      S.topLeftCorner<3, 3>() *= alpha;
      S.topRightCorner<3, 1>() = (1 - alpha) * c;
      shrunk = S * M * S.transpose() + floor * Eigen::Matrix4d::Identity();
      if ((shrunk * Q).trace() > 0) break;
    }
    if (!((shrunk * Q).trace() > 0)) {  // no mass above the floor: a point mass at the centre
      const Eigen::Vector4d centre(c.x(), c.y(), c.z(), 1);
      shrunk = std::max(P(3, 3), 1.0) * centre * centre.transpose() +
               floor * Eigen::Matrix4d::Identity();
    }
    entries_of_pseudo_inertia(shrunk, entries);
    for (int e = 0; e < 10; ++e) x[index[e]] = entries[e];
  }
}

Eigen::MatrixXd standard_from_variables(const Layout& layout, Eigen::Index n) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int k : layout.scalar_params) T(k, k) = 1;
  for (const auto& index : layout.body_params) {
    for (int e = 0; e < 10; ++e) {
      double x[10] = {}, p[10];
      x[e] = 1;
      const Eigen::Matrix4d P = pseudo_inertia_of_entries(x);
      inertial_from_pseudo_inertia(P, p);
      for (int s = 0; s < 10; ++s) T(index[s], index[e]) = p[s];
    }
  }
  return T;
}

void project(const Layout& layout, const std::vector<char>& bounded,
             const std::vector<double>& body_floor, Eigen::VectorXd& x) {
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto& index = layout.body_params[b];
    double entries[10];
    for (int e = 0; e < 10; ++e) entries[e] = x[index[e]];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(pseudo_inertia_of_entries(entries));
    const Eigen::Vector4d clipped = eig.eigenvalues().cwiseMax(body_floor[b]);
    entries_of_pseudo_inertia(
        eig.eigenvectors() * clipped.asDiagonal() * eig.eigenvectors().transpose(), entries);
    for (int e = 0; e < 10; ++e) x[index[e]] = entries[e];
  }
  for (int k : layout.scalar_params) {
    if (bounded[static_cast<std::size_t>(k)]) x[k] = std::max(x[k], 0.0);
  }
}

Eigen::VectorXd variable_scales(const Layout& layout, const Eigen::MatrixXd& A) {
  Eigen::VectorXd d = A.colwise().norm().transpose();
  for (const auto& index : layout.body_params) {
    double largest = 0;
    for (int k : index) largest = std::max(largest, d[k]);
    for (int k : index) d[k] = largest;
  }
  // Variables the data barely see (rounding in K, or no effect at all) keep a scale of the
  // order of the others, not one that would blow up their prior term.
  const double floor = std::max(1e-6 * d.maxCoeff(), 1e-300);
  return d.cwiseMax(floor);
}

BarrierOutcome minimise_on_consistent_set(const Eigen::MatrixXd& H, const Eigen::VectorXd& h,
                                          const Layout& layout, const std::vector<char>& bounded,
                                          const std::vector<double>& body_floor, Eigen::VectorXd y,
                                          int max_iterations, const ConvexTerm& extra,
                                          double extra_weight) {
  const Eigen::Index n = y.size();
  double m = 4.0 * static_cast<double>(layout.body_params.size());
  for (int k : layout.scalar_params) m += bounded[static_cast<std::size_t>(k)] ? 1 : 0;
  for (const auto& row : layout.region_row) m += row ? 1 : 0;
  // Called only strictly inside the cones, where `extra` is defined.
  const auto objective = [&](const Eigen::VectorXd& v) {
    double value = 0.5 * v.dot(H * v) - h.dot(v);
    if (extra && !extra(v, value, nullptr, nullptr)) return std::numeric_limits<double>::infinity();
    return value;
  };
  const double size = std::max({1.0, std::abs(objective(y)), h.cwiseAbs().maxCoeff()});
  BarrierOutcome out;
  // With a convex term of weight w, from t = 1e-6 / w on: at a smaller t the central path's
  // bodies swell as 1/(t w) in the directions only the term decides (its tr(P0^-1 P) against
  // the barrier's -log det). From the usual start that was 1e10 times their mass on the Panda
  // at w = 1e-6: the Hessian of t f, computed, was then indefinite there (Newton decrements
  // below 0), the centring stopped at once at every t, and the solve reported convergence
  // 2.25e4 sigma^2 above its optimum. 1e6 is the swelling weight 1 always had here (t from
  // m / size, about 1e-6 on the Panda and the UR5 tests) and met no rounding trouble.
  double t = m / size;
  if (extra_weight > 0) t = std::max(t, kStartPerWeight / extra_weight);
  // The gap below 1e-9 w: the barrier's pull, 1/t, far below the term's in the directions
  // only it decides (1e-6 w moved base parameters of the UR5 tests by 0.17 sd at w = 1).
  const double gap_tolerance = extra_weight > 0 ? kGapPerWeight * extra_weight : HUGE_VAL;
  for (int outer = 0; outer < 60 && out.iterations < max_iterations; ++outer) {
    for (int inner = 0; inner < 200 && out.iterations < max_iterations; ++inner) {
      double value = 0, extra_value = 0;
      Eigen::VectorXd gradient = H * y - h;
      Eigen::MatrixXd hessian = H;
      if (extra) extra(y, extra_value, &gradient, &hessian);
      gradient *= t;
      hessian *= t;
      barrier(layout, bounded, body_floor, y, value, &gradient, &hessian);
      const Eigen::VectorXd step = -hessian.ldlt().solve(gradient);
      const double decrement = -gradient.dot(step);
      ++out.iterations;
      if (!(decrement > 2e-14)) break;
      // The change of t f + barrier along the step, its quadratic part in closed form: the
      // difference of two values of 1/2 y'Hy - h'y loses to rounding what a weak prior
      // changes when the data term is large (a divergence at weight 1e-6 left Panda links at
      // 1e8 times their mass).
      const double q1 = (H * y - h).dot(step), q2 = step.dot(H * step);
      double extra_here = 0;
      if (extra) extra(y, extra_here, nullptr, nullptr);
      double s = 1;
      for (int halving = 0; halving < 80; ++halving, s *= 0.5) {
        const Eigen::VectorXd trial = y + s * step;
        double trial_value = 0, extra_trial = 0;
        if (!barrier(layout, bounded, body_floor, trial, trial_value, nullptr, nullptr)) continue;
        if (extra && !extra(trial, extra_trial, nullptr, nullptr)) continue;
        const double change =
            t * (s * q1 + 0.5 * s * s * q2 + extra_trial - extra_here) + trial_value - value;
        if (change <= -0.25 * s * decrement) break;
      }
      y += s * step;
      if (decrement < 1e-10) break;
    }
    if (m / t < 1e-13 * size && m / t < gap_tolerance) {
      out.converged = true;
      break;
    }
    t *= 10;
  }
  // The duals: the barrier's gradient over t (for a body the largest entry of its block), the
  // cones' and the regions' apart.
  double value = 0;
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(n, n);
  cone_barrier(layout, bounded, body_floor, y, value, &gradient, &hessian);
  out.push = gradient.cwiseAbs() / t;
  gradient.setZero();
  region_barrier(layout, y, value, &gradient, &hessian);
  out.region_push.assign(layout.body_params.size(), 0.0);
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto& index = layout.body_params[b];
    double largest = 0, largest_region = 0;
    for (int k : index) {
      largest = std::max(largest, out.push[k]);
      largest_region = std::max(largest_region, std::abs(gradient[k]) / t);
    }
    for (int k : index) out.push[k] = largest;
    out.region_push[b] = largest_region;
  }
  out.y = y;
  return out;
}

}  // namespace modelgen::detail
