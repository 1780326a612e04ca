// Real robot descriptions as vendors and projects publish them (tests/model/corpus/SOURCES.md,
// the shipped robots/ and, when ../shared is there, the two robots-ref files whose licence is
// unclear): each loads with the number of degrees of freedom read by hand from the file, gives as
// many base parameters as the rank of its regressor computed two independent ways (the SVD of the
// stacked Newton-Euler regressor, and for URDFs the rank of the energy functions, Gautier's
// energy model: a parameter combination has no effect on the torques iff its kinetic plus
// potential energy is constant), and as many as counted by hand where the structure allows;
// `modelgen` generates its code and `modelid check-trajectory` runs on it. Issue 29.

#include <algorithm>
#include <array>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

struct CorpusFile {
  std::string label;    // test name
  std::string path;     // absolute
  bool shared = false;  // from ../shared/robots-ref (skipped when absent)
  std::string tip;      // --tip, when the file is cut
  bool mimic_as_joint = false;
  int dof = 0;       // moving joints, counted by hand in the file
  int base = -1;     // base parameters counted by hand; -1: not counted by hand
  int warnings = 0;  // warnings the file deserves, read by hand
};

// gtest prints a parameter by its label, not its bytes.
void PrintTo(const CorpusFile& file, std::ostream* out) { *out << file.label; }

std::string corpus(const std::string& file) {
  return test::source_path("tests/model/corpus/" + file);
}

std::vector<CorpusFile> corpus_files() {
  const std::string shared = test::shared_path("robots-ref/");
  return {
      // Panda as published: 7 revolute arm joints, two prismatic fingers, the second a <mimic>
      // follower (refused by default: MimicFollowersAreRefusedByDefault). Cut at the hand: 7.
      {"franka_panda_to_hand", corpus("franka_panda.urdf"), false, "panda_hand", false, 7},
      {"franka_panda_mimic_as_joint", corpus("franka_panda.urdf"), false, "", true, 9, -1, 1},
      {"kuka_kr150r3100_2", corpus("kuka_kr150r3100_2.urdf"), false, "", false, 6},
      {"kuka_lbr_iiwa_14_r820", corpus("kuka_lbr_iiwa_14_r820_kinematic.urdf"), false, "", false,
       7},
      // One fixed box joint with two <origin> (line 55): a warning, the first one used.
      {"kuka_lwr4_cad", corpus("kuka_lwr4_cad.urdf"), false, "", false, 7, -1, 1},
      {"kuka_lwr4_identified", corpus("kuka_lwr4_identified_flobaroid.urdf"), false, "", false, 7},
      {"staubli_tx2_90", corpus("staubli_tx2_90.urdf"), false, "", false, 6},
      {"staubli_tx90", corpus("staubli_tx90.urdf"), false, "", false, 6},
      // Vendor-style files written for this corpus.
      {"gen3_6dof", corpus("gen3_6dof_vendor_style.urdf"), false, "", false, 6},
      {"abb_irb120", corpus("abb_irb120_vendor_style.urdf"), false, "", false, 6},
      // The table joint is vertical, so only the moment of the table and hand about its axis
      // acts, and the drive inertia has the same column: ZZ1R; with Fv1, Fc1, OFF1: 4.
      {"gripper_to_hand", corpus("gripper_mimic_vendor_style.urdf"), false, "hand", false, 1, 4},
      // With the fingers as joints: 4 for the table as above; a finger sliding along the
      // horizontal u on the turning table has the energy m/2 (dq^2 + 2 dq w (u x z).(p + c)
      // + w^2 |p + q u + c|_horizontal^2) + const: its mass, its first moment along u and the
      // horizontal one across u (its inertia tensor and vertical moment join the table's or do
      // nothing), with its drive inertia, Fv, Fc and OFF: 7 per finger. 4 + 2 * 7 = 18.
      {"gripper_mimic_as_joint", corpus("gripper_mimic_vendor_style.urdf"), false, "", true, 3, 18,
       1},
      // Two parallel horizontal axes, gravity in the plane of motion (Khalil's planar arm): the
      // moment about the axis and the two in-plane first moments of each link, 6; the first
      // drive inertia joins the first moment about the axis, the second stays; Fv, Fc, OFF of
      // each joint: 6 + 1 + 6 = 13.
      {"planar_2r", corpus("planar_2r_vendor_style.urdf"), false, "", false, 2, 13},
      // The shipped URDFs (robots/urdf/SOURCES.md): ur5, iiwa14 and kr150_2 are the robots-ref
      // files byte for byte; the Panda without its <mimic>.
      {"shipped_ur5", test::source_path("robots/urdf/ur5.urdf"), false, "", false, 6},
      {"shipped_iiwa14", test::source_path("robots/urdf/kuka_iiwa14_drake.urdf"), false, "", false,
       7},
      {"shipped_kr150_2", test::source_path("robots/urdf/kuka_kr150_2.urdf"), false, "", false, 6},
      {"shipped_panda", test::source_path("robots/urdf/franka_panda.urdf"), false, "", false, 9},
      // Not copied (no licence found, ../shared/robots-ref/SOURCES.md). The COMAU's four
      // velocity limits of 1000 rad/s are placeholders, rightly flagged.
      {"comau_smart_six_urdf", shared + "comau_smart_six.urdf", true, "", false, 6, -1, 4},
      {"staubli_tx40_mdh_modified", shared + "staubli_tx40_mdh_modified.urdf", true, "", false, 6},
  };
}

std::string cli_flags(const CorpusFile& file) {
  std::string flags;
  if (!file.tip.empty()) flags += " --tip " + file.tip;
  if (file.mimic_as_joint) flags += " --mimic-as-joint";
  return flags;
}

// Rank of the columns of `W` scaled to unit norm (their units differ). Columns below 1e-9 of
// the largest are rounding residue of a parameter without effect (2e-17 for the KR150's MY2),
// which scaling would blow up to a column of its own: they are set to zero.
int column_rank(Eigen::MatrixXd W) {
  const double largest = W.colwise().norm().maxCoeff();
  for (Eigen::Index k = 0; k < W.cols(); ++k) {
    const double norm = W.col(k).norm();
    W.col(k) =
        norm > 1e-9 * largest ? Eigen::VectorXd(W.col(k) / norm) : Eigen::VectorXd::Zero(W.rows());
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
  const Eigen::VectorXd& s = svd.singularValues();
  return static_cast<int>((s.array() > 1e-8 * s(0)).count());
}

// The SVD rank of the standard regressor stacked over random states.
int regressor_rank(const ReferenceDynamics& dynamics, test::Random& random) {
  const int n = dynamics.dof(), p = dynamics.num_params();
  const int states = 2 * p / n + 10;
  Eigen::MatrixXd W(states * n, p);
  for (int s = 0; s < states; ++s) {
    W.middleRows(s * n, n) = dynamics.standard_regressor(
        random.vector(n, -3, 3), random.vector(n, -2, 2), random.vector(n, -2, 2));
  }
  return column_rank(W);
}

// The rank of the energy functions H_k(q, dq) = T + V for unit parameter vectors, with the
// constant function (an energy is known up to a constant), minus that constant, plus the
// friction and offset parameters (dissipative: no energy, each independent on its own joint).
int energy_rank(const ReferenceDynamics& dynamics, test::Random& random) {
  const int n = dynamics.dof(), p = dynamics.num_params();
  const int samples = 3 * p + 20;
  Eigen::MatrixXd H(samples, p + 1);
  for (int s = 0; s < samples; ++s) {
    const Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2);
    for (int k = 0; k < p; ++k) {
      const Eigen::VectorXd unit = Eigen::VectorXd::Unit(p, k);
      H(s, k) = dynamics.kinetic_energy(q, dq, unit) + dynamics.potential_energy(q, unit);
    }
    H(s, p) = 1;
  }
  int dissipative = 0;
  for (const StandardParam& param : dynamics.tree().params) {
    if (param.kind == ParamKind::kFv || param.kind == ParamKind::kFc ||
        param.kind == ParamKind::kOff) {
      ++dissipative;
    }
  }
  return column_rank(H) - 1 + dissipative;
}

// A Fourier trajectory around the middle of every joint's range, small enough for any limit.
std::string small_trajectory(const RobotModel& model) {
  std::vector<std::string> rows(static_cast<std::size_t>(model.dof()));
  for (std::size_t b = 0; b < model.tree.bodies.size(); ++b) {
    const int j = model.tree.bodies[b].dof_index;
    if (j < 0) continue;
    const JointLimits& limits = model.joints[b].limits;
    double middle = 0, amplitude = 0.1;
    if (limits.q_lower && limits.q_upper) {
      middle = (*limits.q_lower + *limits.q_upper) / 2;
      amplitude = std::min(amplitude, (*limits.q_upper - *limits.q_lower) / 4);
    }
    rows[static_cast<std::size_t>(j)] = "  - {q0: " + std::to_string(middle) +
                                        ", terms: [{l: 1, a: " + std::to_string(amplitude) +
                                        ", b: 0}]}\n";
  }
  std::string text = "period: 10\nform: position\njoints:\n";
  for (const std::string& row : rows) text += row;
  return text;
}

int header_constant(const std::string& header, const std::string& name) {
  std::smatch match;
  const std::regex pattern("constexpr int " + name + " = ([0-9]+);");
  if (!std::regex_search(header, match, pattern)) return -1;
  return std::stoi(match[1]);
}

class UrdfCorpus : public testing::TestWithParam<CorpusFile> {};

TEST_P(UrdfCorpus, LoadsDerivesGeneratesAndChecks) {
  const CorpusFile& file = GetParam();
  if (file.shared && !std::ifstream(file.path)) {
    GTEST_SKIP() << "no " << file.path << " (../shared is not there)";
  }
  LoadOptions options;
  options.tip_link = file.tip;
  options.mimic_as_joint = file.mimic_as_joint;
  const RobotModel model = load_robot(file.path, options);
  EXPECT_EQ(model.dof(), file.dof);
  const int warnings = static_cast<int>(std::count_if(
      model.notes.begin(), model.notes.end(), [](const DescriptionNote& n) { return n.warning; }));
  EXPECT_EQ(warnings, file.warnings);

  const int base = static_cast<int>(derive_base_parameters(model.tree).params.size());
  const ReferenceDynamics dynamics(model.tree);
  test::Random random(29);
  EXPECT_EQ(base, regressor_rank(dynamics, random));
  if (model.format == DescriptionFormat::kUrdf) {
    EXPECT_EQ(base, energy_rank(dynamics, random));
  }
  if (file.base >= 0) {
    EXPECT_EQ(base, file.base);
  }

  const fs::path dir = test::test_folder("corpus");
  const test::CliRun generate = test::modelgen(test::quoted(file.path) + " -o " +
                                               test::quoted(dir / "gen") + cli_flags(file));
  ASSERT_EQ(generate.exit_code, 0) << generate.err;
  const std::string stem = fs::path(file.path).stem().string();
  const std::string header = test::read_text(dir / "gen" / (stem + ".hpp"));
  EXPECT_EQ(header_constant(header, "kDof"), file.dof);
  EXPECT_EQ(header_constant(header, "kBaseParams"), base);

  test::write_text(dir / "trajectory.yaml", small_trajectory(model));
  const test::CliRun check =
      test::modelid("check-trajectory --robot " + test::quoted(file.path) + cli_flags(file) +
                    " --trajectory " + test::quoted(dir / "trajectory.yaml"));
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
}

INSTANTIATE_TEST_SUITE_P(All, UrdfCorpus, testing::ValuesIn(corpus_files()),
                         [](const testing::TestParamInfo<CorpusFile>& info) {
                           return info.param.label;
                         });

// The shipped MDH descriptions: degrees of freedom by hand, base parameters as the regressor's
// rank (their drive models couple joints, so the energy count does not apply as above).
TEST(MdhCorpus, ShippedDescriptionsLoadAndDerive) {
  const std::vector<std::pair<std::string, int>> files = {{"robots/tx40.yaml", 6},
                                                          {"robots/kr150.yaml", 6},
                                                          {"robots/panda_arm.yaml", 7},
                                                          {"robots/comau_smart_six.yaml", 6}};
  for (const auto& [path, dof] : files) {
    const RobotModel model = load_robot(test::source_path(path));
    EXPECT_EQ(model.dof(), dof) << path;
    test::Random random(29);
    EXPECT_EQ(static_cast<int>(derive_base_parameters(model.tree).params.size()),
              regressor_rank(ReferenceDynamics(model.tree), random))
        << path;
  }
}

// A <mimic> follower in the modelled part is refused, naming it and its leader, in the library
// and in both programs.
TEST(UrdfCorpusMimic, MimicFollowersAreRefusedByDefault) {
  const std::vector<std::array<std::string, 4>> files = {
      {corpus("franka_panda.urdf"), "348", "panda_finger_joint2", "panda_finger_joint1"},
      {corpus("gripper_mimic_vendor_style.urdf"), "65", "right_finger_joint", "finger_joint"}};
  for (const auto& [path, line, follower, leader] : files) {
    const std::string expected = path + ":" + line + ": error: joint '" + follower +
                                 "' mimics joint '" + leader + "' (moves with it)";
    try {
      load_robot(path);
      ADD_FAILURE() << path << " loaded";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what();
    }
    const fs::path dir = test::test_folder("corpus");
    const test::CliRun generate =
        test::modelgen(test::quoted(path) + " -o " + test::quoted(dir / "gen"));
    EXPECT_EQ(generate.exit_code, 1);
    EXPECT_NE(generate.err.find(expected), std::string::npos) << generate.err;
    EXPECT_FALSE(fs::exists(dir / "gen"));
    const test::CliRun check = test::modelid("check " + test::quoted(path));
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_NE(check.err.find(expected), std::string::npos) << check.err;
  }
}

}  // namespace
}  // namespace modelgen
