// MDH YAML descriptions as modelid design reads them: load_robot, the numeric reference model,
// the joint limits of every joint, then a small design (one harmonic, few starts and
// evaluations) when every joint has the q, dq and ddq limits design needs (modelid design
// refuses the others by name). The design may refuse a description with a reason
// (std::runtime_error, which modelid prints against the description, exit 1); anything else
// is a finding: an inconsistent problem let through (std::invalid_argument), or a design with
// numbers that are not finite or a shrink that is not in (0, 1].

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

// The limits of the model's joints in its order; false when a joint lacks one design needs.
bool joint_limits(const modelgen::RobotModel& robot, int dof,
                  std::vector<modelgen::JointLimits>& limits) {
  if (robot.joints.size() != robot.tree.bodies.size()) return false;
  limits.assign(static_cast<std::size_t>(dof), {});
  for (std::size_t b = 0; b < robot.joints.size(); ++b) {
    const int j = robot.tree.bodies[b].dof_index;
    if (j >= 0 && j < dof) limits[static_cast<std::size_t>(j)] = robot.joints[b].limits;
  }
  for (const modelgen::JointLimits& limit : limits) {
    if (!limit.q_lower || !limit.q_upper || !limit.dq || !limit.ddq) return false;
  }
  return true;
}

void check_design(const modelgen::ExcitationDesign& design) {
  const bool finite = design.q0.allFinite() && design.a.allFinite() && design.b.allFinite() &&
                      std::isfinite(design.after.value);
  bool shrinks = design.torque_shrink > 0 && design.torque_shrink <= 1;
  for (double s : design.shrink) shrinks = shrinks && s > 0 && s <= 1;
  // Not a modelgen::Error: the harness reports it as a finding.
  if (!finite) throw std::logic_error("design_excitation returned numbers that are not finite");
  if (!shrinks) throw std::logic_error("design_excitation returned a shrink outside (0, 1]");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = modelgen::fuzz::input_file(data, size, "yaml");
  modelgen::fuzz::expect_only_input_errors([&] {
    const modelgen::RobotModel robot = modelgen::load_robot(path);
    const modelgen::ReferenceModel model(robot.name, robot.tree, "", robot.drives);
    modelgen::ExcitationDesignProblem problem;
    problem.model = &model;
    if (!joint_limits(robot, model.dof(), problem.limits)) return;
    problem.period = 2;
    problem.harmonics = 1;
    for (int j = 0; j < model.dof(); ++j) problem.moving.push_back(j);
    problem.hold = Eigen::VectorXd::Zero(model.dof());
    problem.samples = 10;
    problem.random_starts = 4;
    problem.starts = 1;
    problem.max_evaluations = 20;
    try {
      check_design(modelgen::design_excitation(problem));
    } catch (const std::invalid_argument&) {
      throw;  // an inconsistent problem the loader let through: a finding
    } catch (const std::runtime_error& reason) {
      // What modelid design prints against the description, exit 1.
      throw modelgen::InputError({path}, reason.what());
    }
  });
  return 0;
}
