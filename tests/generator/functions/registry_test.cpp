// The registry of generated functions (generator/functions/registry.cpp) and what the emitter
// makes of it: unique names, one template per function (none per variant), the file order by section with the
// _sincos variants after the plain functions, callee counts, and a Model struct with exactly
// the members the registry marks.

#include "generator/functions/registry.hpp"

#include <set>
#include <string>

#include <gtest/gtest.h>

#include "generator/emit/function_emitter.hpp"
#include "generator/emit/template.hpp"
#include "generator/generate.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

TEST(Registry, NamesAreUniqueAndEveryEntryIsComplete) {
  std::set<std::string> names;
  for (const FunctionEntry& entry : function_registry()) {
    EXPECT_TRUE(names.insert(entry.name).second) << entry.name << " is listed twice";
    EXPECT_NE(entry.build, nullptr) << entry.name;
    EXPECT_FALSE(entry.outputs.empty()) << entry.name;
    EXPECT_NO_THROW(embedded_template(std::string("functions/") + entry.name)) << entry.name;
    if (entry.variants == Variants::kSincos) {
      // The variant reads sin_q and cos_q in place of computing them from q.
      bool takes_q = false;
      for (const ArraySpec& input : entry.inputs) takes_q = takes_q || std::string(input.name) == "q";
      EXPECT_TRUE(takes_q) << entry.name;
    }
  }
}

TEST(Registry, FilesOrderFunctionsBySectionWithVariantsLast) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const BaseParameterSet base = derive_base_parameters(model.tree);
  ExprGraph graph;
  const std::vector<EmittedFunction> functions =
      emit_functions(model, base, graph, {Scalar::kDouble});
  std::size_t expected = 0;
  for (const FunctionEntry& entry : function_registry()) {
    if (entry.emitted == Emitted::kWithEstimate) continue;  // only with --params
    expected += entry.variants == Variants::kSincos ? 2 : 1;
  }
  ASSERT_EQ(functions.size(), expected);
  for (std::size_t i = 1; i < functions.size(); ++i) {
    const EmittedFunction &before = functions[i - 1], &after = functions[i];
    ASSERT_LE(before.entry->section, after.entry->section) << after.name;
    if (before.entry->section == after.entry->section) {
      EXPECT_LE(before.sincos, after.sincos) << after.name << " comes after a _sincos variant";
    }
    EXPECT_EQ(after.name, std::string(after.entry->name) + (after.sincos ? "_sincos" : ""));
  }
  // A variant takes the plain function's arrays, with sin_q and cos_q right after q.
  for (const EmittedFunction& variant : functions) {
    if (!variant.sincos) continue;
    for (const EmittedFunction& plain : functions) {
      if (plain.sincos || plain.entry != variant.entry) continue;
      std::vector<std::string> expected = plain.inputs;
      expected.insert(expected.begin() + 1, {"sin_q", "cos_q"});
      ASSERT_EQ(plain.inputs.front(), "q");
      EXPECT_EQ(variant.inputs, expected) << variant.name;
      EXPECT_EQ(variant.outputs, plain.outputs) << variant.name;
    }
  }
  // A function that calls others counts their operations too.
  for (const EmittedFunction& f : functions) {
    for (const std::string& callee : f.calls) {
      for (const EmittedFunction& g : functions) {
        if (g.name == callee) {
          EXPECT_GT(f.counts.mul, g.counts.mul) << f.name;
        }
      }
    }
  }
}

// With an estimate (--params), inverse_dynamics_identified comes last: a call to
// inverse_dynamics on the constants of the scalar type, no statements of its own, so its
// operation counts are those of inverse_dynamics. Without one it is not emitted (above).
TEST(Registry, IdentifiedInverseDynamicsWrapsInverseDynamics) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const BaseParameterSet base = derive_base_parameters(model.tree);
  ExprGraph graph;
  const std::vector<EmittedFunction> functions =
      emit_functions(model, base, graph, {Scalar::kDouble, Scalar::kFloat}, true);
  const EmittedFunction& identified = functions.back();
  ASSERT_EQ(identified.name, "inverse_dynamics_identified");
  EXPECT_EQ(identified.inputs, (std::vector<std::string>{"q", "dq", "ddq"}));
  EXPECT_EQ(identified.outputs, (std::vector<std::string>{"tau"}));
  ASSERT_EQ(identified.bodies.size(), 2u);
  EXPECT_EQ(identified.bodies[0].lines,
            (std::vector<std::string>{"inverse_dynamics(q, dq, ddq, kIdentifiedBase, tau);"}));
  EXPECT_EQ(identified.bodies[1].lines,
            (std::vector<std::string>{"inverse_dynamics(q, dq, ddq, kIdentifiedBaseFloat, tau);"}));
  for (const EmittedFunction& f : functions) {
    if (f.name != "inverse_dynamics") continue;
    EXPECT_EQ(identified.counts.mul, f.counts.mul);
    EXPECT_EQ(identified.counts.add, f.counts.add);
    EXPECT_EQ(identified.counts.trig, f.counts.trig);
  }
  // Float alone: the one array is kIdentifiedBase, in float.
  ExprGraph float_graph;
  const std::vector<EmittedFunction> float_only =
      emit_functions(model, base, float_graph, {Scalar::kFloat}, true);
  EXPECT_EQ(float_only.back().bodies.at(0).lines,
            (std::vector<std::string>{"inverse_dynamics(q, dq, ddq, kIdentifiedBase, tau);"}));
}

TEST(Registry, ModelStructHasExactlyTheMarkedMembers) {
  const GeneratedModel generated = generate_from_file(test::source_path("robots/tx40.yaml"), {});
  const std::string header = generated.files.files().at(0).content;
  const std::string model_struct = header.substr(header.find("struct Model {"));
  for (const FunctionEntry& entry : function_registry()) {
    const bool member =
        model_struct.find(std::string("static void ") + entry.name + "(") != std::string::npos;
    EXPECT_EQ(member, entry.in_model_struct == InModelStruct::kYes) << entry.name;
  }
}

}  // namespace
}  // namespace modelgen::gen
