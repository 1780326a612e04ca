// modelid check-trajectory --robot R --trajectory T.yaml: the peak use of every joint limit
// of the description by a Fourier excitation, on a dense grid over one period; with effort
// limits and a-priori inertial values, the peak a-priori torques too.

#include <iostream>

#include "modelgen/excitation/limit_use.hpp"
#include "modelgen/io/experiment/fourier_file.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/q_limit_option.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/excitation/a_priori_torque.hpp"
#include "runtime/cli/excitation/trajectory_limits.hpp"
#include "runtime/cli/plots/torque_plots.hpp"
#include "runtime/cli/plots/trajectory_plot.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

int run_check_trajectory(const CommandLine& args) {
  ModelSource source = load_model_source(args.one("--robot"), args);
  apply_q_limit_option(args, source);
  const std::string& path = args.one("--trajectory");
  if (args.has("--plot")) check_plot_folder(args.one("--plot"));
  const FourierTrajectory trajectory = read_fourier(path, source.model->dof());
  note_missing_limits(std::cerr, "check-trajectory", source);
  // The acceleration limits a design was made with (design --ddq-limit), when the
  // description has none.
  std::vector<JointLimits> limits = source.limits;
  if (!limits.empty()) apply_ddq_limit_option(args, limits);
  const long points = limit_grid_points(trajectory);
  std::cout << path << ": period " << shortest(trajectory.period) << " s, "
            << trajectory.a.cols() << " harmonics, checked on " << points
            << " points of one period (" << fixed(points / trajectory.period, 0, 6)
            << " Hz); q use: distance from the middle of the range over half the range\n";
  int exceeded = print_limit_use(std::cout, source, trajectory_extremes(trajectory), limits);
  if (const auto beta = effort_check_parameters(std::cerr, "check-trajectory", source)) {
    std::cout << "a-priori joint torques (the description's inertial values; drive and friction "
                 "values it does not give taken as 0) against the effort limits:\n";
    exceeded += print_torque_use(std::cout, source, torque_peaks(*source.model, *beta, trajectory),
                                 source.limits);
  }
  if (args.has("--plot")) {
    const std::string plot = write_trajectory_plot(args.one("--plot"), trajectory, source, limits,
                                                   path + " on " + source.model->name());
    std::cerr << "modelid check-trajectory: plot written to " << plot << "\n";
  }
  if (exceeded > 0) {
    std::cerr << "modelid check-trajectory: " << exceeded << " limit"
              << (exceeded == 1 ? " is" : "s are") << " exceeded (marked '!')\n";
    return 1;
  }
  return 0;
}

}  // namespace modelgen::internal
