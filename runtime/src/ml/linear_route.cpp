// Swevers et al. 2002, section 3.2 and approach 1 of section 4: weighted least squares on the
// base parameters of the linear drive model (efficiencies 1), then the load, friction and rotor
// inertias from the base-parameter estimates and the a-priori link values.
//
// The base parameters are numeric, of this experiment: a column-pivoted QR of the weighted,
// column-scaled regressor A D^-1 P = Q [R11 R12] gives psi = [I, R11^-1 R12] P^T D theta, the
// combinations the data determine, estimated as R11^-1 Q1^T b with covariance s^2 R11^-1 R11^-T
// (Gautier & Briot eq. 15-18 in this basis). The equations G theta = psi_hat ("solving a set of
// equations", section 3.2) are then solved for the unknown columns with the link values known, by
// generalised least squares with psi_hat's covariance: the combinations the experiment excites
// poorly (section 4's reason 3 for approach 1's errors) count as little as they deserve. The load
// comes from its ten standard parameters, load_from_standard (eq. 3 backwards).

#include "modelgen/ml/linear_route.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "modelgen/ml/identifiability.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "runtime/src/ml/linear_base.hpp"

namespace modelgen {
namespace {

using detail::BaseEstimate;
using detail::column_of;
using detail::drive_stem;
using detail::RouteInputs;
using detail::WeightedSystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Minimum-norm solution of M (x - x0) = y - M x0 on unit-norm columns, and d x / d y.
void minimum_norm_step(const Eigen::MatrixXd& M, const Eigen::VectorXd& y,
                       const Eigen::VectorXd& x0, Eigen::VectorXd& x, Eigen::MatrixXd& dx_dy) {
  Eigen::VectorXd scale = M.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c) {
    if (!(scale[c] > 0)) scale[c] = 1;
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(M *
                                                              scale.cwiseInverse().asDiagonal());
  cod.setThreshold(1e-10);
  dx_dy = scale.cwiseInverse().asDiagonal() * cod.pseudoInverse();
  x = x0 + dx_dy * (y - M * x0);
}

// The unknowns x of the equations G_X x = psi_hat - G_K theta_K.
struct RouteUnknowns {
  bool mass_known = false;
  int load_x = 0;                     // leading entries of x that are load parameters
  std::vector<std::string> names;     // name per entry of x
  std::vector<Eigen::Index> columns;  // column of theta_L per entry of x
  std::vector<std::string> skipped;   // unknowns the linear model does not contain
};

// The equations for the unknowns: G_X x = psi_hat - G_K theta_K, the known part from the
// a-priori values. Unknowns x: the payload's ten standard parameters of the load (its own
// values known), then the other unknown linear parameters and the rotor inertias.
RouteUnknowns route_unknowns(const RouteInputs& in, const std::vector<int>& linear,
                             std::vector<std::string>& notes) {
  const std::vector<int>& payload = in.problem.payload_indices();
  const Eigen::Index L = static_cast<Eigen::Index>(linear.size());
  const bool load = in.load;
  RouteUnknowns u;
  // A load mass known a priori (weighed, say) is the load's standard parameter M: known like the
  // links' values. The other load parameters enter the standard ones nonlinearly; when known,
  // they are imposed in the nonlinear search only.
  u.mass_known = load && !in.is_unknown(in.P);
  u.load_x = load ? (u.mass_known ? kLoadParams - 1 : kLoadParams) : 0;
  for (int m = 0; m < u.load_x; ++m) {  // the load's XX .. MZ (and M)
    u.names.push_back(load_param_names()[m + (u.mass_known ? 1 : 0)]);
    u.columns.push_back(column_of(linear, payload[m]));
  }
  const auto unknown_beyond_mass =
      std::count_if(in.unknown.begin(), in.unknown.end(), [&](int k) { return k > in.P; });
  if (load && unknown_beyond_mass < kLoadParams - 1) {
    notes.push_back(
        "linear route: known load parameters other than the mass are imposed in the nonlinear "
        "search only");
  }
  for (const int k : in.unknown) {
    if (k >= in.P) continue;
    const std::string stem = drive_stem(in.names[k]);
    if (stem == "Rz") continue;
    const Eigen::Index c = column_of(linear, k);
    if (c == L || (load && std::find(payload.begin(), payload.end(), k) != payload.end())) {
      u.skipped.push_back(in.names[k]);
      continue;
    }
    u.names.push_back(in.names[k]);
    u.columns.push_back(c);
  }
  for (const int k : linear) {
    if (drive_stem(in.names[k]) == "JM" && !in.is_unknown(k)) {
      u.names.push_back(in.names[k]);
      u.columns.push_back(column_of(linear, k));
    }
  }
  return u;
}

// x and its covariance, and the whitened equations M_w x = y_w they solve.
struct UnknownEstimate {
  Eigen::VectorXd x;
  Eigen::MatrixXd covariance, Mw;
};

// Generalised least squares for x with the estimates' covariance, from the a-priori values.
UnknownEstimate solve_unknowns(const RouteInputs& in, const std::vector<int>& linear,
                               const BaseEstimate& base, const RouteUnknowns& u) {
  const Eigen::VectorXd& all = in.all;
  const int P = in.P;
  const std::vector<int>& payload = in.problem.payload_indices();
  const Eigen::Index L = static_cast<Eigen::Index>(linear.size());
  const Eigen::Index X = static_cast<Eigen::Index>(u.columns.size());
  Eigen::VectorXd theta_known(L);
  for (Eigen::Index c = 0; c < L; ++c) theta_known[c] = all[linear[c]];  // own values
  if (u.mass_known) theta_known[column_of(linear, payload[9])] += all[P];
  Eigen::VectorXd x0(X);
  std::array<double, 10> load0{};
  if (in.load) load0 = standard_from_load(LoadParameters::from_vector(all.data() + P));
  for (Eigen::Index j = 0; j < X; ++j) {
    const bool load_entry = j < u.load_x;
    x0[j] = load_entry ? load0[static_cast<size_t>(j)] : all[linear[u.columns[j]]];
    if (!load_entry) theta_known[u.columns[j]] = 0;
  }
  Eigen::MatrixXd M(base.r, X);
  for (Eigen::Index j = 0; j < X; ++j) M.col(j) = base.G.col(u.columns[j]);
  // Generalised least squares with the estimates' covariance s^2 R11^-1 R11^-T: whitened by
  // R11 / s, so that combinations the data determine poorly count little.
  const Eigen::MatrixXd whiten = base.R11 / std::sqrt(base.s2);
  UnknownEstimate estimate;
  estimate.Mw = whiten * M;
  const Eigen::VectorXd yw = whiten * (base.psi - base.G * theta_known);
  Eigen::MatrixXd dx_dy;
  minimum_norm_step(estimate.Mw, yw, x0, estimate.x, dx_dy);
  const Eigen::MatrixXd dx_dpsi = dx_dy * whiten;
  estimate.covariance = dx_dpsi * base.psi_covariance * dx_dpsi.transpose();
  return estimate;
}

// The load found from x, and d (load terms) / d x.
struct LoadTerms {
  Eigen::MatrixXd to_load;
  LoadParameters estimate;
  bool found = false;
};

// The load in its own terms; its covariance and the identifiability in those terms through
// d standard / d load (at the estimate, or where the search would start when it has no mass).
LoadTerms load_terms(const RouteInputs& in, const RouteUnknowns& u, const Eigen::VectorXd& x,
                     std::vector<std::string>& notes) {
  const Eigen::Index X = x.size();
  LoadTerms terms;
  terms.to_load = Eigen::MatrixXd::Identity(X, X);
  if (!in.load) return terms;
  const int load_x = u.load_x;
  LoadParameters at = LoadParameters::from_vector(in.all.data() + in.P);
  double standard[10];
  for (int m = 0; m < load_x; ++m) standard[m] = x[m];
  if (u.mass_known) standard[9] = in.all[in.P];
  try {
    terms.estimate = load_from_standard(standard);
    at = terms.estimate;
    terms.found = true;
  } catch (const std::invalid_argument& error) {
    notes.push_back(std::string("linear route: no load from the base parameters (") + error.what() +
                    (at.mass > 0
                         ? "); the search starts from the given load"
                         : "); with no a-priori load, the search starts from 1 kg at the origin of "
                           "the payload link's frame"));
  }
  if (!(at.mass > 0)) at.mass = 1;  // only to name directions in load terms
  // d standard / d load; with the mass known, XX .. MZ against cx .. Iyz.
  const Eigen::MatrixXd S = standard_from_load_jacobian(at);
  terms.to_load.topLeftCorner(load_x, load_x) =
      (u.mass_known ? Eigen::MatrixXd(S.block(0, 1, load_x, load_x)) : S).inverse();
  return terms;
}

// The unknowns' values, standard deviations and identifiability into `fit`, the load in its
// own terms, and the note on the unknowns the linear model leaves alone.
void report_unknowns(const RouteInputs& in, const RouteUnknowns& u, const UnknownEstimate& estimate,
                     const LoadTerms& terms, double rank_tolerance, MlFitResult& fit) {
  const Eigen::Index X = estimate.x.size();
  const Eigen::Index r = estimate.Mw.rows();
  const int load_x = u.load_x;
  const Eigen::MatrixXd covariance =
      terms.to_load * estimate.covariance * terms.to_load.transpose();
  // At least as many rows as unknowns for identifiability(): fewer base parameters than
  // unknowns leave directions undetermined, which zero rows keep visible.
  Eigen::MatrixXd M_load = Eigen::MatrixXd::Zero(std::max(r, X), X);
  M_load.topRows(r) = estimate.Mw * terms.to_load.inverse();
  fit.names = u.names;
  fit.identifiability = identifiability(M_load, u.names, rank_tolerance);
  fit.value = estimate.x;
  fit.std_dev = covariance.diagonal().cwiseSqrt();
  if (terms.found) {
    const std::array<double, kLoadParams> v = terms.estimate.to_vector();
    for (int m = 0; m < load_x; ++m)
      fit.value[m] = v[static_cast<size_t>(m + kLoadParams - load_x)];
  } else if (in.load) {
    fit.value.head(load_x).setConstant(kNaN);
    fit.std_dev.head(load_x).setConstant(kNaN);
  }
  for (Eigen::Index j = 0; j < X; ++j) {
    if (!fit.identifiability.identifiable[static_cast<size_t>(j)]) {
      fit.value[j] = kNaN;
      fit.std_dev[j] = kNaN;
    }
  }
  if (in.load) {
    // The ten load values; a known mass in front, with standard deviation 0.
    Eigen::VectorXd value(kLoadParams), sd(kLoadParams);
    if (u.mass_known) {
      value << in.all[in.P], fit.value.head(load_x);
      sd << 0.0, fit.std_dev.head(load_x);
    } else {
      value = fit.value.head(kLoadParams);
      sd = fit.std_dev.head(kLoadParams);
    }
    fit.has_load = true;
    fit.load = LoadParameters::from_vector(value.data());
    fit.load_std_dev = LoadParameters::from_vector(sd.data());
    fit.load_warnings = load_warnings(fit.load);
  }
  if (!u.skipped.empty()) {
    std::string list;
    for (const std::string& name : u.skipped) list += " " + name;
    fit.notes.push_back("linear route: not in the linear model, kept at the given values:" + list);
  }
}

// The starting point of the nonlinear search: the problem's unknowns from x.
Eigen::VectorXd starting_values(const RouteInputs& in, const std::vector<int>& linear,
                                const RouteUnknowns& u, const Eigen::VectorXd& x,
                                const LoadTerms& terms) {
  const int P = in.P;
  Eigen::VectorXd values = in.all;
  for (Eigen::Index j = u.load_x; j < x.size(); ++j) {
    const int k = linear[u.columns[j]];
    if (in.is_unknown(k)) values[k] = x[j];
  }
  if (terms.found) {
    const std::array<double, kLoadParams> v = terms.estimate.to_vector();
    for (int m = 0; m < kLoadParams; ++m) {
      if (in.is_unknown(P + m)) values[P + m] = v[static_cast<size_t>(m)];
    }
  } else if (in.load && !u.mass_known && !(in.all[P] > 0)) {
    // Nothing to start from: a unit mass, so that the centre of gravity has an effect and the
    // rank at the start is the generic one (at m = 0 the centre of gravity would look
    // unidentifiable and the mass identifiable, whatever the data).
    for (int m = 0; m < kLoadParams; ++m) {
      if (in.is_unknown(P + m)) values[P + m] = m == 0 ? 1.0 : 0.0;
    }
  }
  return values;
}

}  // namespace

LinearRoute linear_route(const MlProblem& problem, double rank_tolerance) {
  const RouteInputs in(problem);
  LinearRoute route;
  MlFitResult& fit = route.fit;
  const std::vector<int> linear = detail::linear_parameters(in);
  const WeightedSystem system = detail::weighted_system(in, linear);
  const BaseEstimate base = detail::base_estimate(system, route);
  fit.residual_std_dev = std::sqrt(base.s2);
  fit.rms_error = detail::linear_rms_error(in, system, base);
  const RouteUnknowns unknowns = route_unknowns(in, linear, fit.notes);
  const UnknownEstimate estimate = solve_unknowns(in, linear, base, unknowns);
  const LoadTerms terms = load_terms(in, unknowns, estimate.x, fit.notes);
  report_unknowns(in, unknowns, estimate, terms, rank_tolerance, fit);
  route.values = starting_values(in, linear, unknowns, estimate.x, terms);
  fit.all_values = route.values;
  fit.initial = fit.value;
  fit.converged = true;
  return route;
}

}  // namespace modelgen
