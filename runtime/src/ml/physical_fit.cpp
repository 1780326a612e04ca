// The consistent maximum-likelihood fit of physical_fit.hpp. The search runs in coordinates
// phi where every value is consistent or a bound keeps it so: the drive unknowns as themselves
// (Ceres bounds), the load as the ten log-Cholesky parameters of its standard parameters about
// the payload link's frame. Each cost block of the problem is wrapped: theta1 = g(phi), and its
// Jacobian is the block's times dg/dphi (Ceres jets through the log-Cholesky map). Unlike the
// linear physical fit (modelgen/estimation/physical.hpp, where Levenberg-Marquardt in these
// coordinates stalled on free link directions), the ML problem's unknowns are few and the data
// determine them, so the logarithms' flattening near the boundary does not stop the search.

#include "modelgen/ml/physical_fit.hpp"

#include <ceres/ceres.h>
#include <ceres/jet.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/src/ml/problem_impl.hpp"
#include "runtime/src/ml/standard_deviations.hpp"

namespace modelgen {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// An efficiency must be positive; the search keeps it above this floor so eq. 8's 1 / Rz
// stays finite.
constexpr double kEfficiencyFloor = 1e-3;
// A load whose pseudo-inertia has its smallest eigenvalue below this fraction of its largest
// sits on the boundary of the consistent set (a degenerate shape: a point, a rod, a plate).
constexpr double kBoundaryRatio = 1e-6;
// The length (m) below which a load's centre of gravity is not told from the frame origin by
// the prior term's scale.
constexpr double kLengthScale = 0.01;

enum class Bound { kNone, kNonnegative, kEfficiency };

// JMj, Rvj, Rcj nonnegative; Rzj an efficiency in (0, 1].
Bound bound_of(const std::string& name) {
  if (name.size() < 3 || name.find_first_not_of("0123456789", 2) != std::string::npos) {
    return Bound::kNone;
  }
  const std::string stem = name.substr(0, 2);
  if (stem == "JM" || stem == "Rv" || stem == "Rc") return Bound::kNonnegative;
  if (stem == "Rz") return Bound::kEfficiency;
  return Bound::kNone;
}

double lower_bound(Bound bound) { return bound == Bound::kEfficiency ? kEfficiencyFloor : 0.0; }

// The load (LoadParameters::to_vector order) of its ten standard parameters about the payload
// link's frame (XX XY XZ YY YZ ZZ MX MY MZ M): standard_from_load inverted, as a template for
// Ceres' jets. The mass must be positive, which the log-Cholesky map guarantees.
template <class T>
void load_from_standard_parameters(const T* s, T* load) {
  const T m = s[9];
  const T cx = s[6] / m, cy = s[7] / m, cz = s[8] / m;
  load[0] = m;
  load[1] = cx;
  load[2] = cy;
  load[3] = cz;
  load[4] = s[0] - m * (cy * cy + cz * cz);  // Ixx
  load[5] = s[3] - m * (cx * cx + cz * cz);  // Iyy
  load[6] = s[5] - m * (cx * cx + cy * cy);  // Izz
  load[7] = s[1] + m * cx * cy;              // Ixy
  load[8] = s[2] + m * cx * cz;              // Ixz
  load[9] = s[4] + m * cy * cz;              // Iyz
}

// theta1 (the problem's unknowns) as a function of the search coordinates phi: the free drive
// unknowns first, then the load's log-Cholesky parameters.
struct Coordinates {
  int U = 0;
  std::vector<int> free;       // theta1 positions searched as themselves
  std::array<int, 10> load{};  // theta1 positions of the load, to_vector() order
  bool has_load = false;
  Eigen::VectorXd held;  // theta1 values, used where a position is not searched

  int size() const { return static_cast<int>(free.size()) + (has_load ? 10 : 0); }
  int load_offset() const { return static_cast<int>(free.size()); }

  // theta1 = g(phi) and, when G is not null, dg/dphi (U x size()).
  void unknowns(const double* phi, double* theta1, Eigen::MatrixXd* G) const {
    for (int u = 0; u < U; ++u) theta1[u] = held[u];
    if (G) G->setZero(U, size());
    for (std::size_t f = 0; f < free.size(); ++f) {
      theta1[free[f]] = phi[f];
      if (G) (*G)(free[f], static_cast<Eigen::Index>(f)) = 1;
    }
    if (!has_load) return;
    using Jet = ceres::Jet<double, 10>;
    Jet log_cholesky[10], standard[10], values[10];
    for (int i = 0; i < 10; ++i) log_cholesky[i] = Jet(phi[load_offset() + i], i);
    inertial_from_log_cholesky(log_cholesky, standard);
    load_from_standard_parameters(standard, values);
    for (int i = 0; i < 10; ++i) {
      theta1[load[i]] = values[i].a;
      if (G) {
        for (int j = 0; j < 10; ++j) (*G)(load[i], load_offset() + j) = values[i].v[j];
      }
    }
  }

  // The load's standard parameters of phi and their derivatives (10 x 10).
  static void standard_of(const double* log_cholesky, double* standard,
                          Eigen::Matrix<double, 10, 10>* D) {
    using Jet = ceres::Jet<double, 10>;
    Jet in[10], out[10];
    for (int i = 0; i < 10; ++i) in[i] = Jet(log_cholesky[i], i);
    inertial_from_log_cholesky(in, out);
    for (int i = 0; i < 10; ++i) {
      standard[i] = out[i].a;
      if (D) D->row(i) = out[i].v.transpose();
    }
  }
};

// A cost block of the problem in the coordinates phi.
class CostInCoordinates final : public ceres::CostFunction {
 public:
  CostInCoordinates(const ceres::CostFunction* inner, const Coordinates& coordinates)
      : inner_(inner), coordinates_(coordinates) {
    set_num_residuals(inner->num_residuals());
    mutable_parameter_block_sizes()->push_back(coordinates.size());
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const bool jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    Eigen::VectorXd theta1(coordinates_.U);
    Eigen::MatrixXd G;
    coordinates_.unknowns(parameters[0], theta1.data(), jacobian ? &G : nullptr);
    const double* inner_parameters[1] = {theta1.data()};
    if (!jacobian) return inner_->Evaluate(inner_parameters, residuals, nullptr);
    RowMajor J(num_residuals(), coordinates_.U);
    double* inner_jacobians[1] = {J.data()};
    if (!inner_->Evaluate(inner_parameters, residuals, inner_jacobians)) return false;
    Eigen::Map<RowMajor>(jacobians[0], num_residuals(), coordinates_.size()) = J * G;
    return true;
  }

 private:
  const ceres::CostFunction* inner_;
  const Coordinates& coordinates_;
};

// The prior term: sqrt(w) (value - start) / scale for each free drive unknown and each of the
// load's standard parameters.
class PriorCost final : public ceres::CostFunction {
 public:
  PriorCost(const Coordinates& coordinates, Eigen::VectorXd centre, Eigen::VectorXd weight)
      : coordinates_(coordinates), centre_(std::move(centre)), weight_(std::move(weight)) {
    set_num_residuals(static_cast<int>(centre_.size()));
    mutable_parameter_block_sizes()->push_back(coordinates.size());
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* phi = parameters[0];
    const int F = coordinates_.size();
    const int free = coordinates_.load_offset();
    double* J = jacobians != nullptr ? jacobians[0] : nullptr;
    if (J) std::fill(J, J + num_residuals() * F, 0.0);
    for (int f = 0; f < free; ++f) {
      residuals[f] = weight_[f] * (phi[f] - centre_[f]);
      if (J) J[f * F + f] = weight_[f];
    }
    if (!coordinates_.has_load) return true;
    double standard[10];
    Eigen::Matrix<double, 10, 10> D;
    Coordinates::standard_of(phi + free, standard, J ? &D : nullptr);
    for (int i = 0; i < 10; ++i) {
      residuals[free + i] = weight_[free + i] * (standard[i] - centre_[free + i]);
      if (!J) continue;
      for (int j = 0; j < 10; ++j) J[(free + i) * F + free + j] = weight_[free + i] * D(i, j);
    }
    return true;
  }

 private:
  const Coordinates& coordinates_;
  Eigen::VectorXd centre_, weight_;
};

std::string text(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

// How many of the load's ten parameters are unknown.
int unknown_load_count(const MlProblem& problem) {
  const int P = problem.model().num_params();
  const std::vector<int>& indices = problem.unknown_indices();
  return static_cast<int>(
      std::count_if(indices.begin(), indices.end(), [P](int k) { return k >= P; }));
}

// The positions of the load's ten parameters among the unknowns (to_vector order), and whether
// they are all there; throws when only some are.
bool load_positions(const MlProblem& problem, std::array<int, 10>& positions) {
  const int P = problem.model().num_params();
  positions.fill(-1);
  int found = 0;
  const std::vector<int>& indices = problem.unknown_indices();
  for (std::size_t u = 0; u < indices.size(); ++u) {
    if (indices[u] < P) continue;
    positions[static_cast<std::size_t>(indices[u] - P)] = static_cast<int>(u);
    ++found;
  }
  if (found != 0 && found != 10) {
    throw EstimationError(
        "physical fit: the load's ten parameters must be all unknown or all known (its "
        "log-Cholesky parameters couple them); " +
        std::to_string(found) + " are unknown");
  }
  return found == 10;
}

// The pseudo-inertia of a load given in to_vector() order.
Eigen::Matrix4d load_pseudo_inertia(const double* load) {
  double standard[10];
  standard_from_load(load, standard);
  return pseudo_inertia(standard);
}

// The nearest consistent standard parameters to those of `load` in the Frobenius norm of the
// pseudo-inertia: its eigenvalues floored at a small fraction of the largest.
Eigen::Matrix<double, 10, 1> consistent_standard(const double* load) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(load_pseudo_inertia(load));
  Eigen::Vector4d lambda = eigen.eigenvalues();
  const double largest = std::max(lambda.cwiseAbs().maxCoeff(), 1e-9);
  lambda = lambda.cwiseMax(1e-4 * largest);
  const Eigen::Matrix4d P =
      eigen.eigenvectors() * lambda.asDiagonal() * eigen.eigenvectors().transpose();
  Eigen::Matrix<double, 10, 1> standard;
  inertial_from_pseudo_inertia(P, standard.data());
  return standard;
}

}  // namespace

std::vector<std::string> ml_physical_violations(const MlProblem& problem, const MlFitResult& fit) {
  std::vector<std::string> violations;
  const std::vector<std::string>& names = problem.unknown_names();
  const std::vector<int>& indices = problem.unknown_indices();
  for (std::size_t u = 0; u < names.size(); ++u) {
    const double value = fit.all_values[indices[u]];
    switch (bound_of(names[u])) {
      case Bound::kNonnegative:
        if (value < 0) violations.push_back(names[u] + " = " + text(value) + " < 0");
        break;
      case Bound::kEfficiency:
        if (!(value > 0 && value <= 1)) {
          violations.push_back(names[u] + " = " + text(value) + " outside (0, 1]");
        }
        break;
      case Bound::kNone:
        break;
    }
  }
  if (unknown_load_count(problem) > 0) {
    const int P = problem.model().num_params();
    const LoadParameters values = LoadParameters::from_vector(fit.all_values.data() + P);
    for (const std::string& warning : physical_consistency_warnings(values)) {
      violations.push_back("load: " + warning);
    }
  }
  return violations;
}

MlPhysicalResult fit_ml_physical(MlProblem& problem, const MlFitResult& unconstrained,
                                 const MlPhysicalOptions& options) {
  if (!(options.prior_weight > 0) || !std::isfinite(options.prior_weight)) {
    throw EstimationError("physical fit: the prior weight must be a positive number");
  }
  if (unconstrained.names != problem.unknown_names()) {
    throw EstimationError("physical fit: the unconstrained estimate has other unknowns than the "
                          "problem (fit it on the same problem)");
  }
  std::array<int, 10> load_at{};
  const bool has_load = load_positions(problem, load_at);  // throws for a partly known load
  MlPhysicalResult result;
  if (ml_physical_violations(problem, unconstrained).empty()) {
    result.fit = unconstrained;
    result.unconstrained_consistent = true;
    result.unconstrained_sum_of_squares = 2 * unconstrained.final_cost;
    return result;
  }
  const std::vector<std::string>& names = problem.unknown_names();
  const std::vector<int>& indices = problem.unknown_indices();
  const int U = problem.num_unknowns();
  const int P = problem.model().num_params();
  for (const std::string& name : names) {
    if (name.compare(0, 5, "load_") != 0 && bound_of(name) == Bound::kNone) {
      throw EstimationError("physical fit: " + name +
                            " is unknown; only the load and the drive parameters JM, Rv, Rc, Rz "
                            "are constrained in the maximum-likelihood fit");
    }
  }

  // The start: the unconstrained values (held ones included) made consistent, and the prior
  // term's centre and scale per drive unknown and for the load's standard parameters.
  Eigen::VectorXd theta1(U);  // the current unknowns
  for (int u = 0; u < U; ++u) theta1[u] = unconstrained.all_values[indices[u]];
  std::vector<Bound> bound(static_cast<std::size_t>(U));
  Eigen::VectorXd centre = Eigen::VectorXd::Zero(U), scale = Eigen::VectorXd::Ones(U);
  for (int u = 0; u < U; ++u) {
    bound[u] = bound_of(names[u]);
    if (bound[u] == Bound::kNone) continue;  // a load parameter
    theta1[u] = std::max(theta1[u], lower_bound(bound[u]));
    if (bound[u] == Bound::kEfficiency) theta1[u] = std::min(theta1[u], 1.0);
    centre[u] = theta1[u];
    const double sd = unconstrained.std_dev[u];
    scale[u] = std::max({std::abs(theta1[u]), std::isfinite(sd) ? sd : 0.0, 1e-9});
  }
  Eigen::Matrix<double, 10, 1> load_phi, load_centre, load_scale;
  if (has_load) {
    double load[10];
    for (int i = 0; i < 10; ++i) load[i] = theta1[load_at[i]];
    load_centre = consistent_standard(load);
    const auto log_cholesky = log_cholesky_from_inertial(load_centre.data());
    if (!log_cholesky) {
      throw EstimationError("physical fit: the load's start is not consistent (internal error)");
    }
    load_phi = *log_cholesky;
    // Scales by group, as the linear fit's: inertia entries, first moments, mass.
    // Floors from the mass and a 1 cm length, so a start at the origin (a point mass, as the
    // linear route gives a load it cannot see) does not pin the centre of gravity there.
    const double mass = std::max(std::abs(load_centre[9]), 1e-6);
    const double inertia =
        std::max(load_centre.head<6>().cwiseAbs().maxCoeff(), mass * kLengthScale * kLengthScale);
    const double moments =
        std::max(load_centre.segment<3>(6).cwiseAbs().maxCoeff(), mass * kLengthScale);
    for (int i = 0; i < 10; ++i) {
      load_scale[i] = i < 6 ? inertia : i < 9 ? moments : mass;
    }
  }

  // Active set: bounds Levenberg-Marquardt ends on are held there and the search repeated
  // without them, and a held bound whose gradient points inside is released, until neither
  // happens. Ceres' projected steps alone stall next to an active bound that couples with
  // other unknowns (measured: 0.1 sigma^2 above the optimum, estimates off by 0.3 sd).
  std::vector<char> held(static_cast<std::size_t>(U), 0);
  Eigen::VectorXd start;
  ceres::Solver::Summary summary;
  int iterations = 0;
  double solve_seconds = 0;
  bool settled = false;  // the active set stopped changing
  bool searched = false;
  for (int round = 0; round < 2 * U + 2; ++round) {
    Coordinates coordinates;
    coordinates.U = U;
    coordinates.has_load = has_load;
    coordinates.load = load_at;
    coordinates.held = theta1;
    std::vector<double> phi, centre_values, scale_values;
    std::vector<Bound> bounds;
    for (int u = 0; u < U; ++u) {
      // Unknowns the data do not identify stay where the unconstrained fit held them.
      if (bound[u] == Bound::kNone || held[u] || !unconstrained.identifiability.identifiable[u]) {
        continue;
      }
      coordinates.free.push_back(u);
      phi.push_back(theta1[u]);
      bounds.push_back(bound[u]);
      centre_values.push_back(centre[u]);
      scale_values.push_back(scale[u]);
    }
    if (has_load) {
      for (int i = 0; i < 10; ++i) {
        phi.push_back(load_phi[i]);
        centre_values.push_back(load_centre[i]);
        scale_values.push_back(load_scale[i]);
      }
    }
    const Eigen::Map<Eigen::VectorXd> prior_centre(centre_values.data(),
                                                   static_cast<Eigen::Index>(centre_values.size()));
    const Eigen::Map<Eigen::VectorXd> prior_scale(scale_values.data(),
                                                  static_cast<Eigen::Index>(scale_values.size()));
    if (round == 0) {
      start.resize(U);
      coordinates.unknowns(phi.data(), start.data(), nullptr);
    }
    // Every identifiable unknown held on its bound and no load: nothing is left to search.
    if (coordinates.size() == 0) {
      settled = true;
      break;
    }
    searched = true;

    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem solver_problem(problem_options);
    std::vector<std::unique_ptr<ceres::CostFunction>> costs;
    for (const ceres::CostFunction* block : detail::MlProblemAccess::cost_functions(problem)) {
      costs.push_back(std::make_unique<CostInCoordinates>(block, coordinates));
      solver_problem.AddResidualBlock(costs.back().get(), nullptr, phi.data());
    }
    costs.push_back(std::make_unique<PriorCost>(
        coordinates, prior_centre, std::sqrt(options.prior_weight) * prior_scale.cwiseInverse()));
    solver_problem.AddResidualBlock(costs.back().get(), nullptr, phi.data());
    for (std::size_t f = 0; f < coordinates.free.size(); ++f) {
      const int i = static_cast<int>(f);
      solver_problem.SetParameterLowerBound(phi.data(), i, lower_bound(bounds[f]));
      if (bounds[f] == Bound::kEfficiency) {
        solver_problem.SetParameterUpperBound(phi.data(), i, 1.0);
      }
    }
    ceres::Solver::Options solver_options;
    solver_options.minimizer_type = ceres::TRUST_REGION;
    solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    solver_options.linear_solver_type = ceres::DENSE_QR;
    solver_options.max_num_iterations = options.max_iterations;
    solver_options.num_threads = std::max(1, options.threads);
    solver_options.function_tolerance = 1e-12;
    solver_options.parameter_tolerance = 1e-12;
    solver_options.gradient_tolerance = 1e-14;
    solver_options.logging_type = ceres::SILENT;
    ceres::Solve(solver_options, &solver_problem, &summary);
    if (summary.termination_type == ceres::FAILURE) {
      throw EstimationError("physical fit: Levenberg-Marquardt failed: " + summary.message);
    }
    iterations += static_cast<int>(summary.iterations.size()) - 1;
    solve_seconds += summary.minimizer_time_in_seconds;
    coordinates.unknowns(phi.data(), theta1.data(), nullptr);
    if (has_load) {
      for (int i = 0; i < 10; ++i) load_phi[i] = phi[coordinates.load_offset() + i];
    }

    // Unknowns the search ended on a bound with are held there for the next round.
    bool changed = false;
    for (std::size_t f = 0; f < coordinates.free.size(); ++f) {
      const int u = coordinates.free[f];
      if (theta1[u] <= lower_bound(bounds[f]) ||
          (bounds[f] == Bound::kEfficiency && theta1[u] >= 1.0)) {
        held[u] = 1;
        changed = true;
      }
    }
    if (changed) continue;
    // None new: release a held one whose cost gradient points into the feasible side.
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    problem.evaluate(theta1, r, &J);
    const Eigen::VectorXd gradient = J.transpose() * r;
    for (int u = 0; u < U; ++u) {
      if (!held[u]) continue;
      const bool at_upper = bound[u] == Bound::kEfficiency && theta1[u] >= 1.0;
      if (at_upper ? gradient[u] > 0 : gradient[u] < 0) {
        held[u] = 0;
        changed = true;
      }
    }
    if (!changed) {
      settled = true;
      break;
    }
  }

  MlFitResult& fit = result.fit;
  fit.names = names;
  fit.initial = start;
  fit.identifiability = unconstrained.identifiability;
  fit.notes = unconstrained.notes;
  // Converged: the active set settled and the last search converged (or none was needed).
  fit.converged = settled && (!searched || summary.termination_type == ceres::CONVERGENCE);
  fit.iterations = iterations;
  fit.solve_seconds = solve_seconds;
  fit.solver_report = searched ? summary.BriefReport() : "no search: every unknown on its bound";

  Eigen::VectorXd residuals;
  Eigen::MatrixXd J;
  problem.evaluate(start, residuals, nullptr);
  fit.initial_cost = 0.5 * residuals.squaredNorm();
  Eigen::VectorXd unconstrained_theta1(U);
  for (int u = 0; u < U; ++u) unconstrained_theta1[u] = unconstrained.all_values[indices[u]];
  problem.evaluate(unconstrained_theta1, residuals, nullptr);
  result.unconstrained_sum_of_squares = residuals.squaredNorm();
  problem.evaluate(theta1, residuals, &J);
  fit.final_cost = 0.5 * residuals.squaredNorm();
  result.cost_increase = 2 * fit.final_cost - result.unconstrained_sum_of_squares;

  // Binding constraints: a drive unknown held on its bound, a load on the cone's boundary.
  std::vector<bool> at_bound(static_cast<std::size_t>(U), false);
  for (int u = 0; u < U; ++u) {
    if (!held[u]) continue;
    at_bound[static_cast<std::size_t>(u)] = true;
    const bool at_upper = bound[u] == Bound::kEfficiency && theta1[u] >= 1.0;
    result.binding.push_back(names[static_cast<std::size_t>(u)] + (at_upper ? " <= 1"
                                                                   : bound[u] == Bound::kEfficiency
                                                                       ? " > 0"
                                                                       : " >= 0"));
  }
  if (has_load) {
    double load[10];
    for (int i = 0; i < 10; ++i) load[i] = theta1[load_at[i]];
    const Eigen::Vector4d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(
                                       load_pseudo_inertia(load), Eigen::EigenvaluesOnly)
                                       .eigenvalues();
    if (lambda[0] < kBoundaryRatio * lambda[3]) {
      result.binding.push_back("load pseudo-inertia > 0");
    }
  }

  // Standard deviations from the Jacobian at the optimum with the binding bounds held (a
  // local, first-order figure: a load on the boundary gets the unconstrained local one).
  std::vector<bool> keep(static_cast<std::size_t>(U));
  Eigen::Index kept = 0;
  for (int u = 0; u < U; ++u) {
    keep[static_cast<std::size_t>(u)] =
        unconstrained.identifiability.identifiable[u] && !at_bound[static_cast<std::size_t>(u)];
    kept += keep[static_cast<std::size_t>(u)] ? 1 : 0;
  }
  const double s2 = residuals.squaredNorm() /
                    static_cast<double>(std::max<Eigen::Index>(1, problem.num_residuals() - kept));
  fit.residual_std_dev = std::sqrt(s2);
  fit.std_dev = detail::standard_deviations(J, keep, s2);
  fit.value = theta1;
  for (int u = 0; u < U; ++u) {
    if (at_bound[static_cast<std::size_t>(u)]) fit.std_dev[u] = 0;
    if (!unconstrained.identifiability.identifiable[u]) fit.value[u] = kNaN;
  }
  fit.all_values = problem.with_unknowns(theta1);
  const Eigen::MatrixXd errors = problem.torque_errors(fit.all_values);
  fit.rms_error =
      (errors.colwise().squaredNorm() / static_cast<double>(errors.rows())).cwiseSqrt().transpose();
  if (has_load) {
    Eigen::VectorXd load = fit.all_values.segment(P, kLoadParams);
    Eigen::VectorXd load_sd(kLoadParams);
    for (int i = 0; i < 10; ++i) {
      const int u = load_at[i];
      load_sd[i] = fit.std_dev[u];
      if (!unconstrained.identifiability.identifiable[u]) load[i] = kNaN;
    }
    fit.has_load = true;
    fit.load = LoadParameters::from_vector(load.data());
    fit.load_std_dev = LoadParameters::from_vector(load_sd.data());
    fit.load_warnings = load_warnings(fit.load);
  }
  return result;
}

}  // namespace modelgen
