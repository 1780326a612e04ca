// The firmware constants of `modelgen --params` (issue 14), compiled: the bundled KR150 run is
// fitted at build time (modelid fit -o), modelgen_generate(PARAMS) bakes the estimate into a
// generated KR150, and inverse_dynamics_identified must equal inverse_dynamics on the values this
// test reads from the estimate file itself, by name, at random states. The banner must carry the
// estimate's SHA-256.

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "kr150.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace model = ::modelgen::kr150;

constexpr int kStates = 2000;

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// beta as the estimate file gives it, in the order of kBaseParamNames.
std::vector<double> estimate_in_model_order() {
  const nlohmann::json estimate = nlohmann::json::parse(file_text(MODELGEN_IDENTIFIED_ESTIMATE));
  std::map<std::string, double> by_name;
  for (const nlohmann::json& entry : estimate.at("parameters")) {
    by_name[entry.at("name").get<std::string>()] = entry.at("value").get<double>();
  }
  EXPECT_EQ(by_name.size(), static_cast<std::size_t>(model::kBaseParams));
  std::vector<double> beta;
  for (int k = 0; k < model::kBaseParams; ++k)
    beta.push_back(by_name.at(model::kBaseParamNames[k]));
  return beta;
}

template <typename T>
double relative_difference(const T* a, const T* b) {
  double difference = 0, size = 0;
  for (int i = 0; i < model::kDof; ++i) {
    difference = std::max(difference, std::abs(static_cast<double>(a[i]) - b[i]));
    size = std::max(size, std::abs(static_cast<double>(b[i])));
  }
  return difference / std::max(size, 1e-300);
}

TEST(IdentifiedConstants, ConstantsAreTheEstimateInBaseParameterOrder) {
  const std::vector<double> beta = estimate_in_model_order();
  ASSERT_EQ(beta.size(), static_cast<std::size_t>(model::kBaseParams));
  for (int k = 0; k < model::kBaseParams; ++k) {
    // Shortest round-trip literals: the exact double, and the float nearest to it.
    EXPECT_EQ(model::kIdentifiedBase[k], beta[k]) << model::kBaseParamNames[k];
    EXPECT_EQ(model::kIdentifiedBaseFloat[k], static_cast<float>(beta[k]))
        << model::kBaseParamNames[k];
  }
}

TEST(IdentifiedConstants, InverseDynamicsIdentifiedIsInverseDynamicsOnTheEstimate) {
  const std::vector<double> beta = estimate_in_model_order();
  ASSERT_EQ(beta.size(), static_cast<std::size_t>(model::kBaseParams));
  std::vector<float> beta_float(beta.begin(), beta.end());
  test::Random random(14);
  double worst = 0, worst_float = 0;
  for (int s = 0; s < kStates; ++s) {
    double q[model::kDof], dq[model::kDof], ddq[model::kDof];
    float qf[model::kDof], dqf[model::kDof], ddqf[model::kDof];
    for (int i = 0; i < model::kDof; ++i) {
      qf[i] = static_cast<float>(q[i] = random.uniform(-M_PI, M_PI));
      dqf[i] = static_cast<float>(dq[i] = random.uniform(-2, 2));
      ddqf[i] = static_cast<float>(ddq[i] = random.uniform(-5, 5));
    }
    double tau[model::kDof], expected[model::kDof];
    model::inverse_dynamics(q, dq, ddq, beta.data(), expected);
    model::inverse_dynamics_identified(q, dq, ddq, tau);
    worst = std::max(worst, relative_difference(tau, expected));
    float tauf[model::kDof], expectedf[model::kDof];
    model::inverse_dynamics(qf, dqf, ddqf, beta_float.data(), expectedf);
    model::inverse_dynamics_identified(qf, dqf, ddqf, tauf);
    worst_float = std::max(worst_float, relative_difference(tauf, expectedf));
  }
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(worst_float, 1e-6);
  std::cout << "worst relative difference over " << kStates << " states: double " << worst
            << ", float " << worst_float << "\n";
}

TEST(IdentifiedConstants, BannerNamesTheEstimateByItsHash) {
  const std::string sha = sha256_hex(read_source_file(MODELGEN_IDENTIFIED_ESTIMATE));
  for (const char* file : {"kr150.hpp", "kr150.cpp"}) {
    const std::string text = file_text(std::string(MODELGEN_IDENTIFIED_DIR) + "/" + file);
    EXPECT_NE(text.find("// Identified parameters: kr150_estimate.json, method IDIM-WLS\n"
                        "// Identified parameters SHA-256: " +
                        sha + "\n"),
              std::string::npos)
        << file;
  }
  const std::string manifest = file_text(std::string(MODELGEN_IDENTIFIED_DIR) + "/kr150.json");
  EXPECT_NE(manifest.find("\"sha256\": \"" + sha + "\""), std::string::npos);
  EXPECT_NE(manifest.find("{\"name\": \"inverse_dynamics_identified\""), std::string::npos);
}

}  // namespace
}  // namespace modelgen
