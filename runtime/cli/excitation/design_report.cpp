// What modelid design prints of a design (design_report.hpp).

#include "runtime/cli/excitation/design_report.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "modelgen/excitation/design_criterion.hpp"
#include "modelgen/excitation/expected_precision.hpp"
#include "modelgen/excitation/limit_use.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/excitation/a_priori_torque.hpp"
#include "runtime/cli/excitation/trajectory_limits.hpp"

namespace modelgen::internal {

namespace {

// The description's a-priori base parameters (unknown standard values taken as 0), or none.
std::optional<Eigen::VectorXd> a_priori_base(const ModelSource& source) {
  const RobotModel* description = source.any_description();
  if (description == nullptr ||
      description->param_names() != source.model->standard_param_names()) {
    return std::nullopt;
  }
  Eigen::VectorXd standard = Eigen::VectorXd::Zero(source.model->num_standard_params());
  bool any = false;
  for (std::size_t k = 0; k < description->known_values.size(); ++k) {
    if (description->known_values[k]) {
      standard[static_cast<Eigen::Index>(k)] = *description->known_values[k];
      any = true;
    }
  }
  if (!any) return std::nullopt;
  Eigen::VectorXd beta(source.model->num_base_params());
  source.model->base_from_standard(standard.data(), beta.data());
  return beta;
}

// The excited columns of `regressor`.
Eigen::MatrixXd excited_columns(const Eigen::MatrixXd& regressor, const std::vector<int>& columns) {
  Eigen::MatrixXd selected(regressor.rows(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) {
    selected.col(static_cast<Eigen::Index>(c)) = regressor.col(columns[c]);
  }
  return selected;
}

void print_criterion_line(std::ostream& out, const std::string& what, const CriterionValue& v) {
  out << pad(what, 28) << "cond " << fixed(v.cond_scaled, 0, 5) << ", unit columns "
      << fixed(v.cond_unit, 0, 5) << ", unscaled " << fixed(v.cond_unscaled, 0, 5)
      << "; smallest singular value " << fixed(v.sigma_min_scaled, 0, 5) << ", unscaled "
      << fixed(v.sigma_min_unscaled, 0, 5) << "\n";
}

// How far the criterion could go at all: a pair of columns nearly parallel sets a floor no
// column scaling removes (Coulomb and viscous friction of one joint, typically: sign(dq) and
// dq). `selected` holds the excited columns.
void print_floor(std::ostream& out, const DesignReport& report, const std::string& what,
                 const Eigen::MatrixXd& selected) {
  const auto& names = report.source.model->base_param_names();
  const std::vector<int>& columns = report.design.columns;
  const CollinearPair pair = most_collinear_pair(selected);
  out << pad(what, 28) << "most collinear columns "
      << names[static_cast<std::size_t>(columns[static_cast<std::size_t>(pair.first)])] << " and "
      << names[static_cast<std::size_t>(columns[static_cast<std::size_t>(pair.second)])]
      << " (|cos| " << fixed(pair.correlation, 0, 4) << "): no column scaling brings cond below "
      << fixed(pair.cond_floor, 0, 4) << "\n";
}

}  // namespace

void print_conditioning(std::ostream& out, const DesignReport& report) {
  const ExcitationDesignProblem& problem = report.problem;
  const ExcitationDesign& design = report.design;
  const IdentificationModel& model = *report.source.model;
  const auto& names = model.base_param_names();
  out << model.name() << ": " << problem.moving.size() << " moving axes, " << problem.harmonics
      << " harmonics, period " << shortest(problem.period) << " s; the regressor stacked over "
      << design.samples << " samples of one period ("
      << fixed(design.samples / problem.period, 0, 6)
      << " Hz); columns divided by their RMS norm over the random starts (fixed: units drop "
         "out, a weakly excited parameter still counts)\n";
  out << "base parameters the moving axes excite: " << design.columns.size() << " of "
      << names.size();
  if (design.columns.size() < names.size()) {
    out << " (left out:";
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (std::find(design.columns.begin(), design.columns.end(), static_cast<int>(c)) ==
          design.columns.end()) {
        out << " " << names[c];
      }
    }
    out << ")";
  }
  out << "\n";
  out << "criterion " << (problem.criterion == DesignCriterion::kCond ? "log cond" : "-log det")
      << ": best of 100 random feasible starts " << fixed(design.before.value, 0, 6)
      << ", designed " << fixed(design.after.value, 0, 6) << " (" << design.evaluations
      << " evaluations)\n";
  print_criterion_line(out, "best random feasible start:", design.before);
  print_criterion_line(out, "design:", design.after);
  print_floor(out, report, "design:", excited_columns(design.regressor, design.columns));
}

void print_comparison(std::ostream& out, const DesignReport& report,
                      const FourierTrajectory& compared, const std::string& path) {
  // The same criterion on another trajectory (Swevers 2002 Table 1, say): the same columns
  // and the same number of samples per period.
  const ExcitationDesign& design = report.design;
  const Eigen::MatrixXd selected = excited_columns(
      stacked_regressor(*report.source.model, compared, design.samples), design.columns);
  const CriterionValue value =
      evaluate_criterion(selected, design.scale, report.problem.criterion, false);
  out << "--compare " << path << ": criterion " << fixed(value.value, 0, 6) << " (period "
      << shortest(compared.period) << " s, " << design.samples << " samples)\n";
  print_criterion_line(out, "--compare:", value);
  print_floor(out, report, "--compare:", selected);
}

void print_shrinks(std::ostream& out, const DesignReport& report) {
  const std::vector<double>& shrink = report.design.shrink;
  for (std::size_t j = 0; j < shrink.size(); ++j) {
    if (shrink[j] < 1) {
      out << joint_label(report.source, static_cast<int>(j))
          << ": left a limit between the optimiser's constraint points; its oscillation shrunk by "
          << fixed(100 * (1 - shrink[j]), 0, 3) << "% to stay inside on the dense grid\n";
    }
  }
}

void print_expected_precision(std::ostream& out, const DesignReport& report, double noise) {
  // sigma^2 (W^T W)^-1 over the excited columns: the covariance of an OLS fit of one period
  // sampled as assumed, with the noise --noise on every torque sample.
  const ExcitationDesign& design = report.design;
  const auto& names = report.source.model->base_param_names();
  const Eigen::VectorXd expected_sd =
      expected_std_devs(excited_columns(design.regressor, design.columns), noise);
  const std::optional<Eigen::VectorXd> prior = a_priori_base(report.source);
  out << "expected standard deviations for --noise " << shortest(noise)
      << " N m per torque sample, one period at the rate above"
      << (prior ? ", %std of the description's a-priori values" : "") << ":\n";
  for (std::size_t c = 0; c < design.columns.size(); ++c) {
    const double sd = expected_sd[static_cast<Eigen::Index>(c)];
    out << "  " << pad(names[static_cast<std::size_t>(design.columns[c])], 10) << " sd "
        << fixed(sd, 0, 4);
    if (prior && (*prior)[design.columns[c]] != 0) {
      out << "  " << fixed(100 * sd / std::abs((*prior)[design.columns[c]]), 0, 3) << "%";
    }
    out << "\n";
  }
}

void print_limits_and_torques(std::ostream& out, const DesignReport& report) {
  const ExcitationDesignProblem& problem = report.problem;
  const long points = limit_grid_points(report.trajectory);
  out << "limit use on " << points << " points of one period ("
      << fixed(points / report.design.period, 0, 6) << " Hz), margin " << shortest(problem.margin)
      << ":\n";
  print_limit_use(out, report.source, trajectory_extremes(report.trajectory), problem.limits);
  if (problem.a_priori.size() == 0) return;
  if (report.design.torque_shrink < 1) {
    out << "the a-priori torques left an effort limit between the optimiser's constraint "
           "points; every oscillation shrunk by "
        << fixed(100 * (1 - report.design.torque_shrink), 0, 3)
        << "% to stay inside on the dense grid\n";
  }
  out << "a-priori joint torques (the description's inertial values; drive and friction values "
         "it does not give taken as 0), held within the effort limits times the margin:\n";
  print_torque_use(out, report.source,
                   torque_peaks(*report.source.model, problem.a_priori, report.trajectory),
                   problem.limits);
}

}  // namespace modelgen::internal
