// modelid export as a user runs it: the identified description it writes loads (urdfdom, then
// modelgen's loader) and gives back the estimate's base parameters to 1e-9, computed here
// through the regrouping of the written file's own model; what the loader merged (fixed links)
// is undone as the help says; the rest of the file is kept; bad estimates are refused.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::modelid;
using test::quoted;

ReferenceModel reference_of(const RobotModel& robot, const std::string& path) {
  return ReferenceModel(robot.name, robot.tree, sha256_hex(read_source_file(path)), robot.drives);
}

// The base parameters of an estimate file ("parameters", in the model's order).
Eigen::VectorXd estimate_base(const nlohmann::json& est, const IdentificationModel& model) {
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(model.num_base_params());
  const auto& names = model.base_param_names();
  for (const nlohmann::json& p : est["parameters"]) {
    const auto it = std::find(names.begin(), names.end(), p["name"].get<std::string>());
    EXPECT_NE(it, names.end()) << p["name"];
    if (it != names.end()) beta[it - names.begin()] = p["value"].get<double>();
  }
  return beta;
}

// The round trip of the issue: the written description, loaded by modelgen, has a-priori values
// whose base parameters (through that model's regrouping) are the estimate's. Parameters the
// description has no place for (drive parameters in a URDF) come from the estimate's standard
// set. Returns the largest relative difference.
double round_trip_error(const fs::path& written, const nlohmann::json& est) {
  const RobotModel robot = load_robot(written.string());
  const ReferenceModel model = reference_of(robot, written.string());
  Eigen::VectorXd standard = Eigen::VectorXd::Zero(model.num_standard_params());
  for (int k = 0; k < model.num_standard_params(); ++k) {
    const std::string& name = model.standard_param_names()[static_cast<std::size_t>(k)];
    const bool inertial = robot.tree.params[static_cast<std::size_t>(k)].kind <= ParamKind::kM;
    if (robot.format == DescriptionFormat::kUrdf && !inertial) {
      standard[k] = est["standard"][name].get<double>();
    } else if (robot.known_values[static_cast<std::size_t>(k)]) {
      standard[k] = *robot.known_values[static_cast<std::size_t>(k)];
    } else {
      ADD_FAILURE() << name << " has no value in " << written;
    }
  }
  Eigen::VectorXd beta(model.num_base_params());
  model.base_from_standard(standard.data(), beta.data());
  const Eigen::VectorXd expected = estimate_base(est, model);
  double worst = 0;
  for (Eigen::Index b = 0; b < beta.size(); ++b) {
    worst = std::max(worst, std::abs(beta[b] - expected[b]) / (1 + std::abs(expected[b])));
  }
  return worst;
}

// A physically consistent standard set for any description, made here: per body a mass, a
// centre of mass and an inertia about it (positive definite, triangle inequalities), moved to
// the body frame's origin by the parallel-axis theorem; positive drive parameters.
Eigen::VectorXd consistent_standard(const RobotModel& robot) {
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.tree.params.size()));
  for (std::size_t k = 0; k < robot.tree.params.size(); ++k) p[k] = 0.1 + 0.01 * k;
  for (std::size_t b = 0; b < robot.tree.bodies.size(); ++b) {
    const std::string j = std::to_string(b + 1);
    if (robot.param_index("M" + j) < 0) continue;
    const double m = 1 + 0.3 * b;
    const Eigen::Vector3d c(0.02 * (b + 1), -0.01, 0.05);
    Eigen::Matrix3d Ic;
    Ic << 0.05, 0.001, 0, 0.001, 0.045, 0.002, 0, 0.002, 0.04;
    Ic *= 1 + 0.2 * b;
    const Eigen::Matrix3d J =
        Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const std::pair<const char*, double> values[] = {
        {"XX", J(0, 0)}, {"XY", J(0, 1)},   {"XZ", J(0, 2)},   {"YY", J(1, 1)},   {"YZ", J(1, 2)},
        {"ZZ", J(2, 2)}, {"MX", m * c.x()}, {"MY", m * c.y()}, {"MZ", m * c.z()}, {"M", m}};
    for (const auto& [stem, value] : values) p[robot.param_index(stem + j)] = value;
  }
  return p;
}

// An estimate file as fit --physical writes it, for `standard` of the description at `path`.
nlohmann::json estimate_of(const std::string& path, const Eigen::VectorXd& standard) {
  const RobotModel robot = load_robot(path);
  const ReferenceModel model = reference_of(robot, path);
  Eigen::VectorXd beta(model.num_base_params());
  model.base_from_standard(standard.data(), beta.data());
  nlohmann::json est;
  est["model"] = model.name();
  est["description_sha256"] = model.description_sha256();
  est["method"] = "IDIM-WLS (physically consistent)";
  est["parameters"] = nlohmann::json::array();
  for (int b = 0; b < model.num_base_params(); ++b) {
    est["parameters"].push_back({{"name", model.base_param_names()[b]}, {"value", beta[b]}});
  }
  for (int k = 0; k < model.num_standard_params(); ++k) {
    est["standard"][model.standard_param_names()[k]] = standard[k];
  }
  est["physical"] = {{"prior_weight", 0.001}};
  return est;
}

const tinyxml2::XMLElement* link_element(const tinyxml2::XMLDocument& doc,
                                         const std::string& name) {
  for (const tinyxml2::XMLElement* link = doc.RootElement()->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    if (link->Attribute("name", name.c_str())) return link;
  }
  return nullptr;
}

double mass_of(const tinyxml2::XMLDocument& doc, const std::string& link) {
  const tinyxml2::XMLElement* element = link_element(doc, link);
  if (!element || !element->FirstChildElement("inertial")) return -1;
  return element->FirstChildElement("inertial")
      ->FirstChildElement("mass")
      ->DoubleAttribute("value");
}

// The UR5 of robots/urdf as a user identifies it: simulate from perturbed URDF values, fit
// with --physical, export. urdfdom and modelgen load the result; its base parameters are the
// estimate's.
void expect_decided_lines(const std::string& text, const nlohmann::json& est);

TEST(ModelidExport, SimulatedUr5RoundTripsThroughTheUrdf) {
  const fs::path dir = test::test_folder("export");
  const std::string urdf = test::source_path("robots/urdf/ur5.urdf");
  const RobotModel robot = load_robot(urdf);
  nlohmann::json truth;
  for (std::size_t k = 0; k < robot.tree.params.size(); ++k) {
    const std::string& name = robot.tree.params[k].name;
    // The URDF's values, the masses 10 % heavier; friction the URDF does not have.
    const double value = robot.known_values[k].value_or(0.5) * 1.1;
    truth["standard"][name] = value;
  }
  test::write_text(dir / "truth.json", truth.dump());
  const CliRun simulated = modelid(
      "simulate --robot " + quoted(fs::path(urdf)) + " --params " + quoted(dir / "truth.json") +
      " --trajectory " + test::quoted_source("robots/data/kr150/excitation.yaml") +
      " --noise 0.05 --seed 14 --sample-time 0.02 --periods 1 -o " + quoted(dir / "run.csv"));
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const CliRun fit =
      modelid("fit --robot " + quoted(fs::path(urdf)) + " --data " + quoted(dir / "run.csv") +
              " --method ols --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  // One period of a trajectory made for another robot leaves the wrists' first moments to the
  // noise (fit's link table and warning say so); the round trip is what is checked here.
  const CliRun exported =
      modelid("export --robot " + quoted(fs::path(urdf)) + " --params " + quoted(dir / "est.json") +
              " -o " + quoted(dir / "id.urdf") + " --force");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;

  const std::string text = test::read_text(dir / "id.urdf");
  ASSERT_NE(urdf::parseURDF(text), nullptr) << text;
  const nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  EXPECT_LT(round_trip_error(dir / "id.urdf", est), 1e-9);

  // The rest of the URDF is kept: the same joints, the same visual meshes; the drive
  // parameters, which URDF has no element for, are in a comment.
  tinyxml2::XMLDocument original, written;
  ASSERT_EQ(original.LoadFile(urdf.c_str()), tinyxml2::XML_SUCCESS);
  ASSERT_EQ(written.Parse(text.c_str()), tinyxml2::XML_SUCCESS);
  for (const char* tag : {"joint", "link", "transmission", "visual", "collision", "mesh"}) {
    int before = 0, after = 0;
    const auto count = [&](const tinyxml2::XMLDocument& doc, int& n) {
      std::vector<const tinyxml2::XMLElement*> stack{doc.RootElement()};
      while (!stack.empty()) {
        const tinyxml2::XMLElement* e = stack.back();
        stack.pop_back();
        if (std::string(e->Name()) == tag) ++n;
        for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
      }
    };
    count(original, before);
    count(written, after);
    EXPECT_EQ(before, after) << tag;
  }
  EXPECT_NE(text.find("Fv1"), std::string::npos);
  EXPECT_NE(text.find("<!--"), std::string::npos);
  expect_decided_lines(text, est);
}

// Issue 30: the written file says, a line per link, what the data decided, as EST.json's
// "links" do, and names the drive parameters its "drives" say the data did not decide.
void expect_decided_lines(const std::string& text, const nlohmann::json& est) {
  ASSERT_TRUE(est.contains("links"));
  for (const nlohmann::json& link : est["links"]) {
    const std::string start = "link '" + link["body"].get<std::string>() + "': ";
    const std::size_t at = text.find(start);
    ASSERT_NE(at, std::string::npos) << start << "\n" << text;
    const std::string line = text.substr(at, text.find('\n', at) - at);
    const std::size_t prior_part = std::min(line.find("; the prior"), line.size());
    const std::string data_part = line.substr(0, prior_part);
    for (const auto& [key, words] :
         {std::pair<std::string, std::string>{"mass", "mass"}, {"com", "centre of mass"}}) {
      EXPECT_EQ(data_part.find(words) != std::string::npos, link["decided_by"][key] == "data")
          << line;
    }
  }
  for (const nlohmann::json& drive : est["drives"]) {
    if (drive["decided_by"] != "prior") continue;
    const std::size_t at = text.find("the data did not decide (regrouped):");
    ASSERT_NE(at, std::string::npos) << text;
    EXPECT_NE(text.find(drive["name"].get<std::string>(), at), std::string::npos) << drive;
  }
}

TEST(ModelidExport, TheYamlSaysWhatTheDataDecided) {
  // The bundled KR 150 run: Ia1 enters only with ZZ1 (fit's drive table says "prior").
  const fs::path dir = test::test_folder("export_decided");
  const std::string yaml = test::source_path("robots/kr150.yaml");
  const CliRun fit = modelid("fit --robot " + quoted(fs::path(yaml)) + " --data " +
                             test::quoted_source("robots/data/kr150/excitation.csv") +
                             " --method wls --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const CliRun exported =
      modelid("export --robot " + quoted(fs::path(yaml)) + " --params " + quoted(dir / "est.json") +
              " -o " + quoted(dir / "id.yaml") + " --force");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const std::string text = test::read_text(dir / "id.yaml");
  const nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  expect_decided_lines(text, est);
  EXPECT_NE(text.find("# drive parameters the data did not decide (regrouped): Ia1"),
            std::string::npos)
      << text;
}

// A two-axis arm with a 0.8 kg tool on a fixed joint, turned and offset: modelgen merges the
// tool into link l2's body.
constexpr const char* kToolArm = R"(<?xml version="1.0"?>
<robot name="tool_arm">
  <link name="base"/>
  <joint name="j1" type="revolute">
    <parent link="base"/>
    <child link="l1"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <link name="l1">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/>
    </inertial>
  </link>
  <joint name="j2" type="revolute">
    <parent link="l1"/>
    <child link="l2"/>
    <origin xyz="0.4 0 0" rpy="1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <link name="l2">
    <inertial>
      <origin xyz="0.15 0.01 0" rpy="0 0 0.3"/>
      <mass value="1.5"/>
      <inertia ixx="0.004" ixy="0.0002" ixz="0" iyy="0.01" iyz="0" izz="0.011"/>
    </inertial>
  </link>
  <joint name="tool_joint" type="fixed">
    <parent link="l2"/>
    <child link="tool"/>
    <origin xyz="0.3 0 0" rpy="0 1.5707963267948966 0"/>
  </joint>
  <!-- a gripper -->
  <link name="tool">
    <inertial>
      <origin xyz="0 0 0.05" rpy="0.2 0 0"/>
      <mass value="0.8"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.001"/>
    </inertial>
  </link>
</robot>
)";

// The description's own values with link 2's body (l2 and the tool) scaled by `scale`: still
// a physical body, of mass scale * 2.3 kg.
nlohmann::json tool_arm_estimate(const fs::path& urdf, double scale) {
  const RobotModel robot = load_robot(urdf.string());
  Eigen::VectorXd standard = consistent_standard(robot);
  for (std::size_t k = 0; k < robot.tree.params.size(); ++k) {
    if (robot.known_values[k]) standard[k] = *robot.known_values[k];
    if (robot.tree.params[k].body == 1 && robot.known_values[k]) standard[k] *= scale;
  }
  return estimate_of(urdf.string(), standard);
}

TEST(ModelidExport, FixedLinksKeepTheirInertialsAndTheMovingLinkTakesTheRest) {
  const fs::path dir = test::test_folder("export");
  test::write_text(dir / "arm.urdf", kToolArm);
  const nlohmann::json est = tool_arm_estimate(dir / "arm.urdf", 1.25);
  test::write_text(dir / "est.json", est.dump(2));
  const CliRun run = modelid("export --robot " + quoted(dir / "arm.urdf") + " --params " +
                             quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "modelid export: the identified inertials of tool_arm written to " +
                         (dir / "id.urdf").string() + "\n");

  const std::string text = test::read_text(dir / "id.urdf");
  ASSERT_NE(urdf::parseURDF(text), nullptr) << text;
  EXPECT_LT(round_trip_error(dir / "id.urdf", est), 1e-9);
  tinyxml2::XMLDocument written;
  ASSERT_EQ(written.Parse(text.c_str()), tinyxml2::XML_SUCCESS);
  // The tool as it was; l2 the body's 1.25 * 2.3 kg less the tool's 0.8.
  EXPECT_EQ(mass_of(written, "tool"), 0.8);
  EXPECT_NEAR(mass_of(written, "l2"), 1.25 * 2.3 - 0.8, 1e-12);
  EXPECT_NEAR(mass_of(written, "l1"), 2, 1e-12);
  const tinyxml2::XMLElement* origin =
      link_element(written, "l2")->FirstChildElement("inertial")->FirstChildElement("origin");
  EXPECT_STREQ(origin->Attribute("rpy"), "0 0 0.3");  // the link's inertial frame is kept
  EXPECT_NE(text.find("a gripper"), std::string::npos);

  // Identified again: one comment of export's, the new one.
  const nlohmann::json est2 = tool_arm_estimate(dir / "id.urdf", 1.1);
  test::write_text(dir / "est2.json", est2.dump(2));
  const CliRun rerun = modelid("export --robot " + quoted(dir / "id.urdf") + " --params " +
                               quoted(dir / "est2.json") + " -o " + quoted(dir / "id2.urdf"));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_LT(round_trip_error(dir / "id2.urdf", est2), 1e-9);
  const std::string text2 = test::read_text(dir / "id2.urdf");
  EXPECT_EQ(text2.find("modelid export:"), text2.rfind("modelid export:"));
  EXPECT_NE(text2.find("est2.json"), std::string::npos);
}

TEST(ModelidExport, AToolHeavierThanItsIdentifiedBodyMovesOntoTheMovingLink) {
  const fs::path dir = test::test_folder("export");
  test::write_text(dir / "arm.urdf", kToolArm);
  // 0.3 * 2.3 kg = 0.69 kg for the body: less than the tool's a-priori 0.8 kg (and under half
  // the a-priori body, which export writes only with --force).
  const nlohmann::json est = tool_arm_estimate(dir / "arm.urdf", 0.3);
  test::write_text(dir / "est.json", est.dump(2));
  const CliRun run =
      modelid("export --robot " + quoted(dir / "arm.urdf") + " --params " +
              quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf") + " --force");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string warning =
      (dir / "arm.urdf").string() + ":25: warning: link 'l2': the identified body (";
  EXPECT_EQ(run.err.substr(0, warning.size()), warning);
  EXPECT_NE(run.err.find(" kg) is no physical body; 'l2' takes the whole body, and the "
                         "<inertial> of 'tool' is removed\n"),
            std::string::npos)
      << run.err;

  const std::string text = test::read_text(dir / "id.urdf");
  ASSERT_NE(urdf::parseURDF(text), nullptr) << text;
  EXPECT_LT(round_trip_error(dir / "id.urdf", est), 1e-9);
  tinyxml2::XMLDocument written;
  ASSERT_EQ(written.Parse(text.c_str()), tinyxml2::XML_SUCCESS);
  EXPECT_EQ(mass_of(written, "tool"), -1);  // no <inertial> left
  EXPECT_NEAR(mass_of(written, "l2"), 0.3 * 2.3, 1e-12);
}

// MDH YAML: the identified values become the `known:` section, replacing the one there (TX-40)
// or added at the end (KR150); the text before it is kept byte for byte.
void yaml_round_trip(const std::string& shipped, const std::string& kept_prefix_end) {
  const fs::path dir = test::test_folder("export");
  const std::string path = test::source_path(shipped);
  // Made-up bodies, far from the shipped a-priori ones: written with --force.
  const nlohmann::json est = estimate_of(path, consistent_standard(load_robot(path)));
  test::write_text(dir / "est.json", est.dump(2));
  const CliRun run =
      modelid("export --robot " + quoted(fs::path(path)) + " --params " + quoted(dir / "est.json") +
              " -o " + quoted(dir / "id.yaml") + " --force");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_LT(round_trip_error(dir / "id.yaml", est), 1e-9);
  const std::string original = test::read_text(path);
  const std::string text = test::read_text(dir / "id.yaml");
  const std::size_t end =
      kept_prefix_end.empty() ? original.size() : original.find(kept_prefix_end);
  ASSERT_NE(end, std::string::npos);
  EXPECT_EQ(text.substr(0, end), original.substr(0, end));
  EXPECT_EQ(text.find("Ia1: 0.362"), std::string::npos);  // the old value is gone

  // Identified again: the section and its comment replaced, not repeated.
  const std::string again = (dir / "id.yaml").string();
  const nlohmann::json est2 = estimate_of(again, 1.5 * consistent_standard(load_robot(again)));
  test::write_text(dir / "est2.json", est2.dump(2));
  const CliRun rerun = modelid("export --robot " + quoted(dir / "id.yaml") + " --params " +
                               quoted(dir / "est2.json") + " -o " + quoted(dir / "id2.yaml"));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_LT(round_trip_error(dir / "id2.yaml", est2), 1e-9);
  const std::string text2 = test::read_text(dir / "id2.yaml");
  EXPECT_EQ(text2.substr(0, end), original.substr(0, end));
  const std::string note = "# Identified by modelid export";
  EXPECT_EQ(text2.find(note), text2.rfind(note));
  EXPECT_EQ(text2.find("\nknown:"), text2.rfind("\nknown:"));
}

TEST(ModelidExport, ALinkFarFromItsAPrioriValuesIsRefusedUnlessForced) {
  const fs::path dir = test::test_folder("export_far");
  test::write_text(dir / "arm.urdf", kToolArm);
  // Link 2's body (l2 and the tool, 2.3 kg a-priori) at 0.4 times its a-priori mass, its centre
  // of mass unchanged: off by more than a factor 2.
  test::write_text(dir / "est.json", tool_arm_estimate(dir / "arm.urdf", 0.4).dump(2));
  const std::string command = "export --robot " + quoted(dir / "arm.urdf") + " --params " +
                              quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf");
  const CliRun refused = modelid(command);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("link 'l2': mass 0.4 x its a-priori value"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find("link 'l1'"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "id.urdf"));
  const CliRun forced = modelid(command + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(fs::exists(dir / "id.urdf"));
}

// One link: a 0.1 x 0.1 x 0.4 box from the joint up, its a-priori mass 1 kg at its centre.
constexpr const char* kBoxArm = R"(<?xml version="1.0"?>
<robot name="box_arm">
  <link name="base"/>
  <link name="a">
    <inertial><origin xyz="0 0 0.2"/><mass value="1"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.1 0.1 0.4"/></geometry></collision>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
</robot>
)";

TEST(ModelidExport, ALinkOutsideItsGeometryIsRefusedUnlessForced) {
  // The link's mass 9 cm off the box's axis (not far from its a-priori centre, 10 cm): beyond
  // the ellipsoid around the box, whose semi-axis there is sqrt(3) x 5 cm = 8.7 cm.
  const fs::path dir = test::test_folder("export_region");
  test::write_text(dir / "arm.urdf", kBoxArm);
  const RobotModel robot = load_robot((dir / "arm.urdf").string());
  Eigen::VectorXd standard = consistent_standard(robot);
  const double values[] = {
      1e-4, 0, -0.09 * 0.2, 1e-4 + 0.09 * 0.09 + 0.04, 0, 1e-4 + 0.09 * 0.09, 0.09, 0, 0.2, 1};
  const char* stems[] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
  for (int s = 0; s < 10; ++s) standard[robot.param_index(std::string(stems[s]) + "1")] = values[s];
  standard[robot.param_index("XX1")] += 0.04;  // the parallel-axis terms about the origin
  test::write_text(dir / "est.json", estimate_of((dir / "arm.urdf").string(), standard).dump(2));
  const std::string command = "export --robot " + quoted(dir / "arm.urdf") + " --params " +
                              quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf");
  const CliRun refused = modelid(command);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("link 'a': its mass reaches outside the region its geometry gives"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(refused.err.find("x its a-priori value"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find("from its a-priori position"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "id.urdf"));
  const CliRun forced = modelid(command + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
}

TEST(ModelidExport, Tx40KnownSectionIsReplaced) { yaml_round_trip("robots/tx40.yaml", "known:"); }

TEST(ModelidExport, Kr150GetsAKnownSection) { yaml_round_trip("robots/kr150.yaml", ""); }

TEST(ModelidExport, AFitWithoutPhysicalIsRefused) {
  const fs::path dir = test::test_folder("export");
  const std::string path = test::source_path("robots/tx40.yaml");
  nlohmann::json est = estimate_of(path, consistent_standard(load_robot(path)));
  est.erase("standard");
  est.erase("physical");
  test::write_text(dir / "est.json", est.dump(2));
  const CliRun run = modelid("export --robot " + quoted(fs::path(path)) + " --params " +
                             quoted(dir / "est.json") + " -o " + quoted(dir / "id.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("refit with 'modelid fit --physical"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "id.yaml"));
}

TEST(ModelidExport, AnEstimateOfAnotherRobotIsRefused) {
  const fs::path dir = test::test_folder("export");
  const std::string kr150 = test::source_path("robots/kr150.yaml");
  test::write_text(dir / "est.json",
                   estimate_of(kr150, consistent_standard(load_robot(kr150))).dump(2));
  const CliRun run =
      modelid("export --robot " + test::quoted_source("robots/tx40.yaml") + " --params " +
              quoted(dir / "est.json") + " -o " + quoted(dir / "id.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("the estimate belongs to another model"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "id.yaml"));
}

TEST(ModelidExport, AnUnwritableOutputChangesNothing) {
  const fs::path dir = test::test_folder("export");
  test::write_text(dir / "arm.urdf", kToolArm);
  test::write_text(dir / "est.json", tool_arm_estimate(dir / "arm.urdf", 1.25).dump(2));
  const fs::path out = dir / "missing" / "id.urdf";
  const CliRun run = modelid("export --robot " + quoted(dir / "arm.urdf") + " --params " +
                             quoted(dir / "est.json") + " -o " + quoted(out));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err, out.string() +
                         ": error: cannot write the file: No such file or directory (no file "
                         "was changed)\n");
  EXPECT_FALSE(fs::exists(dir / "missing"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(ModelidExport, ACompiledInModelNameIsNotADescription) {
  const fs::path dir = test::test_folder("export");
  const CliRun run = modelid("export --robot tx40 --params " + quoted(dir / "est.json") + " -o " +
                             quoted(dir / "id.yaml"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("export needs the description file"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace modelgen
