// modelid fit --physical as a user runs it, checked by computations of its own: every link of
// the standard set in EST.json has a positive definite pseudo-inertia (formed here from the
// values) and every rotor inertia and friction coefficient is >= 0; the base parameters in
// EST.json are those the standard set gives through the numeric reference's regrouping; the
// torques are predicted nearly as well as by the unconstrained fit; the unconstrained
// estimate was impossible to begin with.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <nlohmann/json.hpp>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/region_fit.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::modelid;
using test::quoted;
using test::quoted_source;

double value_of(const nlohmann::json& standard, const std::string& name) {
  return standard.contains(name) ? standard[name].get<double>() : 0.0;
}

TEST(ModelidPhysical, TheBundledKr150RunGivesAConsistentRobot) {
  const fs::path dir = test::test_folder("physical");
  const CliRun fit =
      modelid("fit --robot kr150 --data " + quoted_source("robots/data/kr150/excitation.csv") +
              " --method wls --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("physically consistent estimate"), std::string::npos) << fit.out;
  const nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  ASSERT_TRUE(est.contains("standard") && est.contains("physical") && est.contains("links"));

  // The unconstrained estimate was impossible: some friction or rotor inertia below zero, as
  // fit's own warning says.
  std::set<std::string> negative;
  for (const nlohmann::json& p : est["physical"]["unconstrained"]) {
    const std::string name = p["name"];
    if ((name.rfind("Fv", 0) == 0 || name.rfind("Fc", 0) == 0 || name.rfind("Ia", 0) == 0) &&
        name.back() != 'R' && p["value"].get<double>() < 0) {
      negative.insert(name);
    }
  }
  ASSERT_FALSE(negative.empty()) << "the data no longer give an impossible estimate to correct";

  // The standard set is physical, link by link, formed here from the numbers.
  const RobotModel robot = load_robot(test::source_path("robots/kr150.yaml"));
  const nlohmann::json& standard = est["standard"];
  for (std::size_t b = 0; b < robot.tree.bodies.size(); ++b) {
    const std::string j = std::to_string(b + 1);
    const double m = value_of(standard, "M" + j);
    if (!standard.contains("M" + j)) continue;
    Eigen::Matrix3d I;
    I << value_of(standard, "XX" + j), value_of(standard, "XY" + j), value_of(standard, "XZ" + j),
        value_of(standard, "XY" + j), value_of(standard, "YY" + j), value_of(standard, "YZ" + j),
        value_of(standard, "XZ" + j), value_of(standard, "YZ" + j), value_of(standard, "ZZ" + j);
    const Eigen::Vector3d h(value_of(standard, "MX" + j), value_of(standard, "MY" + j),
                            value_of(standard, "MZ" + j));
    Eigen::Matrix4d P;  // the second moment of the mass distribution and its first moments
    P.topLeftCorner<3, 3>() = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
    P.topRightCorner<3, 1>() = h;
    P.bottomLeftCorner<1, 3>() = h.transpose();
    P(3, 3) = m;
    EXPECT_EQ(Eigen::LLT<Eigen::Matrix4d>(P).info(), Eigen::Success) << "link " << j << "\n" << P;
  }
  for (const auto& [name, value] : standard.items()) {
    for (const char* stem : {"Ia", "Fv", "Fc", "Iam", "Fvm"}) {
      const std::string s = stem;
      if (name.rfind(s, 0) == 0 && std::isdigit(static_cast<unsigned char>(name[s.size()]))) {
        EXPECT_GE(value.get<double>(), 0.0) << name;
      }
    }
  }

  // The base parameters written are those of the standard set.
  const ReferenceModel reference(robot.name, robot.tree);
  Eigen::VectorXd p(reference.num_standard_params());
  for (int k = 0; k < p.size(); ++k) {
    p[k] = value_of(standard, reference.standard_param_names()[static_cast<std::size_t>(k)]);
  }
  Eigen::VectorXd beta(reference.num_base_params());
  reference.base_from_standard(p.data(), beta.data());
  ASSERT_EQ(est["parameters"].size(), static_cast<std::size_t>(beta.size()));
  for (int b = 0; b < beta.size(); ++b) {
    const nlohmann::json& entry = est["parameters"][static_cast<std::size_t>(b)];
    EXPECT_EQ(entry["name"], reference.base_param_names()[static_cast<std::size_t>(b)]);
    EXPECT_NEAR(entry["value"].get<double>(), beta[b], 1e-8 * (1 + std::abs(beta[b])))
        << entry["name"];
  }

  // Binding bounds (the negative drive values above) leave every base parameter a spread.
  for (const nlohmann::json& entry : est["parameters"]) {
    EXPECT_GT(entry["std"].get<double>(), 0.0) << entry["name"];
  }
  // A drive parameter reported as decided by the data is a base parameter of its own (the base
  // parameter of that name has its value); Ia1, about the vertical first axis, enters only
  // with ZZ1 and is reported as the prior's.
  ASSERT_TRUE(est.contains("drives"));
  bool saw_ia1 = false;
  for (const nlohmann::json& drive : est["drives"]) {
    const std::string name = drive["name"];
    if (name == "Ia1") {
      saw_ia1 = true;
      EXPECT_EQ(drive["decided_by"], "prior");
      const auto& with = drive["regrouped_with"];
      EXPECT_NE(std::find(with.begin(), with.end(), "ZZ1"), with.end()) << drive;
    }
    if (drive["decided_by"] != "data") continue;
    bool found = false;
    for (const nlohmann::json& entry : est["parameters"]) {
      if (entry["name"] != name) continue;
      found = true;
      EXPECT_NEAR(entry["value"].get<double>(), drive["value"].get<double>(),
                  1e-8 * (1 + std::abs(drive["value"].get<double>())))
          << name;
    }
    EXPECT_TRUE(found) << name << " is said to be decided by the data but is no base parameter";
  }
  EXPECT_TRUE(saw_ia1);
  EXPECT_NE(fit.out.find("drive parameters"), std::string::npos) << fit.out;

  // Consistency costs little here: the torques are predicted within 5 % of the unconstrained
  // fit's error. The bounds that bind are on parameters the unconstrained fit had negative (a
  // negative one the data can trade for another, such as Fv5 for Fvm5, need not bind) or on
  // drive parameters regrouped with links (the data do not split them: Ia2 with ZZ2 and the
  // masses of links 3-7); the regions guessed from the DH rows are dropped (next test).
  const double constrained = est["rel_error_norm"];
  const double unconstrained = est["physical"]["unconstrained_rel_error_norm"];
  EXPECT_LE(constrained, 1.05 * unconstrained);
  std::set<std::string> regrouped, with_region;
  for (const nlohmann::json& drive : est["drives"]) {
    if (drive["decided_by"] == "prior") regrouped.insert(drive["name"].get<std::string>());
  }
  for (const nlohmann::json& link : est["links"]) {
    if (link.contains("region_extent")) with_region.insert(link["body"].get<std::string>());
  }
  ASSERT_FALSE(est["physical"]["binding_constraints"].empty());
  for (const nlohmann::json& c : est["physical"]["binding_constraints"]) {
    const std::string text = c;
    if (text.rfind("body '", 0) == 0) {
      const std::string body = text.substr(6, text.find('\'', 6) - 6);
      EXPECT_TRUE(with_region.count(body)) << text;
      continue;
    }
    if (text.rfind("guessed regions of", 0) == 0) continue;
    const std::string name = text.substr(0, text.find(' '));
    EXPECT_TRUE(negative.count(name) || regrouped.count(name)) << text;
  }
}

TEST(ModelidPhysical, TheEstimateDrivesPredictAndSimulate) {
  const fs::path dir = test::test_folder("physical_use");
  const std::string data = quoted_source("robots/data/kr150/excitation.csv");
  ASSERT_EQ(modelid("fit --robot kr150 --data " + data + " --method wls --physical -o " +
                    quoted(dir / "est.json"))
                .exit_code,
            0);
  const CliRun predict = modelid("predict --robot kr150 --params " + quoted(dir / "est.json") +
                                 " --data " + data + " --decimated");
  EXPECT_EQ(predict.exit_code, 0) << predict.err;
  const CliRun simulate =
      modelid("simulate --robot kr150 --params " + quoted(dir / "est.json") + " --trajectory " +
              quoted_source("robots/data/kr150/excitation.yaml") +
              " --noise 0 --sample-time 0.01 -o " + quoted(dir / "sim.csv"));
  EXPECT_EQ(simulate.exit_code, 0) << simulate.err;
  // A standard set edited by hand no longer gives the base parameters beside it: refused.
  nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  est["standard"]["M3"] = est["standard"]["M3"].get<double>() + 10;
  test::write_text(dir / "edited.json", est.dump(2));
  const CliRun edited =
      modelid("predict --robot kr150 --params " + quoted(dir / "edited.json") + " --data " + data);
  EXPECT_NE(edited.exit_code, 0);
  EXPECT_NE(edited.err.find("the \"standard\" set gives"), std::string::npos) << edited.err;
}

// The KR 150 description gives no region and no a-priori link values, so its regions are
// guessed from the DH rows; they hold its example data's truth (kr150_region_guess_test), and
// the data do not reject them: the fit keeps them, and every guessed link ends within its
// region (its extent, the rms over its mass in units of the ellipsoid, at most 1).
TEST(ModelidPhysical, GuessedRegionsThatHoldTheTruthAreKept) {
  const fs::path dir = test::test_folder("physical_guess");
  const CliRun fit =
      modelid("fit --robot kr150 --data " + quoted_source("robots/data/kr150/excitation.csv") +
              " --method wls --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(fit.out.find("not enforced"), std::string::npos) << fit.out;
  const nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  const RobotModel robot = load_robot(test::source_path("robots/kr150.yaml"));
  const nlohmann::json& links = est["links"];
  ASSERT_EQ(links.size(), robot.body_regions.size());
  int held = 0;
  for (std::size_t b = 0; b < links.size(); ++b) {
    if (!robot.body_regions[b]) continue;
    double p[10];
    const char* stems[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
    for (int s = 0; s < 10; ++s) p[s] = value_of(est["standard"], stems[s] + std::to_string(b + 1));
    EXPECT_LE(test::extent(p, *robot.body_regions[b]), 1 + 1e-6) << links[b]["body"];
    held += links[b]["decided_by"]["mass"] == "bound";
  }
  EXPECT_GT(held, 0);  // the guesses do hold links the data leave free
}

// The rejection path: the same arm with an A3 that carries a counterweight a metre behind
// the elbow (its centre of mass 1 m along -x3, outside the guess, which reaches 0.3 m), data
// simulated from it: the guesses would raise the weighted sum of squares far beyond chance, so
// the fit says so and holds no link by them.
TEST(ModelidPhysical, GuessedRegionsTheDataRejectAreDropped) {
  const fs::path dir = test::test_folder("physical_guess_rejected");
  nlohmann::json truth =
      nlohmann::json::parse(test::read_text(test::source_path("robots/data/kr150/true.json")));
  nlohmann::json& standard = truth["standard"];
  // 150 kg at (-1, 0, 0) with central inertia diag(10, 20, 20), about the frame origin.
  for (const char* zero : {"XY3", "XZ3", "YZ3", "MY3", "MZ3"}) standard[zero] = 0.0;
  standard["XX3"] = 10.0;
  standard["YY3"] = 20.0 + 150.0;
  standard["ZZ3"] = 20.0 + 150.0;
  standard["MX3"] = -150.0;
  standard["M3"] = 150.0;
  test::write_text(dir / "true.json", truth.dump(2));
  const RobotModel robot = load_robot(test::source_path("robots/kr150.yaml"));
  ASSERT_TRUE(robot.body_regions[2] && robot.body_regions[2]->guessed);
  const BodyRegion& a3 = *robot.body_regions[2];
  EXPECT_GT(std::pow((-1.0 - a3.centre[0]) / a3.semi_axes[0], 2), 1.0);  // outside the guess
  ASSERT_EQ(modelid("simulate --robot kr150 --params " + quoted(dir / "true.json") +
                    " --trajectory " + quoted_source("robots/data/kr150/excitation.yaml") +
                    " --noise 2 --seed 1 --sample-time 0.01 -o " + quoted(dir / "run.csv"))
                .exit_code,
            0);
  const CliRun fit = modelid("fit --robot kr150 --data " + quoted(dir / "run.csv") +
                             " --method wls --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("not enforced: the data reject them"), std::string::npos) << fit.out;
  const nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  for (const nlohmann::json& link : est["links"]) {
    EXPECT_NE(link["decided_by"]["mass"], "bound") << link.dump();  // no guess holds a link
  }
}

TEST(ModelidPhysical, TheLinkTableStandsBesideTheAPrioriValues) {
  // The UR5 simulated from its own URDF inertials: EST.json's links carry the URDF's masses and
  // centres of mass (read here through the loader) as a-priori values, who decided each, the
  // weight the default rule chose; a link far from its a-priori values is warned about on
  // stderr exactly when EST.json says so.
  const fs::path dir = test::test_folder("physical_links");
  const std::string urdf = test::source_path("robots/urdf/ur5.urdf");
  ASSERT_EQ(modelid("simulate --robot " + quoted(fs::path(urdf)) + " --trajectory " +
                    quoted_source("robots/data/kr150/excitation.yaml") +
                    " --noise 0.05 --seed 14 --sample-time 0.02 --periods 1 -o " +
                    quoted(dir / "run.csv"))
                .exit_code,
            0);
  const CliRun fit =
      modelid("fit --robot " + quoted(fs::path(urdf)) + " --data " + quoted(dir / "run.csv") +
              " --method ols --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("by the default rule"), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("principal moments"), std::string::npos) << fit.out;
  const nlohmann::json est = nlohmann::json::parse(test::read_text(dir / "est.json"));
  EXPECT_EQ(est["physical"]["prior_weight_rule"], "default");
  const RobotModel robot = load_robot(urdf);
  const nlohmann::json& links = est["links"];
  ASSERT_EQ(links.size(), 6u);
  for (std::size_t b = 0; b < links.size(); ++b) {
    const nlohmann::json& link = links[b];
    const std::string j = std::to_string(b + 1);
    const double m = *robot.known_values[static_cast<std::size_t>(robot.param_index("M" + j))];
    ASSERT_TRUE(link.contains("a_priori")) << link;
    EXPECT_NEAR(link["a_priori"]["mass"].get<double>(), m, 1e-12 * m) << link["body"];
    const double mz = *robot.known_values[static_cast<std::size_t>(robot.param_index("MZ" + j))];
    EXPECT_NEAR(link["a_priori"]["com"][2].get<double>(), mz / m, 1e-9) << link["body"];
    for (const char* what : {"mass", "com", "principal_moments"}) {
      const std::string by = link["decided_by"][what];
      EXPECT_TRUE(by == "data" || by == "prior") << by;
    }
    const std::string warning = "warning: link '" + link["body"].get<std::string>() + "' is far";
    EXPECT_EQ(fit.err.find(warning) != std::string::npos, !link["far_from_a_priori"].empty())
        << fit.err;
  }
}

TEST(ModelidPhysical, OptionsAreChecked) {
  const std::string data = " --data " + quoted_source("robots/data/kr150/excitation.csv");
  const CliRun weight_alone = modelid("fit --robot kr150 --method wls --prior-weight 1" + data);
  EXPECT_NE(weight_alone.exit_code, 0);
  EXPECT_NE(weight_alone.err.find("--prior-weight belongs to --physical"), std::string::npos)
      << weight_alone.err;
  const CliRun bad_weight =
      modelid("fit --robot kr150 --method wls --physical --prior-weight -1" + data);
  EXPECT_NE(bad_weight.exit_code, 0);
  EXPECT_NE(bad_weight.err.find("--prior-weight must be positive"), std::string::npos)
      << bad_weight.err;
  // The ML fits take --physical too, and check its weight the same way.
  const CliRun ml =
      modelid("fit --robot kr150 --method ml --approach 2 --periodic --prior-weight 1" + data);
  EXPECT_NE(ml.exit_code, 0);
  EXPECT_NE(ml.err.find("--prior-weight belongs to --physical"), std::string::npos) << ml.err;
  // A weighed load mass with --physical: the ten load parameters are searched together.
  const fs::path dir = test::test_folder("physical");
  test::write_text(dir / "mass.json", "{\"load_m\": 125.46}");
  const CliRun partly = modelid("fit --robot " + quoted_source("robots/kr150.yaml") +
                                " --method ml --approach 3 --periodic --physical --known " +
                                quoted(dir / "mass.json") + data);
  EXPECT_EQ(partly.exit_code, 2) << partly.err;
  EXPECT_NE(partly.err.find("all unknown or all known"), std::string::npos) << partly.err;
}

}  // namespace
}  // namespace modelgen
