// Numeric base-parameter derivation (Gautier 1991; Gautier & Briot Sec. II): rank of the
// stacked standard regressor, independent columns chosen greedily left to right by
// Gram-Schmidt with reorthogonalization, regrouping coefficients from a least-squares solve.

#include "modelgen/model/base_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <stdexcept>

#include <Eigen/QR>

#include "modelgen/model/reference_dynamics.hpp"

namespace modelgen {

namespace {

// Uniform doubles from a fixed seed, identical on every platform (std::uniform_real_distribution
// is implementation-defined).
class Sampler {
 public:
  explicit Sampler(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }

 private:
  std::mt19937_64 engine_;
};

// The standard regressor stacked over `states` random states (dof rows each).
Eigen::MatrixXd stacked_regressor(const ReferenceDynamics& dynamics, int states, Sampler& s) {
  const RigidBodyTree& tree = dynamics.tree();
  const int n = dynamics.dof();
  Eigen::MatrixXd W(states * n, dynamics.num_params());
  Eigen::VectorXd q(n), dq(n), ddq(n);
  for (int k = 0; k < states; ++k) {
    for (const Body& body : tree.bodies) {
      if (body.dof_index < 0) continue;
      const int i = body.dof_index;
      q[i] = body.type == JointType::kRevolute ? s.uniform(-std::numbers::pi, std::numbers::pi)
                                               : s.uniform(-0.5, 0.5);
      // Velocities never zero, so that friction columns keep their sign pattern generic.
      // Two draws in named steps: the order of operands of * is unspecified in C++.
      const double magnitude = s.uniform(0.2, 2.0);
      const bool negative = s.uniform(0, 1) < 0.5;
      dq[i] = negative ? -magnitude : magnitude;
      ddq[i] = s.uniform(-3, 3);
    }
    W.middleRows(k * n, n) = dynamics.standard_regressor(q, dq, ddq);
  }
  return W;
}

double snap_coefficient(double x) {
  if (std::abs(x) < 1e-10) return 0.0;
  for (int digits = 1; digits <= 17; ++digits) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    const double y = std::strtod(text, nullptr);
    if (std::abs(y - x) <= 1e-12 * std::abs(x)) return y;
  }
  return x;
}

}  // namespace

BaseParameterSet derive_base_parameters(const RigidBodyTree& tree) {
  const ReferenceDynamics dynamics(tree);
  const int num_params = dynamics.num_params();
  const int states = 2 * num_params / std::max(1, dynamics.dof()) + 20;
  Sampler sampler(20240917);
  const Eigen::MatrixXd W = stacked_regressor(dynamics, states, sampler);

  double largest = 0;
  for (int k = 0; k < num_params; ++k) largest = std::max(largest, W.col(k).norm());
  // A column counts as independent when the part of it the earlier columns do not explain is
  // above `dependence` relative to its norm. Floating point alone leaves ~1e-12 there, hence the
  // floor of 1e-8. But the geometry is only known to the description's angle precision: an
  // angle off by delta rad (a rounded pi/2 the loader did not snap, axes parallel only to
  // delta) moves a column that is dependent for the true robot by about delta relative to its
  // norm, and that part is not identifiable on the real robot. So effects below the precision
  // count as dependence.
  const double dependence = std::max(1e-8, tree.angle_precision);
  // Likewise a column that vanishes for the true robot (MX1 when axis 1 is vertical) is about
  // delta times an ordinary column when the geometry is off by delta.
  const double negligible = std::max(1e-10, tree.angle_precision);
  std::vector<int> independent, dependent;
  BaseParameterSet result;
  Eigen::MatrixXd Q(W.rows(), 0);
  for (int k = 0; k < num_params; ++k) {
    Eigen::VectorXd v = W.col(k);
    const double norm = v.norm();
    if (norm <= negligible * largest) {
      result.without_effect.push_back(k);
      continue;
    }
    for (int pass = 0; pass < 2; ++pass) v -= Q * (Q.transpose() * v);
    if (v.norm() <= dependence * norm) {
      dependent.push_back(k);
      continue;
    }
    independent.push_back(k);
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = v / v.norm();
  }

  // Columns of dependent parameters as combinations of the independent ones.
  Eigen::MatrixXd W_independent(W.rows(), independent.size());
  for (std::size_t i = 0; i < independent.size(); ++i) W_independent.col(i) = W.col(independent[i]);
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(independent.size(), dependent.size());
  if (!dependent.empty()) {
    Eigen::MatrixXd W_dependent(W.rows(), dependent.size());
    for (std::size_t d = 0; d < dependent.size(); ++d) W_dependent.col(d) = W.col(dependent[d]);
    X = W_independent.colPivHouseholderQr().solve(W_dependent);
  }
  // Coefficients are products of geometric constants (2 r3, d3^2 + r3^2, ...); least squares
  // leaves noise of ~1e-15 relative on them, so each is replaced by the shortest decimal within
  // 1e-12 relative (0.06999999999999988 -> 0.07), and tiny ones by zero.
  for (Eigen::Index r = 0; r < X.rows(); ++r) {
    for (Eigen::Index c = 0; c < X.cols(); ++c) X(r, c) = snap_coefficient(X(r, c));
  }

  result.K = Eigen::MatrixXd::Zero(independent.size(), num_params);
  for (std::size_t i = 0; i < independent.size(); ++i) {
    BaseParameter base;
    base.standard_index = independent[i];
    base.relation.push_back({independent[i], 1.0});
    result.K(i, independent[i]) = 1.0;
    for (std::size_t d = 0; d < dependent.size(); ++d) {
      if (X(i, d) == 0.0) continue;
      base.relation.push_back({dependent[d], X(i, d)});
      result.K(i, dependent[d]) = X(i, d);
    }
    base.name = tree.params[independent[i]].name + (base.relation.size() > 1 ? "R" : "");
    result.params.push_back(std::move(base));
  }

  // Self-check on fresh states: W_std == W_base K, i.e. tau is the same for every p.
  const Eigen::MatrixXd W_check = stacked_regressor(dynamics, 8, sampler);
  Eigen::MatrixXd W_base(W_check.rows(), independent.size());
  for (std::size_t i = 0; i < independent.size(); ++i) W_base.col(i) = W_check.col(independent[i]);
  const double error = (W_check - W_base * result.K).cwiseAbs().maxCoeff();
  // Columns taken as dependent within `dependence` leave errors of that relative size.
  const double allowed = 10 * dependence;
  if (error > allowed * std::max(1.0, W_check.cwiseAbs().maxCoeff())) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", error);
    throw std::logic_error(std::string("base parameters: regrouping relations fail their check (error ") +
                           text + ")");
  }
  return result;
}

}  // namespace modelgen
