// Typo suggestions of the loaders (closest_match, did_you_mean): the closest candidate within a
// third of the word's length, and a cost bounded by the candidates, not by the word: a name of
// a megabyte (a fuzzed JSON key) must not build a table per candidate.

#include <chrono>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/error.hpp"

namespace modelgen {
namespace {

TEST(DidYouMean, SuggestsTheClosestCandidate) {
  const std::vector<std::string> keys = {"name", "type", "ant", "alpha", "d", "theta", "r"};
  EXPECT_EQ(closest_match("alpah", keys), "alpha");  // one transposition
  EXPECT_EQ(closest_match("thetta", keys), "theta");  // one insertion
  EXPECT_EQ(closest_match("ALPHA", keys), "alpha");  // case ignored
  EXPECT_EQ(closest_match("gravity", keys), "");  // nothing within a third of 7 letters
  EXPECT_EQ(did_you_mean("ZZ2", {"XX1", "ZZ1"}), " (did you mean 'ZZ1'?)");
  EXPECT_EQ(did_you_mean("mass", {"XX1", "ZZ1"}), "");
}

TEST(DidYouMean, AMegabyteNameAgainstManyCandidatesIsFast) {
  std::vector<std::string> names;
  for (int j = 1; j <= 50; ++j) {
    for (const char* p : {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M", "Ia", "Fv"}) {
      names.push_back(p + std::to_string(j) + "R");
    }
  }
  const std::string huge(1 << 20, 'Z');
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(closest_match(huge, names), "");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // A table per candidate takes tens of seconds here; skipping by length takes microseconds.
  EXPECT_LT(seconds, 1.0);
}

TEST(DidYouMean, LongNamesStillGetSuggestions) {
  const std::string word(300, 'a');
  std::string near = word;
  near[150] = 'b';
  EXPECT_EQ(closest_match(word, {near, std::string(10, 'a')}), near);
}

}  // namespace
}  // namespace modelgen
