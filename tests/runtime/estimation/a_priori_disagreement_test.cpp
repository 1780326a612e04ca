// Issue 30: where the data reject a link's a-priori values. A hand-built regrouping of two
// bodies and a drive parameter, each z worked out by hand: a row with a parameter without an
// a-priori value has none; a rounding-level coefficient is no regrouping; a row that two
// bodies enter is listed for both; largest |z| first; the threshold.

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/estimation/a_priori_disagreement.hpp"

namespace modelgen {
namespace {

struct Case {
  std::vector<std::array<int, 10>> bodies{{0, 1, 2, 3, 4, 5, 6, 7, 8, 9},
                                          {10, 11, 12, 13, 14, 15, 16, 17, 18, 19}};
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(4, 21);
  std::vector<std::optional<double>> a_priori = std::vector<std::optional<double>>(21, 0.0);
  Eigen::VectorXd beta_hat = Eigen::VectorXd(4), sd = Eigen::VectorXd(4);
  std::vector<std::string> names{"ZZ1R", "MX1R", "MY2", "M2R"};
  Case() {
    K(0, 5) = 1;  // ZZ1R = ZZ1 + Ia1; Ia1 (20) has no a-priori value
    K(0, 20) = 1;
    K(1, 6) = 1;  // MX1R = MX1 + 0.5 M2
    K(1, 19) = 0.5;
    K(2, 17) = 1;  // MY2
    K(3, 19) = 1;  // M2R = M2, and a rounding-level MX1
    K(3, 6) = 1e-14;
    a_priori[5] = 1.0;
    a_priori[20] = std::nullopt;
    a_priori[6] = 0.2;
    a_priori[19] = 2.0;
    a_priori[17] = 0.1;
    beta_hat << 50.0, 1.0, 0.15, 2.5;
    sd << 0.01, 0.01, 0.01, 0.2;
  }
};

TEST(APrioriDisagreement, ListsTheRejectedBaseParametersOfEachBody) {
  const Case c;
  // z: ZZ1R undefined; MX1R (0.2 + 0.5 * 2 - 1.0) / 0.01 = +20; MY2 (0.1 - 0.15) / 0.01 = -5;
  // M2R (2 - 2.5) / 0.2 = -2.5.
  const auto loose = a_priori_disagreement(c.bodies, c.K, c.a_priori, c.beta_hat, c.sd, c.names, 2);
  ASSERT_EQ(loose.size(), 2u);
  ASSERT_EQ(loose[0].size(), 1u);  // not ZZ1R (no a-priori Ia1), not M2R (rounding only)
  EXPECT_EQ(loose[0][0].name, "MX1R");
  EXPECT_NEAR(loose[0][0].z(), 20.0, 1e-9);
  ASSERT_EQ(loose[1].size(), 3u);
  EXPECT_EQ(loose[1][0].name, "MX1R");
  EXPECT_EQ(loose[1][1].name, "MY2");
  EXPECT_NEAR(loose[1][1].z(), -5.0, 1e-9);
  EXPECT_EQ(loose[1][2].name, "M2R");
  EXPECT_NEAR(loose[1][2].z(), -2.5, 1e-9);
  const auto strict =
      a_priori_disagreement(c.bodies, c.K, c.a_priori, c.beta_hat, c.sd, c.names, 3);
  ASSERT_EQ(strict[1].size(), 2u);  // M2R is within 3 sd
  EXPECT_EQ(disagreement_words(strict[1], 1), std::vector<std::string>{"MX1R +20.0 sd"});
  EXPECT_EQ(disagreement_words(strict[1], 5),
            (std::vector<std::string>{"MX1R +20.0 sd", "MY2 -5.0 sd"}));
}

TEST(APrioriDisagreement, RefusesMismatchedSizes) {
  const Case c;
  const std::vector<std::string> short_names{"ZZ1R"};
  EXPECT_THROW(a_priori_disagreement(c.bodies, c.K, c.a_priori, c.beta_hat, c.sd, short_names, 3),
               std::invalid_argument);
}

}  // namespace
}  // namespace modelgen
