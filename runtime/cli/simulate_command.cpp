// modelid simulate: samples a Fourier excitation (Swevers 2002, eq. 15-17), computes the joint
// torques of given base parameters by the model's inverse dynamics (Gautier & Briot eq. 4-6)
// and adds seeded Gaussian noise, then writes the trajectory CSV.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <random>

#include "modelgen/data.hpp"
#include "modelgen/excitation.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/fourier_file.hpp"
#include "runtime/cli/model_source.hpp"
#include "runtime/cli/parameter_file.hpp"
#include "runtime/cli/progress.hpp"

namespace modelgen::internal {

const std::map<std::string, OptionKind> kSimulateOptions = {
    {"--robot", OptionKind::kOnce},      {"--params", OptionKind::kOnce},
    {"--trajectory", OptionKind::kOnce}, {"--noise", OptionKind::kOnce},
    {"--seed", OptionKind::kOnce},       {"--sample-time", OptionKind::kOnce},
    {"--periods", OptionKind::kOnce},    {"-o", OptionKind::kOnce}};

int run_simulate(const Arguments& args) {
  reject_positional(args);
  const ModelSource source = load_model_source(args.one("--robot"));
  const IdentificationModel& model = *source.model;
  const Eigen::VectorXd beta = read_base_parameters(args.one("--params"), model);
  const FourierTrajectory fourier = read_fourier(args.one("--trajectory"), model.dof());
  const double noise = parse_number(args.one("--noise"), "--noise");
  const double sample_time = args.has("--sample-time")
                                 ? parse_number(args.one("--sample-time"), "--sample-time")
                                 : fourier.period / 1000.0;
  const double periods =
      args.has("--periods") ? parse_number(args.one("--periods"), "--periods") : 1.0;
  std::uint64_t seed = 1;
  if (args.has("--seed")) {
    const std::string& text = args.one("--seed");
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
    if (ec != std::errc() || end != text.data() + text.size()) {
      throw UsageError{"--seed must be a non-negative integer, not '" + text + "'"};
    }
  }
  const std::string& output = args.one("-o");
  Trajectory x = sample(fourier, sample_time, periods * fourier.period);
  // Gaussian torque noise by Box-Muller on a fixed generator: the same seed, the same file.
  std::mt19937_64 engine(seed);
  auto uniform = [&engine] { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; };
  std::vector<double> tau(model.dof());
  Progress progress("simulating", x.t.size());
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    if (s % 1024 == 0) progress.update(s);
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    for (int j = 0; j < model.dof(); ++j) {
      const double u1 = uniform(), u2 = uniform();  // named: operand order is unspecified
      const double g = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
      x.tau(s, j) = tau[j] + noise * g;
    }
  }
  progress.update(x.t.size());
  progress.finish();
  write_trajectory_csv(output, x);
  std::cerr << "modelid simulate: " << x.t.size() << " samples of " << model.name()
            << " written to " << output << "\n";
  return 0;
}

}  // namespace modelgen::internal
