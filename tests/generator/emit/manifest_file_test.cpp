// The manifest (generator/emit/manifest_file): valid JSON whose fields are the facts of the
// generation, the regrouping relations reading back as the exact doubles derived, and the
// operation counts those of the generated functions.

#include "generator/emit/manifest_file.hpp"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "generator/generate.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/generated_format.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

TEST(ManifestFile, ReadsBackAsTheFactsOfTheGeneration) {
  const std::string path = test::source_path("robots/kr150.yaml");
  const GeneratedModel generated = generate_from_file(path, {});
  // The manifest is written last, after the header, the tables and the function files.
  const std::string& text = generated.files.files().back().content;
  ASSERT_EQ(generated.files.files().back().name, "kr150.json");
  const nlohmann::json manifest = nlohmann::json::parse(text);

  const RobotModel model = load_robot(path);
  EXPECT_EQ(manifest["format_version"], kGeneratedFormatVersion);
  EXPECT_EQ(manifest["robot"], "kr150");
  EXPECT_EQ(manifest["input"], "kr150.yaml");
  EXPECT_EQ(manifest["dof"], model.dof());
  ASSERT_EQ(manifest["standard_parameters"].size(), model.tree.params.size());
  for (std::size_t k = 0; k < model.tree.params.size(); ++k) {
    EXPECT_EQ(manifest["standard_parameters"][k], model.tree.params[k].name);
  }
  const BaseParameterSet base = derive_base_parameters(model.tree);
  ASSERT_EQ(manifest["base_parameters"].size(), base.params.size());
  for (std::size_t b = 0; b < base.params.size(); ++b) {
    const nlohmann::json& entry = manifest["base_parameters"][b];
    EXPECT_EQ(entry["name"], base.params[b].name);
    ASSERT_EQ(entry["relation"].size(), base.params[b].relation.size());
    for (const auto& [k, coefficient] : base.params[b].relation) {
      EXPECT_EQ(entry["relation"][model.tree.params[k].name].get<double>(), coefficient);
    }
  }
  ASSERT_EQ(manifest["functions"].size(), generated.functions.size());
  for (std::size_t i = 0; i < generated.functions.size(); ++i) {
    const nlohmann::json& f = manifest["functions"][i];
    EXPECT_EQ(f["name"], generated.functions[i].name);
    EXPECT_EQ(f["mul"], generated.functions[i].counts.mul);
    EXPECT_EQ(f["add"], generated.functions[i].counts.add);
    EXPECT_EQ(f["sin_cos"], generated.functions[i].counts.trig);
  }
}

TEST(ManifestFile, OneMemberPerLineAndOneArrayElementPerLine) {
  const GeneratedModel generated = generate_from_file(test::source_path("robots/tx40.yaml"), {});
  const std::string& text = generated.files.files().back().content;
  EXPECT_EQ(text.rfind("{\n  \"generator\": \"modelgen\",\n", 0), 0U);
  EXPECT_NE(text.find("\n  \"standard_parameters\": [\n    \"XX1\",\n"), std::string::npos);
  EXPECT_NE(text.find("\n    {\"name\": \"idim_regressor_standard\", \"mul\": "), std::string::npos);
  EXPECT_EQ(text.substr(text.size() - 6), "  ]\n}\n");
}

}  // namespace
}  // namespace modelgen::gen
