// Every broken YAML description in tests/bad_inputs/yaml/ must give one clear message naming
// the file, line and column and what is wrong, both from the loader and from `modelgen
// describe` (exit code 1, nothing on stdout, no crash).

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

struct BadInput {
  const char* file;
  const char* position;  // ":line:column" expected right after the file name
  const char* phrase;    // must appear in the message
};

// Positions counted by hand in each file (1-based line and column of the offending token).
const BadInput kCases[] = {
    {"syntax_error.yaml", ":4:", "YAML syntax error"},
    {"unknown_key.yaml", ":4:22:", "unknown key 'alpah' in joint 2 (did you mean 'alpha'?)"},
    {"unknown_top_key.yaml", ":2:1:", "unknown key 'gravty' in the robot description (did you mean 'gravity'?)"},
    {"wrong_type.yaml", ":6:8:", "'d' must be a number, got 'twenty'"},
    {"bad_angle.yaml", ":3:29:", "'alpha' must be an angle"},
    {"missing_field.yaml", ":4:5:", "missing field 'theta' in joint 2"},
    {"missing_name.yaml", ":1:1:", "missing field 'name'"},
    {"unknown_joint_type.yaml", ":3:12:", "unknown joint type 'revolut' (did you mean 'revolute'?)"},
    {"coupling_not_square.yaml", ":10:9:", "is not square"},
    {"coupling_wrong_size.yaml", ":8:23:", "is 2x2 but must be 3x3"},
    {"coupling_singular.yaml", ":7:23:", "is singular"},
    {"coupling_both_forms.yaml", ":6:5:", "exactly one of"},
    {"antecedent_cycle.yaml", ":4:27:", "antecedents form a cycle: 2 -> 3 -> 2"},
    {"antecedent_missing.yaml", ":4:27:", "antecedent 'elbow' of joint 2 is not a link name"},
    {"name_keyword.yaml", ":1:7:", "robot name 'class' is reserved"},
    {"known_unknown_parameter.yaml", ":6:3:", "'ZZ2' in 'known' is not a standard parameter"},
    {"ratio_count.yaml", ":6:10:", "'ratio' must be a list of 2 numbers"},
    {"limits_reversed.yaml", ":3:66:", "lower < upper"},
    {"all_fixed.yaml", ":3:3:", "no moving joint"},
    {"empty.yaml", "", "the file is empty"},
};

std::string bad_input_path(const char* file) {
  return test::source_path("tests/bad_inputs/yaml/") + file;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(YamlBadInputs, LoaderNamesFileLineAndProblem) {
  for (const BadInput& c : kCases) {
    const std::string path = bad_input_path(c.file);
    try {
      load_robot(path);
      ADD_FAILURE() << c.file << ": loaded without error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + c.position, 0), 0u) << c.file << ": " << what;
      EXPECT_NE(what.find(c.phrase), std::string::npos) << c.file << ": " << what;
    }
  }
}

TEST(YamlBadInputs, ModelgenDescribeExitsWithTheMessage) {
  const std::string modelgen = std::string(MODELGEN_BINARY_DIR) + "/bin/modelgen";
  const std::string out = testing::TempDir() + "modelgen_bad_stdout.txt";
  const std::string err = testing::TempDir() + "modelgen_bad_stderr.txt";
  for (const BadInput& c : kCases) {
    const std::string path = bad_input_path(c.file);
    const std::string command =
        "'" + modelgen + "' describe '" + path + "' >'" + out + "' 2>'" + err + "'";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << c.file << ": modelgen did not exit normally";
    EXPECT_EQ(WEXITSTATUS(status), 1) << c.file;
    EXPECT_EQ(read(out), "") << c.file;
    const std::string message = read(err);
    EXPECT_NE(message.find(path + c.position), std::string::npos) << message;
    EXPECT_NE(message.find(c.phrase), std::string::npos) << message;
  }
}

TEST(YamlBadInputs, MissingFileAndUnknownExtension) {
  EXPECT_THROW(load_robot(test::source_path("robots/no_such_robot.yaml")), InputError);
  EXPECT_THROW(load_robot(test::source_path("README.md")), InputError);
}

}  // namespace
}  // namespace modelgen::gen
