// fit --truth on simulated data: the distance of each estimate from the truth in its standard
// deviations, the count beyond 3 and the median error, checked against the same quantities
// computed here from the EST.json fit writes (value, std, truth), and a truth moved far off on
// one parameter named as the worst.

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using test::CliRun;
using test::modelid;
using test::quoted;

struct Summary {
  int beyond = -1, compared = -1, well_determined = -1;
  double median = -1;
  std::string worst;  // the first name in the parenthesis, empty when none is beyond
};

// The two summary lines of fit's standard output.
Summary summary_of(const std::string& out) {
  Summary s;
  std::smatch m;
  const std::regex counts(
      R"(against the truth: (\d+) of (\d+) parameters beyond 3 std(?: \((\w+))?)");
  if (std::regex_search(out, m, counts)) {
    s.beyond = std::stoi(m[1]);
    s.compared = std::stoi(m[2]);
    s.worst = m[3];
  }
  const std::regex median(R"(median \|error\| ([0-9.e+-]+) % over the (\d+) with %std)");
  if (std::regex_search(out, m, median)) {
    s.median = std::stod(m[1]);
    s.well_determined = std::stoi(m[2]);
  }
  return s;
}

TEST(ModelidTruth, FitSaysHowFarEachEstimateIsFromTheTruth) {
  const std::filesystem::path dir = test::test_folder();
  const std::filesystem::path truth = test::source_path("robots/data/tx40/true.json");
  const CliRun simulate =
      modelid("simulate --robot tx40 --params " + quoted(truth) + " --trajectory " +
              test::quoted_source("robots/data/tx40/design.yaml") + " --noise 0.5 -o " +
              quoted(dir / "run.csv"));
  ASSERT_EQ(simulate.exit_code, 0) << simulate.err;
  const CliRun fit =
      modelid("fit --robot tx40 --data " + quoted(dir / "run.csv") + " --method wls --truth " +
              quoted(truth) + " -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("truth    error %    err/std"), std::string::npos) << fit.out;

  // The same numbers from the estimate file.
  const nlohmann::json estimate = nlohmann::json::parse(test::read_text(dir / "est.json"));
  int beyond = 0, compared = 0;
  std::vector<double> errors;
  for (const auto& p : estimate["parameters"]) {
    const double value = p["value"], std_dev = p["std"], rel_std = p["rel_std"], t = p["truth"];
    if (!(std_dev > 0)) continue;
    ++compared;
    if (std::abs(value - t) > 3 * std_dev) ++beyond;
    if (rel_std <= 10 && t != 0) errors.push_back(100 * std::abs(value - t) / std::abs(t));
  }
  std::sort(errors.begin(), errors.end());
  ASSERT_FALSE(errors.empty());
  const std::size_t n = errors.size();
  const double median = n % 2 ? errors[n / 2] : (errors[n / 2 - 1] + errors[n / 2]) / 2;

  const Summary s = summary_of(fit.out);
  EXPECT_EQ(s.compared, compared) << fit.out;
  EXPECT_EQ(s.beyond, beyond) << fit.out;
  EXPECT_EQ(s.well_determined, static_cast<int>(n)) << fit.out;
  EXPECT_NEAR(s.median, median, 1e-3 * median) << fit.out;
  // Unbiased estimates from white noise: about 0.3 % of them beyond 3 std, so a handful at most.
  EXPECT_LE(beyond, 3) << fit.out;

  // A truth moved by 1 N m s/rad on Fv1 (tens of its standard deviations) is named first.
  nlohmann::json moved = nlohmann::json::parse(test::read_text(truth));
  moved["base"]["Fv1"] = moved["base"]["Fv1"].get<double>() + 1.0;
  test::write_text(dir / "moved.json", moved.dump(2));
  const CliRun off = modelid("fit --robot tx40 --data " + quoted(dir / "run.csv") +
                             " --method wls --truth " + quoted(dir / "moved.json"));
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const Summary o = summary_of(off.out);
  EXPECT_EQ(o.beyond, beyond + 1) << off.out;
  EXPECT_EQ(o.worst, "Fv1") << off.out;
}

}  // namespace
}  // namespace modelgen
