// Excitation design by SLSQP (NLopt) over Fourier coefficients; see excitation_design.hpp.
//
// Variables, per moving joint: q0, a_1..a_L, b_1..b_L of the position form
// q = q0 + sum a_l sin(l wf t) + b_l cos(l wf t) (Swevers 2002 eq. 15), so that
//   dq = sum l wf (a_l cos - b_l sin),  ddq = -sum (l wf)^2 (a_l sin + b_l cos),
// all linear in the variables: the limit constraints and their gradients are exact closed
// forms. The criterion's gradient is analytic through the Fourier series, the criterion
// (design_criterion.hpp) and the model's state Jacobian (design_gradient.cpp): exact for a
// generated model, 2 Jacobians per sample for cond.

#include "modelgen/excitation/excitation_design.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <Eigen/QR>
#include <nlopt.h>

#include "runtime/src/excitation/design_variables.hpp"

namespace modelgen {

namespace {

using detail::Design;
using detail::RowMajor;
using detail::shortest_text;

double objective(unsigned n, const double* x, double* grad, void* data) {
  Design& design = *static_cast<Design*>(data);
  ++design.evaluations;
  std::vector<double> point(x, x + n), gradient;
  const CriterionValue value = design.criterion(point, grad != nullptr ? &gradient : nullptr);
  if (grad != nullptr) std::copy(gradient.begin(), gradient.end(), grad);
  // SLSQP cannot step from +inf; a rank-deficient point is just very bad.
  return std::isfinite(value.value) ? value.value : 1e30;
}

void constraint(unsigned /*m*/, double* result, unsigned /*n*/, const double* x, double* grad,
                void* data) {
  static_cast<Design*>(data)->limit_constraints(x, result, grad);
}

}  // namespace

FourierTrajectory to_trajectory(const Eigen::VectorXd& q0, const Eigen::MatrixXd& a,
                                const Eigen::MatrixXd& b, double period) {
  // Position amplitudes to FourierTrajectory's velocity amplitudes (its eq. 15 form).
  FourierTrajectory x;
  x.period = period;
  x.q0 = q0;
  x.a.resize(a.rows(), a.cols());
  x.b.resize(b.rows(), b.cols());
  const double wf = 2 * std::numbers::pi / period;
  for (Eigen::Index l = 0; l < a.cols(); ++l) {
    x.a.col(l) = a.col(l) * ((l + 1) * wf);
    x.b.col(l) = -b.col(l) * ((l + 1) * wf);
  }
  return x;
}

Eigen::MatrixXd stacked_regressor(const IdentificationModel& model,
                                  const FourierTrajectory& trajectory, int samples) {
  const int dof = model.dof();
  Eigen::MatrixXd W(static_cast<Eigen::Index>(samples) * dof, model.num_base_params());
  RowMajor block(dof, model.num_base_params());
  Eigen::VectorXd q, dq, ddq;
  for (int k = 0; k < samples; ++k) {
    trajectory.evaluate(trajectory.period * k / samples, q, dq, ddq);
    model.regressor(q.data(), dq.data(), ddq.data(), block.data());
    W.middleRows(static_cast<Eigen::Index>(k) * dof, dof) = block;
  }
  return W;
}

double design_objective(const ExcitationDesignProblem& problem, const std::vector<int>& columns,
                        const Eigen::VectorXd& scale, const std::vector<double>& x,
                        std::vector<double>* gradient) {
  Design design(problem);
  design.set_columns(columns);
  design.set_scale(scale);
  return design.criterion(x, gradient).value;
}

std::vector<double> design_constraints(const ExcitationDesignProblem& problem,
                                       const std::vector<double>& x, std::vector<double>* jacobian) {
  Design design(problem);
  std::vector<double> c(static_cast<std::size_t>(design.constraints()));
  if (jacobian != nullptr) jacobian->assign(c.size() * x.size(), 0.0);
  design.limit_constraints(x.data(), c.data(), jacobian != nullptr ? jacobian->data() : nullptr);
  return c;
}

ExcitationDesign design_excitation(const ExcitationDesignProblem& problem) {
  if (problem.model == nullptr || problem.moving.empty() || problem.harmonics < 1 ||
      !(problem.period > 0) || problem.hold.size() != problem.model->dof() ||
      problem.limits.size() != static_cast<std::size_t>(problem.model->dof()) ||
      problem.random_starts < 1 || problem.starts < 1 ||
      (problem.a_priori.size() != 0 && problem.a_priori.size() != problem.model->num_base_params())) {
    throw std::invalid_argument("design_excitation: inconsistent problem");
  }
  const auto say = [&problem](const std::string& line) {
    if (problem.progress) problem.progress(line);
  };
  Design design(problem);
  std::uint64_t state = problem.seed;

  // Random feasible starts; the first three also decide which base parameters the moving axes
  // excite at all (a held axis leaves some unidentifiable: Swevers 2002 section 4.2).
  std::vector<std::vector<double>> starts;
  for (int s = 0; s < problem.random_starts; ++s) {
    std::vector<double> start = design.random_start(state);
    if (!start.empty()) starts.push_back(std::move(start));
  }
  if (starts.empty()) throw std::runtime_error(design.explain_torque_at_rest(problem.random_starts));
  design.choose_columns({starts.begin(), starts.begin() + std::min<std::size_t>(3, starts.size())});
  design.choose_scale(starts);
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t s = 0; s < starts.size(); ++s) {
    ranked.emplace_back(design.criterion(starts[s], nullptr).value, s);
  }
  std::sort(ranked.begin(), ranked.end());
  say(std::to_string(starts.size()) + " random feasible starts, best criterion " +
      shortest_text(ranked.front().first));

  ExcitationDesign result;
  result.period = problem.period;
  result.samples = design.samples();
  result.columns = design.columns();
  result.scale = design.scale();
  result.before = design.criterion(starts[ranked.front().second], nullptr);

  std::vector<double> lower, upper, best, best_shrink;
  design.variable_bounds(lower, upper);
  double best_value = std::numeric_limits<double>::infinity();
  const int optimised = std::min(problem.starts, static_cast<int>(starts.size()));
  for (int s = 0; s < optimised; ++s) {
    std::vector<double> x = starts[ranked[static_cast<std::size_t>(s)].second];
    nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, static_cast<unsigned>(x.size()));
    nlopt_set_min_objective(opt, objective, &design);
    const std::vector<double> tolerances(static_cast<std::size_t>(design.constraints()), 1e-9);
    nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(design.constraints()), constraint,
                                     &design, tolerances.data());
    nlopt_set_lower_bounds(opt, lower.data());
    nlopt_set_upper_bounds(opt, upper.data());
    nlopt_set_maxeval(opt, problem.max_evaluations);
    nlopt_set_ftol_rel(opt, 1e-7);
    double value = 0;
    const int before = design.evaluations;
    const nlopt_result code = nlopt_optimize(opt, x.data(), &value);
    nlopt_destroy(opt);
    const std::vector<double> shrink = design.repair_on_dense_grid(x);
    const double torque_shrink = design.repair_torque_on_dense_grid(x);
    const double repaired = design.criterion(x, nullptr).value;
    say("start " + std::to_string(s + 1) + "/" + std::to_string(optimised) + ": " +
        shortest_text(ranked[static_cast<std::size_t>(s)].first) + " -> " + shortest_text(repaired) +
        " (" + std::to_string(design.evaluations - before) + " evaluations, NLopt code " +
        std::to_string(static_cast<int>(code)) + ")");
    if (repaired < best_value) {
      best_value = repaired, best = x, best_shrink = shrink, result.torque_shrink = torque_shrink;
    }
  }
  // The kept design, checked once more on the dense grid (a no-op unless it was repaired).
  design.repair_on_dense_grid(best);
  design.repair_torque_on_dense_grid(best);
  result.shrink = best_shrink;
  design.coefficients(best, result.q0, result.a, result.b);
  result.after = design.criterion(best, nullptr);
  result.evaluations = design.evaluations;
  result.regressor = stacked_regressor(*problem.model,
                                       to_trajectory(result.q0, result.a, result.b, problem.period),
                                       design.samples());
  return result;
}

}  // namespace modelgen
