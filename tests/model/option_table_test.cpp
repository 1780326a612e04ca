// The command tables of modelgen/model/option_table.hpp: what the parser accepts and refuses,
// and that help and usage say what the table holds. Expectations are written from the table
// below, by hand.

#include "modelgen/model/option_table.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace modelgen {
namespace {

CommandSpec example() {
  CommandSpec spec{.program = "tool",
                   .name = "fit",
                   .summary = "fits things",
                   .selector = "--method",
                   .families = {{"the closed-loop methods", {"iv", "didim"}}}};
  spec.options = {
      {.name = "--robot", .value = "ROBOT", .help = "the robot", .required = true},
      {.name = "--data", .value = "FILE", .help = "a record", .repeatable = true},
      {.name = "--method",
       .type = ValueType::kChoice,
       .help = "the estimator",
       .choices = {"ols", "wls", "iv", "didim"}},
      {.name = "--controller",
       .value = "C.yaml",
       .help = "the controller",
       .methods = {"iv", "didim"}},
      {.name = "--cutoff",
       .type = ValueType::kPositive,
       .value = "HZ",
       .help = "filter",
       .unit = "Hz",
       .default_value = "10 x the band"},
      {.name = "--lags", .type = ValueType::kWhole, .value = "M", .help = "lags"},
      {.name = "--starts", .type = ValueType::kCount, .value = "K", .help = "starts"},
      {.name = "--physical", .type = ValueType::kFlag, .help = "consistent"},
      {.name = "--prior-weight",
       .type = ValueType::kPositive,
       .value = "W",
       .help = "weight",
       .needs = "--physical"},
      {.name = "--raw", .type = ValueType::kFlag, .help = "no filter", .group = "Data"},
  };
  spec.exclusive = {{"--raw", "--cutoff", "the filter is off"}};
  spec.elsewhere = {{"--params", "generation (-o DIR)"}};
  return spec;
}

CommandLine parse(const std::vector<std::string>& words) {
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  return parse_command(example(), static_cast<int>(argv.size()), argv.data(), 0);
}

std::string refusal(const std::vector<std::string>& words) {
  try {
    parse(words);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(OptionTable, AcceptsWhatTheTableAllows) {
  const CommandLine line = parse({"--robot", "r.yaml", "--data", "a.csv", "--data", "b.csv",
                                  "--method", "iv", "--controller", "c.yaml", "--physical",
                                  "--prior-weight", "0.5", "--lags", "0", "--starts", "3"});
  EXPECT_EQ(line.command, "fit");
  EXPECT_EQ(line.one("--robot"), "r.yaml");
  EXPECT_EQ(line.all("--data"), (std::vector<std::string>{"a.csv", "b.csv"}));
  EXPECT_TRUE(line.has("--physical"));
  EXPECT_EQ(line.one("--prior-weight"), "0.5");
}

TEST(OptionTable, AMistypedOptionNamesTheClosestOne) {
  EXPECT_EQ(refusal({"--robot", "r", "--metod", "wls"}),
            "unknown option '--metod' for fit (did you mean '--method'?)");
  // Nothing close: no guess.
  EXPECT_EQ(refusal({"--robot", "r", "--zzzzzzzz"}), "unknown option '--zzzzzzzz' for fit");
  EXPECT_EQ(refusal({"--robot", "r", "--params", "x.json"}),
            "fit takes no --params; it belongs to generation (-o DIR)");
}

TEST(OptionTable, AMistypedChoiceNamesTheAllowedOnesAndTheClosest) {
  EXPECT_EQ(refusal({"--robot", "r", "--method", "wsl"}),
            "--method must be ols, wls, iv or didim, not 'wsl' (did you mean 'wls'?)");
}

TEST(OptionTable, ValuesAreCheckedByType) {
  EXPECT_EQ(refusal({"--robot", "r", "--cutoff", "abc"}), "--cutoff must be a number, not 'abc'");
  EXPECT_EQ(refusal({"--robot", "r", "--cutoff", "0"}), "--cutoff must be positive, not '0'");
  EXPECT_EQ(refusal({"--robot", "r", "--cutoff", "inf"}), "--cutoff must be a number, not 'inf'");
  EXPECT_EQ(refusal({"--robot", "r", "--lags", "-1"}),
            "--lags must be a whole number >= 0, not '-1'");
  EXPECT_EQ(refusal({"--robot", "r", "--lags", "1.5"}),
            "--lags must be a whole number >= 0, not '1.5'");
  EXPECT_EQ(refusal({"--robot", "r", "--starts", "0"}),
            "--starts must be a whole number of at least 1, not '0'");
  EXPECT_EQ(refusal({"--robot", "r", "--cutoff"}), "--cutoff needs a value");
}

TEST(OptionTable, OptionsOfOtherMethodsAreRefusedWithTheirFamily) {
  EXPECT_EQ(refusal({"--robot", "r", "--method", "wls", "--controller", "c.yaml"}),
            "--controller belongs to the closed-loop methods, --method iv or didim, not --method "
            "wls");
  // Without the selector the command decides; the table does not guess.
  EXPECT_EQ(refusal({"--robot", "r", "--controller", "c.yaml"}), "(accepted)");
}

TEST(OptionTable, NeedsExclusionsRepeatsOperandsAndRequiredOptions) {
  EXPECT_EQ(refusal({"--robot", "r", "--prior-weight", "1"}),
            "--prior-weight belongs to --physical; add --physical");
  EXPECT_EQ(refusal({"--robot", "r", "--raw", "--cutoff", "5"}),
            "--raw and --cutoff exclude each other (the filter is off)");
  EXPECT_EQ(refusal({"--robot", "r", "--robot", "s"}), "--robot given twice");
  EXPECT_EQ(refusal({"--robot", "r", "stray.csv"}),
            "unexpected argument 'stray.csv' for fit "
            "(each data file needs its own --data)");
  EXPECT_EQ(refusal({"--data", "a.csv"}), "fit needs --robot ROBOT");
}

TEST(OptionTable, HelpListsEveryOptionWithItsFacts) {
  const std::string help = command_help(example());
  EXPECT_EQ(help.rfind("usage: tool fit --robot ROBOT [OPTIONS]\n", 0), 0u) << help;
  for (const OptionSpec& option : example().options) {
    EXPECT_NE(help.find("  " + option.name + " "), std::string::npos) << option.name << "\n"
                                                                      << help;
  }
  EXPECT_NE(help.find("--method ols|wls|iv|didim"), std::string::npos) << help;
  EXPECT_NE(help.find("unit Hz; default 10 x the band"), std::string::npos) << help;
  EXPECT_NE(help.find("with --method iv or didim only"), std::string::npos) << help;
  EXPECT_NE(help.find("with --physical only"), std::string::npos) << help;
  EXPECT_NE(help.find("\nData:\n  --raw"), std::string::npos) << help;
  for (std::size_t start = 0, end; start < help.size(); start = end + 1) {
    end = help.find('\n', start);
    EXPECT_LE(end - start, 96u) << help.substr(start, end - start);
  }
}

TEST(OptionTable, OrListReadsAsASentence) {
  EXPECT_EQ(or_list({"a"}), "a");
  EXPECT_EQ(or_list({"a", "b"}), "a or b");
  EXPECT_EQ(or_list({"a", "b", "c"}), "a, b or c");
}

}  // namespace
}  // namespace modelgen
