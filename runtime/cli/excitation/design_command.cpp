// modelid design: an optimal Fourier excitation for the description's robot (Swevers 1997,
// Bona & Curatella eq. 17-20) within its joint limits, written in the trajectory format
// simulate reads (form: position), with a report of what it achieves.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/excitation/expected_precision.hpp"
#include "modelgen/excitation/limit_use.hpp"
#include "modelgen/io/experiment/fourier_file.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/q_limit_option.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/excitation/a_priori_torque.hpp"
#include "runtime/cli/excitation/design_report.hpp"
#include "runtime/cli/excitation/trajectory_limits.hpp"
#include "runtime/cli/plots/torque_plots.hpp"
#include "runtime/cli/plots/trajectory_plot.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

int parse_count(const std::string& text, const std::string& option, int low, int high) {
  int value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < low || value > high) {
    throw UsageError{option + " must be an integer from " + std::to_string(low) + " to " +
                     std::to_string(high) + ", not '" + text + "'"};
  }
  return value;
}

// --axes 3,4,5,6 (1-based) as 0-based joints, sorted; default every joint.
std::vector<int> parse_axes(const CommandLine& args, int dof) {
  std::vector<int> axes;
  if (!args.has("--axes")) {
    for (int j = 0; j < dof; ++j) axes.push_back(j);
    return axes;
  }
  for (const std::string& item : comma_items(args.one("--axes"), "--axes")) {
    const int axis = parse_count(item, "--axes", 1, dof) - 1;
    if (std::find(axes.begin(), axes.end(), axis) != axes.end()) {
      throw UsageError{"--axes names axis " + item + " twice"};
    }
    axes.push_back(axis);
  }
  std::sort(axes.begin(), axes.end());
  return axes;
}

// The position of every joint that does not move: --hold qJ=V, else 0 when inside its range,
// else the middle of the range.
Eigen::VectorXd parse_hold(const CommandLine& args, const ModelSource& source,
                           const std::vector<int>& moving) {
  const int dof = source.model->dof();
  Eigen::VectorXd hold = Eigen::VectorXd::Zero(dof);
  std::vector<bool> given(static_cast<std::size_t>(dof), false);
  if (args.has("--hold")) {
    for (const std::string& item : comma_items(args.one("--hold"), "--hold")) {
      const auto equals = item.find('=');
      if (equals == std::string::npos || item.size() < 2 || item[0] != 'q') {
        throw UsageError{"--hold takes qJ=POSITION items (q1=0,q2=-1.57), not '" + item + "'"};
      }
      const int j = parse_count(item.substr(1, equals - 1), "--hold's joint", 1, dof) - 1;
      if (std::find(moving.begin(), moving.end(), j) != moving.end()) {
        throw UsageError{"--hold: joint " + std::to_string(j + 1) + " moves (--axes); hold only the others"};
      }
      hold[j] = parse_number(item.substr(equals + 1), "--hold");
      given[static_cast<std::size_t>(j)] = true;
    }
  }
  for (int j = 0; j < dof; ++j) {
    const JointLimits& limit = source.limits.empty() ? JointLimits{} : source.limits[static_cast<std::size_t>(j)];
    if (std::find(moving.begin(), moving.end(), j) != moving.end() || !limit.q_lower) continue;
    const bool inside = hold[j] >= *limit.q_lower && hold[j] <= *limit.q_upper;
    if (given[static_cast<std::size_t>(j)] && !inside) {
      throw UsageError{"--hold: q" + std::to_string(j + 1) + " = " + shortest(hold[j]) +
                       " is outside " + joint_label(source, j) + "'s range [" +
                       shortest(*limit.q_lower) + ", " + shortest(*limit.q_upper) + "]"};
    }
    if (!inside) hold[j] = (*limit.q_lower + *limit.q_upper) / 2;
  }
  return hold;
}

// The limits the moving joints need, with --ddq-limit for descriptions that give none (or to
// override theirs); a missing one is an error naming the joint and the key.
std::vector<JointLimits> design_limits(const CommandLine& args, const ModelSource& source,
                                       const std::vector<int>& moving) {
  const RobotModel* description = source.any_description();
  const std::string where = description != nullptr ? description->source_file : source.model->name();
  if (source.limits.empty()) {
    throw std::runtime_error("modelid design: error: no description of '" + source.model->name() +
                             "' was found, and design needs its joint limits (q, dq, ddq); "
                             "give --robot DESCRIPTION.yaml");
  }
  std::vector<JointLimits> limits = source.limits;
  apply_ddq_limit_option(args, limits);
  for (int j : moving) {
    const JointLimits& limit = limits[static_cast<std::size_t>(j)];
    std::string key;
    if ((!limit.q_lower || !limit.q_upper) && !limit.continuous)
      key = "q";
    else if (!limit.dq) key = "dq";
    else if (!limit.ddq) key = "ddq";
    if (key.empty()) continue;
    throw std::runtime_error(
        where + ": error: " + joint_label(source, j) + " has no '" + key +
        "' limit, which design needs for every moving joint: add limits: {" + key +
        ": ...} to the joint (URDF: <limit lower upper velocity>)" +
        (key == "ddq" ? ", or give --ddq-limit" : ""));
  }
  return limits;
}

std::string trajectory_yaml(const ExcitationDesign& design, const std::string& header) {
  std::ostringstream out;
  out << header << "period: " << shortest(design.period) << "\nform: position\njoints:\n";
  for (Eigen::Index j = 0; j < design.q0.size(); ++j) {
    out << "  - {q0: " << shortest(design.q0[j]);
    if (design.a.row(j).cwiseAbs().maxCoeff() == 0 && design.b.row(j).cwiseAbs().maxCoeff() == 0) {
      out << ", terms: []}\n";
      continue;
    }
    for (const auto& [name, m] : {std::pair{"a", &design.a}, std::pair{"b", &design.b}}) {
      out << ", " << name << ": [";
      for (Eigen::Index l = 0; l < m->cols(); ++l) out << (l ? ", " : "") << shortest((*m)(j, l));
      out << "]";
    }
    out << "}\n";
  }
  return out.str();
}

// The problem the options describe (fit's table checked types; the ranges are design's).
ExcitationDesignProblem design_problem(const CommandLine& args, const ModelSource& source) {
  const IdentificationModel& model = *source.model;
  ExcitationDesignProblem problem;
  problem.model = &model;
  problem.period = parse_number(args.one("--period"), "--period");
  if (!(problem.period >= 0.1 && problem.period <= 1e4)) {
    throw UsageError{"--period must be from 0.1 s to 1e4 s, not '" + args.one("--period") + "'"};
  }
  problem.harmonics = parse_count(args.one("--harmonics"), "--harmonics", 1, 50);
  problem.moving = parse_axes(args, model.dof());
  problem.limits = design_limits(args, source, problem.moving);
  problem.hold = parse_hold(args, source, problem.moving);
  if (const auto beta = effort_check_parameters(std::cerr, "design", source)) problem.a_priori = *beta;
  if (args.has("--criterion")) {
    problem.criterion =
        args.one("--criterion") == "cond" ? DesignCriterion::kCond : DesignCriterion::kLogDet;
  }
  if (args.has("--margin")) {
    problem.margin = parse_number(args.one("--margin"), "--margin");
    if (!(problem.margin > 0 && problem.margin <= 1)) {
      throw UsageError{"--margin must be in (0, 1], not '" + args.one("--margin") + "'"};
    }
  }
  if (args.has("--starts")) problem.starts = parse_count(args.one("--starts"), "--starts", 1, 100);
  if (args.has("--samples")) problem.samples = parse_count(args.one("--samples"), "--samples", 10, 100000);
  if (args.has("--max-evaluations")) {
    problem.max_evaluations = parse_count(args.one("--max-evaluations"), "--max-evaluations", 1, 1000000);
  }
  if (args.has("--seed")) {
    const std::string& text = args.one("--seed");
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), problem.seed);
    if (ec != std::errc() || end != text.data() + text.size()) {
      throw UsageError{"--seed must be a non-negative integer, not '" + text + "'"};
    }
  }
  problem.progress = [](const std::string& line) {
    std::cerr << "modelid design: " << line << "\n";
  };
  return problem;
}

// The head of the written file: the command that makes it again (the options that change it,
// as given) and the criterion it reached.
std::string design_header(const CommandLine& args, const ExcitationDesignProblem& problem,
                          const ExcitationDesign& design) {
  std::ostringstream header;
  header << "# made by: modelid design";
  for (const char* option :
       {"--robot", "--angle-tolerance", "--name", "--base", "--tip", "--period", "--harmonics",
        "--axes", "--hold", "--criterion", "--margin", "--starts", "--seed", "--samples",
        "--ddq-limit", "--max-evaluations"}) {
    if (args.has(option)) header << " " << option << " " << args.one(option);
  }
  if (args.has("--mimic-as-joint")) header << " --mimic-as-joint";
  for (const std::string& range : args.all("--q-limit")) header << " --q-limit " << range;
  header << "\n# criterion "
         << (problem.criterion == DesignCriterion::kCond ? "log cond" : "-log det")
         << ": best of 100 random feasible starts " << fixed(design.before.value, 0, 6)
         << ", this design " << fixed(design.after.value, 0, 6) << "\n";
  return header.str();
}

}  // namespace

int run_design(const CommandLine& args) {
  ModelSource source = load_model_source(args.one("--robot"), args);
  apply_q_limit_option(args, source);
  const IdentificationModel& model = *source.model;
  const ExcitationDesignProblem problem = design_problem(args, source);
  const double noise = args.has("--noise") ? parse_number(args.one("--noise"), "--noise") : 1.0;
  const std::string& output = args.one("-o");
  if (args.has("--plot")) check_plot_folder(args.one("--plot"));
  // Read before the optimisation: a broken file should not cost a design run.
  std::optional<FourierTrajectory> compared;
  if (args.has("--compare")) compared = read_fourier(args.one("--compare"), model.dof());

  // The library's reasons (effort limits no start meets) name no file; the description is it.
  const ExcitationDesign design = [&] {
    try {
      return design_excitation(problem);
    } catch (const std::runtime_error& error) {
      const RobotModel* description = source.any_description();
      throw std::runtime_error((description != nullptr ? description->source_file : model.name()) +
                               ": error: " + error.what());
    }
  }();

  // The file first: the report is about what was written.
  write_file(output, trajectory_yaml(design, design_header(args, problem, design)));
  const FourierTrajectory trajectory = to_trajectory(design.q0, design.a, design.b, design.period);
  const DesignReport report{source, problem, design, trajectory};
  print_conditioning(std::cout, report);
  if (compared) print_comparison(std::cout, report, *compared, args.one("--compare"));
  print_shrinks(std::cout, report);
  print_expected_precision(std::cout, report, noise);
  print_limits_and_torques(std::cout, report);
  std::cerr << "modelid design: written to " << output << "\n";
  if (args.has("--plot")) {
    const std::string plot = write_trajectory_plot(args.one("--plot"), trajectory, source, problem.limits,
                                                   output + ": modelid design for " + model.name());
    std::cerr << "modelid design: plot written to " << plot << "\n";
  }
  return 0;
}

}  // namespace modelgen::internal
