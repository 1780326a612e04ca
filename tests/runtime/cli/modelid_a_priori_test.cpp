// modelid simulate without --params uses the description's a-priori values (here the URDF
// inertials of the UR5): its noise-free torques are those KDL computes from the same inertials,
// independently of modelgen's dynamics. And a parameter file that no robot can have is refused
// before anything is simulated.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace modelgen::io;  // the data CSV (modelgen/io/experiment/trajectory_csv.hpp)

namespace fs = std::filesystem;
using test::CliRun;
using test::modelid;
using test::quoted;
using test::quoted_source;

constexpr const char* kUr5 = "robots/urdf/ur5.urdf";

TEST(ModelidSimulate, WithoutParamsTheDescriptionsInertialsAreSimulated) {
  const fs::path dir = test::test_folder("a_priori");
  test::write_text(dir / "trajectory.yaml",
                   "period: 4\nform: position\njoints:\n"
                   "  - {q0: 0.1, terms: [{l: 1, a: 0.4, b: 0.1}]}\n"
                   "  - {q0: -1.0, terms: [{l: 1, a: 0.3, b: -0.2}, {l: 2, a: 0.1, b: 0}]}\n"
                   "  - {q0: 1.2, terms: [{l: 2, a: 0.3, b: 0.1}]}\n"
                   "  - {q0: -0.5, terms: [{l: 1, a: 0.5, b: 0}]}\n"
                   "  - {q0: 0.3, terms: [{l: 3, a: 0.2, b: 0.2}]}\n"
                   "  - {q0: 0, terms: [{l: 1, a: 0.6, b: -0.3}]}\n");
  const CliRun run = modelid("simulate --robot " + quoted_source(kUr5) + " --trajectory " +
                             quoted(dir / "trajectory.yaml") + " --noise 0 --sample-time 0.1 -o " +
                             quoted(dir / "data.csv"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The UR5 URDF has no friction or rotor inertias: the note says they are 0.
  EXPECT_NE(run.err.find("no --params: the description's a-priori values"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("are 0: "), std::string::npos) << run.err;

  const RobotModel robot = load_robot(test::source_path(kUr5));
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.tree.params.size()));
  for (std::size_t k = 0; k < robot.known_values.size(); ++k) {
    if (robot.known_values[k]) p[static_cast<Eigen::Index>(k)] = *robot.known_values[k];
  }
  const Trajectory data = read_trajectory_csv((dir / "data.csv").string(), 6);
  ASSERT_TRUE(data.has_velocity);
  ASSERT_EQ(data.q.rows(), 40);
  double largest = 0;
  for (Eigen::Index s = 0; s < data.q.rows(); ++s) {
    const Eigen::VectorXd expected =
        test::kdl_inverse_dynamics(robot.tree, data.q.row(s).transpose(),
                                   data.dq.row(s).transpose(), data.ddq.row(s).transpose(), p);
    for (Eigen::Index j = 0; j < 6; ++j) {
      EXPECT_NEAR(data.tau(s, j), expected[j], 1e-9 * (1 + std::abs(expected[j])))
          << "sample " << s << " axis " << j + 1;
      largest = std::max(largest, std::abs(expected[j]));
    }
  }
  EXPECT_GT(largest, 1.0);  // gravity on the UR5's shoulder: the comparison has content
}

TEST(ModelidSimulate, ADescriptionWithoutAPrioriValuesNeedsParams) {
  const fs::path dir = test::test_folder("a_priori");
  const CliRun run =
      modelid("simulate --robot " + quoted_source("tests/bad_inputs/robots/two_axes.yaml") +
              " --trajectory " + quoted_source("tests/bad_inputs/robots/two_axes_trajectory.yaml") +
              " --noise 0 -o " + quoted(dir / "none.csv"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("this one has none"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "none.csv"));
}

TEST(ModelidSimulate, AnImpossibleTruthIsRefusedNamingTheLink) {
  const fs::path dir = test::test_folder("a_priori");
  nlohmann::json truth =
      nlohmann::json::parse(test::read_text(test::source_path("robots/data/kr150/true.json")));
  // Link 3 with its centre of mass 2 m from the axis but the inertia of the original:
  // XX3 < m (cy^2 + cz^2) then, the inertia about the centre of mass not positive.
  truth["standard"]["MY3"] = 300.0;
  truth["standard"]["Fv5"] = -1.0;
  const std::string text = truth.dump(2);
  test::write_text(dir / "truth.json", text);
  const std::size_t key = text.find("\"standard\"");
  const std::string line = std::to_string(1 + std::count(text.begin(), text.begin() + key, '\n'));
  const CliRun run = modelid("simulate --robot kr150 --params " + quoted(dir / "truth.json") +
                             " --trajectory " + quoted_source("robots/data/kr150/excitation.yaml") +
                             " --noise 0 -o " + quoted(dir / "impossible.csv"));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("truth.json:" + line + ":"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("cannot be those of a physical robot"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("link 'A3' XX3: inertia about the centre of mass is not positive"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("Fv5"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "impossible.csv"));
}

// The drive-model files (simulate --drive, fit --method ml --known) are held to the same
// conditions: link 3 of the bundled load demo given its centre of mass 2 m off the axis.
TEST(ModelidSimulate, AnImpossibleDriveTruthOrAPrioriValueIsRefused) {
  const fs::path dir = test::test_folder("a_priori");
  for (const char* file : {"drive_truth.json", "known.json"}) {
    nlohmann::json values = nlohmann::json::parse(
        test::read_text(test::source_path(std::string("robots/data/kr150/load/") + file)));
    values["MY3"] = 300.0;
    test::write_text(dir / file, values.dump(2));
  }
  const std::string robot = quoted_source("robots/kr150.yaml");
  const CliRun simulate = modelid(
      "simulate --robot " + robot + " --drive " + quoted(dir / "drive_truth.json") +
      " --trajectory " + quoted_source("robots/data/kr150/load/table1.yaml") +
      " --noise 1 --sample-time 0.024 --ignore-limits -o " + quoted(dir / "load.csv"));
  EXPECT_EQ(simulate.exit_code, 1) << simulate.err;
  EXPECT_NE(simulate.err.find("drive_truth.json: error: these values cannot be those of a "
                              "physical robot: link 'A3' XX3: "),
            std::string::npos)
      << simulate.err;
  EXPECT_FALSE(fs::exists(dir / "load.csv"));
  const CliRun fit = modelid("fit --method ml --approach 3 --robot " + robot + " --known " +
                             quoted(dir / "known.json") + " --data " +
                             quoted_source("robots/data/kr150/excitation.csv") + " --periodic");
  EXPECT_EQ(fit.exit_code, 1) << fit.err;
  EXPECT_NE(fit.err.find("known.json: error: these a-priori values cannot be those of a "
                         "physical robot: link 'A3' XX3: "),
            std::string::npos)
      << fit.err;
}

}  // namespace
}  // namespace modelgen
