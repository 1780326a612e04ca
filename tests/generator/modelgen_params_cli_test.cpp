// `modelgen ROBOT --params EST.json` as a user runs it: the estimate's base parameters become
// constants in the order of the model's base parameters whatever the order of the file, the
// banner, the regeneration command and the manifest name the estimate and its hash, and an
// estimate without a description hash is used with a warning. Broken estimates are files in
// tests/bad_inputs/estimate/; the compiled constants are tested in tests/firmware/.

#include <filesystem>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::modelgen;
using test::read_text;

const char* const kRobot = "tests/bad_inputs/robots/two_axes.yaml";

// Values chosen for the test, listed in an order of their own (not the model's).
const std::vector<std::pair<std::string, double>> kValues = {
    {"OFF2", 0.05}, {"Fc2", 0.6},     {"Fv2", 0.3},  {"Ia2", 0.0625}, {"MY2", -0.25}, {"MX2", 2.5},
    {"ZZ2", 0.375}, {"OFF1", -0.125}, {"Fc1", 0.75}, {"Fv1", 0.5},    {"ZZ1R", 1.25}};

// The literal a test value is written as: shortest round trip (these are exact in both types
// but 0.05, 0.3 and 0.6, whose shortest float forms are the same digits).
std::string literal(double value, bool is_float) {
  std::string text = std::to_string(value);
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text += '0';
  return text + (is_float ? "f" : "");
}

// An estimate as modelid fit -o writes it; `extra_members` go before "parameters".
std::string estimate_json(const std::string& description_hash_member,
                          const std::string& extra_members = "") {
  std::string text = "{\n  \"model\": \"two_axes\",\n" + description_hash_member +
                     "  \"method\": \"IDIM-WLS\",\n" + extra_members + "  \"parameters\": [\n";
  for (std::size_t k = 0; k < kValues.size(); ++k) {
    text += "    {\"name\": \"" + kValues[k].first +
            "\", \"value\": " + literal(kValues[k].second, false) +
            (k + 1 < kValues.size() ? "},\n" : "}\n");
  }
  return text + "  ]\n}\n";
}

std::string hash_member() {
  return "  \"description_sha256\": \"" + sha256_hex(read_source_file(test::source_path(kRobot))) +
         "\",\n";
}

double value_of(const std::string& name) {
  for (const auto& [n, v] : kValues) {
    if (n == name) return v;
  }
  ADD_FAILURE() << name << " is not a test value";
  return 0;
}

// The base parameter names in the order the manifest lists them (the model's order).
std::vector<std::string> manifest_base_order(const std::string& manifest) {
  const std::size_t begin = manifest.find("\"base_parameters\": [");
  const std::size_t end = manifest.find("]", manifest.find("\n  ]", begin));
  std::vector<std::string> names;
  const std::regex name(R"re(\n    \{"name": "([A-Za-z0-9]+)")re");
  const std::string list = manifest.substr(begin, end - begin);
  for (std::sregex_iterator m(list.begin(), list.end(), name), last; m != last; ++m) {
    names.push_back((*m)[1]);
  }
  return names;
}

TEST(ModelgenParams, ConstantsFollowTheModelsBaseParameterOrder) {
  const fs::path dir = test::test_folder();
  const fs::path estimate = dir / "two_axes_est.json";
  test::write_text(estimate, estimate_json(hash_member()));
  const CliRun run = modelgen(test::quoted_source(kRobot) + " -o " + test::quoted(dir / "out") +
                              " --params " + test::quoted(estimate));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(run.out, "");
  const std::string header = read_text(dir / "out/two_axes.hpp");
  const std::string source = read_text(dir / "out/two_axes.cpp");
  // Prototypes as one line: long parameter lists are wrapped at 100 columns.
  const std::regex wrap("\n +");
  const std::string header_line = std::regex_replace(header, wrap, " ");
  const std::string function_line = std::regex_replace(
      read_text(dir / "out/two_axes_inverse_dynamics_identified.cpp"), wrap, " ");
  const std::string manifest = read_text(dir / "out/two_axes.json");

  const std::vector<std::string> order = manifest_base_order(manifest);
  ASSERT_EQ(order.size(), kValues.size()) << manifest;
  for (const auto& [array, is_float] :
       {std::pair<std::string, bool>{"double kIdentifiedBase", false},
        std::pair<std::string, bool>{"float kIdentifiedBaseFloat", true}}) {
    std::string expected = "const " + array + "[kBaseParams] = {\n";
    for (const std::string& name : order) {
      expected += "    " + literal(value_of(name), is_float) + ",  // " + name + "\n";
    }
    EXPECT_NE(source.find(expected + "};\n"), std::string::npos) << expected << "\n" << source;
    EXPECT_NE(header.find("extern const " + array + "[kBaseParams];"), std::string::npos);
  }
  for (const char* scalar : {"double", "float"}) {
    const std::string s(scalar);
    const std::string prototype = "void inverse_dynamics_identified(const " + s + "* q, const " +
                                  s + "* dq, const " + s + "* ddq, " + s + "* tau)";
    EXPECT_NE(header_line.find(prototype + ";"), std::string::npos) << prototype;
    EXPECT_NE(function_line.find(prototype + " {"), std::string::npos) << prototype;
  }

  const std::string sha = sha256_hex(read_source_file(estimate.string()));
  const std::string banner_lines =
      "// Identified parameters: two_axes_est.json, method IDIM-WLS\n"
      "// Identified parameters SHA-256: " +
      sha + "\n";
  for (const std::string* text : {&header, &source}) {
    EXPECT_NE(text->find(banner_lines), std::string::npos) << text->substr(0, 600);
    EXPECT_NE(text->find("// Regenerate: modelgen two_axes.yaml -o <dir> --params "
                         "two_axes_est.json\n"),
              std::string::npos);
  }
  EXPECT_NE(manifest.find("\"identified_from\": {\"file\": \"two_axes_est.json\", \"sha256\": \"" +
                          sha + "\", \"method\": \"IDIM-WLS\"}"),
            std::string::npos)
      << manifest;
  EXPECT_NE(manifest.find("{\"name\": \"inverse_dynamics_identified\""), std::string::npos);
  EXPECT_NE(manifest.find("{\"name\": \"ZZ1R\", \"value\": 1.25}"), std::string::npos);
}

// fit --physical adds a consistent standard set; the constants are still "parameters", the base
// estimate (here the standard set would give ZZ1R = 99 + 0.25 M2).
TEST(ModelgenParams, PhysicalEstimateGivesItsBaseParameters) {
  const fs::path dir = test::test_folder();
  const fs::path estimate = dir / "physical.json";
  test::write_text(estimate, estimate_json(hash_member(),
                                           "  \"standard\": {\"ZZ1\": 99.0, \"M2\": 4.0},\n"
                                           "  \"physical\": {\"prior_weight\": 0.001},\n"));
  const CliRun run = modelgen(test::quoted_source(kRobot) + " -o " + test::quoted(dir / "out") +
                              " --params " + test::quoted(estimate));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(read_text(dir / "out/two_axes.cpp").find("    1.25,  // ZZ1R\n"), std::string::npos);
}

TEST(ModelgenParams, WithoutParamsNothingIdentifiedIsEmitted) {
  const fs::path dir = test::test_folder();
  const CliRun run = modelgen(test::quoted_source(kRobot) + " -o " + test::quoted(dir));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* file : {"two_axes.hpp", "two_axes.cpp", "two_axes.json"}) {
    const std::string text = read_text(dir / file);
    EXPECT_EQ(text.find("dentified"), std::string::npos) << file;
  }
}

TEST(ModelgenParams, EstimateWithoutDescriptionHashIsUsedWithAWarning) {
  const fs::path dir = test::test_folder();
  const fs::path estimate = dir / "hand_written.json";
  test::write_text(estimate, estimate_json(""));
  const CliRun run = modelgen(test::quoted_source(kRobot) + " -o " + test::quoted(dir / "out") +
                              " --params " + test::quoted(estimate));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, estimate.string() +
                         ": warning: no \"description_sha256\", so nothing shows that the "
                         "estimate was made on two_axes.yaml; its values are taken by base "
                         "parameter name\n");
  EXPECT_TRUE(fs::exists(dir / "out/two_axes.cpp"));
}

TEST(ModelgenParams, MissingEstimateFileWritesNothing) {
  const fs::path dir = test::test_folder();
  const CliRun run = modelgen(test::quoted_source(kRobot) + " -o " + test::quoted(dir / "out") +
                              " --params " + test::quoted(dir / "absent.json"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err, (dir / "absent.json").string() + ": error: cannot open the file\n");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(ModelgenParams, ParamsBelongsToGeneration) {
  for (const char* command : {"describe", "base"}) {
    const CliRun run =
        modelgen(std::string(command) + " " + test::quoted_source(kRobot) + " --params x.json");
    EXPECT_EQ(run.exit_code, 2) << command;
    EXPECT_NE(run.err.find("modelgen: " + std::string(command) +
                           " takes no --params; it belongs to generation (-o DIR)"),
              std::string::npos)
        << run.err;
  }
}

}  // namespace
}  // namespace modelgen
