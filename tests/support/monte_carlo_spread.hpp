// The Monte-Carlo check of reported standard deviations (issue 31): over R independent noisy
// fits, each parameter's reported sd (root mean square over the runs) against the spread of
// its estimates. With R runs the spread's own relative error is about 1 / sqrt(2 (R - 1)).
#pragma once

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

namespace modelgen::test {

class SpreadCheck {
 public:
  explicit SpreadCheck(Eigen::Index parameters)
      : sum_(Eigen::VectorXd::Zero(parameters)),
        squares_(Eigen::VectorXd::Zero(parameters)),
        variance_(Eigen::VectorXd::Zero(parameters)) {}

  void add(const Eigen::VectorXd& value, const Eigen::VectorXd& std_dev) {
    sum_ += value;
    squares_ += value.cwiseAbs2();
    variance_ += std_dev.cwiseAbs2();
    ++runs_;
  }

  // Per parameter: reported sd over observed spread.
  Eigen::VectorXd ratios() const {
    const double r = runs_;
    const Eigen::VectorXd mean = sum_ / r;
    const Eigen::VectorXd spread =
        ((squares_ - r * mean.cwiseAbs2()) / (r - 1)).cwiseMax(0).cwiseSqrt();
    return (variance_ / r).cwiseSqrt().cwiseQuotient(spread.cwiseMax(1e-300));
  }

  // Per parameter: reported sd over the root-mean-square error from `truth` (bias included).
  Eigen::VectorXd error_ratios(const Eigen::VectorXd& truth) const {
    const double r = runs_;
    const Eigen::VectorXd mse = (squares_ - 2 * truth.cwiseProduct(sum_)) / r + truth.cwiseAbs2();
    return (variance_ / r).cwiseSqrt().cwiseQuotient(mse.cwiseMax(1e-300).cwiseSqrt());
  }

  static double median(const Eigen::VectorXd& v) {
    std::vector<double> sorted(v.data(), v.data() + v.size());
    std::sort(sorted.begin(), sorted.end());
    return sorted[sorted.size() / 2];
  }

  // Prints the median, smallest and largest ratio and checks them: the median within
  // [0.8, 1.25] (the 20 %), every parameter within [lo, hi]. The bounds per parameter:
  // with 200 runs each observed spread is off by 5 % (1 sd), and the largest of 61 such errors
  // is about 2.5 sd, 13 %; [0.65, 1.5] leaves room for the estimator's own bias on the few
  // weakest parameters. `upper` false: only the lower bounds (a conservative sd passes).
  // `median_lo` below 0.8 only where a known shortfall is stated.
  void expect_covered(const std::string& what, double lo = 0.65, double hi = 1.5, bool upper = true,
                      double median_lo = 0.8) const {
    if (!upper) hi = INFINITY;
    Eigen::VectorXd r = ratios();
    std::vector<double> sorted(r.data(), r.data() + r.size());
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    std::cout << "[ monte carlo ] " << what << ": " << runs_ << " runs, reported sd / spread: "
              << "median " << median << ", min " << sorted.front() << ", max " << sorted.back()
              << "\n";
    EXPECT_GE(median, median_lo) << what;
    if (upper) {
      EXPECT_LE(median, 1.25) << what;
    }
    for (Eigen::Index k = 0; k < r.size(); ++k) {
      EXPECT_TRUE(r[k] >= lo && r[k] <= hi)
          << what << ": parameter " << k << " reported sd / spread " << r[k];
    }
  }

 private:
  Eigen::VectorXd sum_, squares_, variance_;
  int runs_ = 0;
};

}  // namespace modelgen::test
