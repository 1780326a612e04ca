// modelid export as a user runs it: the identified description it writes loads (urdfdom, then
// modelgen's loader) and gives back the estimate's base parameters to 1e-9, computed here
// through the regrouping of the written file's own model; what the loader merged (fixed links)
// is undone as the help says; the rest of the file is kept. Refusals: modelid_export_refusal_test.

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

#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/export_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::consistent_standard;
using test::estimate_of;
using test::kToolArm;
using test::link_element;
using test::mass_of;
using test::modelid;
using test::quoted;
using test::round_trip_error;
using test::tool_arm_estimate;

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
    // The data's part ends where the prior's or the bound's begins.
    const std::size_t others =
        std::min({line.find("; the prior"), line.find("; the bound"), line.size()});
    const std::string data_part = line.substr(0, others);
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

TEST(ModelidExport, Tx40KnownSectionIsReplaced) { yaml_round_trip("robots/tx40.yaml", "known:"); }

TEST(ModelidExport, Kr150GetsAKnownSection) { yaml_round_trip("robots/kr150.yaml", ""); }

}  // namespace
}  // namespace modelgen
