// The prior term of physical_prior.hpp: group scales, the log-det divergence of the bodies with
// a-priori inertials, the quadratic pull on the rest and the null space of the scaled
// regrouping map.

#include "runtime/src/estimation/physical_prior.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"

namespace modelgen::detail {

Eigen::VectorXd prior_scales(const RigidBodyTree& tree, const Layout& layout,
                             const Eigen::VectorXd& reference, const Eigen::MatrixXd& K,
                             const Eigen::VectorXd* base_std_dev) {
  std::vector<std::vector<int>> groups[3];  // inertias, first moments, masses
  for (const auto& index : layout.body_params) {
    groups[0].push_back({index[0], index[1], index[2], index[3], index[4], index[5]});
    groups[1].push_back({index[6], index[7], index[8]});
    groups[2].push_back({index[9]});
  }
  std::vector<std::vector<int>> by_kind(static_cast<std::size_t>(ParamKind::kFcm) + 1);
  for (int k : layout.scalar_params) {
    by_kind[static_cast<std::size_t>(tree.params[static_cast<std::size_t>(k)].kind)].push_back(k);
  }
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(reference.size());
  const auto largest_of = [&](const std::vector<int>& members) {
    double largest = 0;
    for (int k : members) largest = std::max(largest, std::abs(reference[k]));
    return largest;
  };
  for (const auto& cls : groups) {
    double class_largest = 0;
    for (const auto& members : cls) class_largest = std::max(class_largest, largest_of(members));
    for (const auto& members : cls) {
      const double size = std::max(largest_of(members), 1e-3 * class_largest);
      for (int k : members) scale[k] = size > 0 ? size : 1.0;
    }
  }
  for (const auto& members : by_kind) {
    const double size = largest_of(members);
    for (int k : members) scale[k] = size > 0 ? size : 1.0;
  }
  if (base_std_dev == nullptr) return scale;
  for (Eigen::Index k = 0; k < K.cols(); ++k) {
    double resolved = std::numeric_limits<double>::infinity();
    const double column = K.col(k).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < K.rows(); ++j) {
      if (std::abs(K(j, k)) > 1e-9 * column) {
        resolved = std::min(resolved, (*base_std_dev)[j] / std::abs(K(j, k)));
      }
    }
    if (std::isfinite(resolved)) scale[k] = std::max(scale[k], resolved);
  }
  return scale;
}

std::optional<BodyDivergence> log_det_divergence(const Eigen::Matrix4d& P0, const double* x,
                                                 bool derivatives) {
  const Eigen::Matrix4d P = pseudo_inertia_of_entries(x);
  const Eigen::LLT<Eigen::Matrix4d> llt(P), llt0(P0);
  if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0)) {
    return std::nullopt;
  }
  const Eigen::Matrix4d P0_inverse = llt0.solve(Eigen::Matrix4d::Identity());
  BodyDivergence out;
  const double log_det = 2 * llt.matrixLLT().diagonal().array().log().sum();
  const double log_det0 = 2 * llt0.matrixLLT().diagonal().array().log().sum();
  out.value = log_det0 - log_det + (P0_inverse * P).trace() - 4;
  if (!derivatives) return out;
  const Eigen::Matrix4d P_inverse = llt.solve(Eigen::Matrix4d::Identity());
  const std::array<Eigen::Matrix4d, 10>& E = entry_basis();
  std::array<Eigen::Matrix4d, 10> PE;  // P^-1 E_e
  for (std::size_t e = 0; e < 10; ++e) {
    PE[e] = P_inverse * E[e];
    out.gradient[static_cast<Eigen::Index>(e)] = (P0_inverse * E[e]).trace() - PE[e].trace();
  }
  for (std::size_t e = 0; e < 10; ++e) {
    for (std::size_t f = 0; f <= e; ++f) {
      const double h = (PE[e] * PE[f]).trace();
      out.hessian(static_cast<Eigen::Index>(e), static_cast<Eigen::Index>(f)) = h;
      out.hessian(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(e)) = h;
    }
  }
  return out;
}

std::optional<DivergenceCentre> divergence_centre(const double* p0, double radius) {
  const Eigen::Matrix4d P0 = pseudo_inertia(p0);
  const Eigen::Vector4d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(P0).eigenvalues();
  const double m = P0(3, 3);
  if (!(m > 0) || lambda[0] < -1e-12 * lambda[3]) return std::nullopt;
  DivergenceCentre out{P0, 0, radius};
  if (radius > 0) {
    // Sigma_c = Sigma - h h' / m: the second moments about the centre of mass.
    const Eigen::Vector3d h = P0.block<3, 1>(0, 3);
    const Eigen::Matrix3d about_com = P0.topLeftCorner<3, 3>() - h * h.transpose() / m;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(about_com);
    Eigen::Vector3d moment = axes.eigenvalues();
    const double sphere = m * radius * radius / 5;
    for (int i = 0; i < 3; ++i) {
      if (moment[i] < kThinAxisFraction * sphere) {
        moment[i] = sphere;
        ++out.thin_axes;
      }
    }
    if (out.thin_axes > 0) {
      out.P0.topLeftCorner<3, 3>() =
          axes.eigenvectors() * moment.asDiagonal() * axes.eigenvectors().transpose() +
          h * h.transpose() / m;
      return out;
    }
  }
  if (!(lambda[0] > 1e-12 * lambda[3])) return std::nullopt;  // singular, nothing to spread by
  return out;
}

double spread_radius(const RigidBodyTree& tree, const std::optional<BodyRegion>& region) {
  if (region) {
    return 0.5 * std::min({region->semi_axes[0], region->semi_axes[1], region->semi_axes[2]});
  }
  double reach = 0;
  for (const Body& body : tree.bodies) {
    const auto& t = body.fixed.translation;
    reach += std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  }
  return reach / 20;
}

std::string spread_note(const std::string& body_name, const DivergenceCentre& centre) {
  static const char* const kShape[] = {"", "mass in a plane", "mass on a line", "point mass"};
  std::ostringstream says;
  says.precision(2);
  says << "body '" << body_name << "': a-priori inertia singular (" << kShape[centre.thin_axes]
       << "): for the prior, spread along its " << centre.thin_axes
       << " thin axes as a solid sphere of radius " << centre.radius
       << " m about the a-priori centre of mass (same mass and centre of mass)";
  return says.str();
}

std::vector<std::optional<DivergenceCentre>> divergence_centres(
    const Layout& layout, const Eigen::VectorXd& prior_value, const std::vector<char>& has_a_priori,
    const std::vector<double>& radius) {
  std::vector<std::optional<DivergenceCentre>> centre(layout.body_params.size());
  for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
    const auto& index = layout.body_params[b];
    bool known = true;
    double p0[10];
    for (int s = 0; s < 10; ++s) {
      known = known && has_a_priori[static_cast<std::size_t>(index[s])];
      p0[s] = prior_value[index[s]];
    }
    if (known) centre[b] = divergence_centre(p0, radius[b]);
  }
  return centre;
}

ConvexTerm divergence_term(const Layout& layout,
                           const std::vector<std::optional<Eigen::Matrix4d>>& centre,
                           double weight) {
  return [&layout, centre, weight](const Eigen::VectorXd& y, double& value,
                                   Eigen::VectorXd* gradient, Eigen::MatrixXd* hessian) {
    for (std::size_t b = 0; b < layout.body_params.size(); ++b) {
      if (!centre[b]) continue;
      const auto& index = layout.body_params[b];
      double x[10];
      for (int e = 0; e < 10; ++e) x[e] = y[index[e]];
      const auto d = log_det_divergence(*centre[b], x, gradient != nullptr);
      if (!d) return false;
      value += weight * d->value;
      if (gradient == nullptr) continue;
      for (int e = 0; e < 10; ++e) {
        (*gradient)[index[e]] += weight * d->gradient[e];
        for (int f = 0; f < 10; ++f) (*hessian)(index[e], index[f]) += weight * d->hessian(e, f);
      }
    }
    return true;
  };
}

QuadraticPrior quadratic_prior(const Eigen::MatrixXd& K, const Eigen::MatrixXd& standard_per_y,
                               const Eigen::VectorXd& scale, const Eigen::VectorXd& prior_value,
                               const std::vector<char>& in_divergence) {
  std::vector<Eigen::Index> Q;
  for (Eigen::Index k = 0; k < K.cols(); ++k) {
    if (!in_divergence[static_cast<std::size_t>(k)]) Q.push_back(k);
  }
  const auto q = static_cast<Eigen::Index>(Q.size());
  Eigen::MatrixXd K_Q(K.rows(), q), LT(q, standard_per_y.cols());
  Eigen::VectorXd scale_Q(q), Lp0(q);
  for (Eigen::Index i = 0; i < q; ++i) {
    K_Q.col(i) = K.col(Q[static_cast<std::size_t>(i)]);
    scale_Q[i] = scale[Q[static_cast<std::size_t>(i)]];
    LT.row(i) = standard_per_y.row(Q[static_cast<std::size_t>(i)]) / scale_Q[i];
    Lp0[i] = prior_value[Q[static_cast<std::size_t>(i)]] / scale_Q[i];
  }
  QuadraticPrior out;
  if (q == 0) {
    out.G1 = Eigen::MatrixXd::Zero(0, standard_per_y.cols());
    out.g1 = Eigen::VectorXd::Zero(0);
    return out;
  }
  const Eigen::MatrixXd N = scaled_null_space(K_Q, scale_Q);
  out.G1 = N.transpose() * LT;
  out.g1 = N.transpose() * Lp0;
  return out;
}

Eigen::MatrixXd null_space_of(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  const Eigen::MatrixXd KM = K * M;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(KM, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double largest = s.size() > 0 ? s[0] : 0.0;
  Eigen::Index rank = 0;
  while (rank < s.size() && s[rank] > 1e-10 * largest) ++rank;
  return svd.matrixV().rightCols(KM.cols() - rank);
}

Eigen::MatrixXd scaled_null_space(const Eigen::MatrixXd& K, const Eigen::VectorXd& scale) {
  return null_space_of(K, scale.asDiagonal().toDenseMatrix());
}

}  // namespace modelgen::detail
