// Standard deviations of a (weighted) least-squares estimate whose equation errors are
// correlated from row to row, where eq. 17-18 of Gautier & Briot (s^2 (W^T W)^-1, white
// errors) are too small: a sandwich covariance (A^T A)^-1 S (A^T A)^-1 on the weighted rows A,
// S the covariance of the score A^T e estimated from the residuals (issue 31).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen::detail {

/// One group of equations (a joint of an experiment), rows in time order, already weighted.
struct ResidualGroup {
  Eigen::MatrixXd X;  ///< rows x b (the regressor, or the instruments for IV)
  Eigen::VectorXd r;  ///< the residuals of those rows
  /// >= 0: the rows are one period whose noise lies on harmonics 0..H only (the periodic route
  /// keeps the torques up to a harmonic); -1: a stationary noise sequence.
  int harmonics = -1;
};

struct SandwichCovariance {
  Eigen::MatrixXd meat;     ///< S, b x b
  std::string description;  ///< which estimator and why, for the user; empty: none was needed
};

/// Whether a stationary residual sequence is correlated enough to need the sandwich, from its
/// lag-1 autocorrelation rho, and the Bartlett bandwidth for it (Andrews' AR(1) rule).
struct Correlation {
  double rho = 0;
  bool significant = false;  ///< |rho| > 3 / sqrt(rows) and |rho| > 0.05
  int bandwidth = 0;         ///< L, lags 1..L weighted 1 - l / (L + 1); 0 when not significant
};

/// From sum r_t r_{t-1} and sum r_t^2 over `rows` rows in `sequences` separate sequences.
Correlation residual_correlation(double lag_products, double squares, Eigen::Index rows,
                                 Eigen::Index sequences);

/// The Bartlett-weighted sum of a score sequence's lagged products, sum_|l|<=L (1 - |l| / (L + 1))
/// sum_t g_t g_(t-l)^T, by overlapping batch means: the outer products of the sums of every L + 1
/// consecutive scores, divided by L + 1, weigh lag l by exactly L + 1 - |l| (Welch 1987). The rows
/// are fed one at a time, so a record too long to hold as a matrix costs a ring of L + 1 scores,
/// and the lags cost nothing: O(rows b^2) for any L.
class BartlettScoreSum {
 public:
  BartlettScoreSum(Eigen::Index b, int bandwidth);
  void add(const Eigen::Ref<const Eigen::VectorXd>& score);
  /// The sum over the rows fed so far (at least L + 1), the windows cut by the ends made up for.
  [[nodiscard]] Eigen::MatrixXd meat() const;
  [[nodiscard]] Eigen::Index rows() const { return rows_; }

 private:
  Eigen::Index window_;
  Eigen::MatrixXd recent_;  ///< ring of the last window_ scores
  Eigen::VectorXd sum_;     ///< their sum
  Eigen::MatrixXd block_;   ///< window sums waiting for one matrix product
  Eigen::Index filled_ = 0, rows_ = 0;
  Eigen::MatrixXd meat_;
};

/// The coefficient an AR(1) prewhitening takes out of a residual sequence (Andrews & Monahan
/// 1992), from its autocovariances (sums of products over the rows) at lags 0, 1, K and K + 1:
/// (g1 - g(K+1)) / (g0 - gK), clamped to [0, 0.97]; for an AR(1) rho, whatever K. Not g1 / g0: a
/// fit takes the noise on its regressor's slow columns out of the residual, which lowers the
/// autocovariances at lags much shorter than those columns' periods by about the same amount;
/// the differences keep the noise's own. K about the correlation length (prewhitening_lag):
/// K = 1 would divide by g0 - g1, the small power of the changes, and leave the coefficient
/// +-0.02 on 10 000 rows of rho 0.95 (measured), a factor 2 on 1 / (1 - rho)^2. 0 when not
/// positive.
double prewhitening_coefficient(double g0, double g1, double gk, double gk1);

/// K for prewhitening_coefficient from the lag-1 autocorrelation rho: 1 / (1 - rho) rounded
/// up, at least 1 and at most `rows` / 20 (and 1 without positive rho).
Eigen::Index prewhitening_lag(double rho, Eigen::Index rows);

/// The meat of a sequence summed while streaming (identify_covariance.cpp's undecimated rows).
struct StreamedMeat {
  Eigen::MatrixXd meat;
  Eigen::Index rows = 0;
  Correlation correlation;  ///< of the residuals: whether the sandwich is needed
  double whiten = 0;        ///< prewhitening coefficient the scores were summed with, or 0
  Correlation whitened;     ///< of the prewhitened residuals (their bandwidth, their rows' worth)
};

/// S from the groups' residuals (and any sequences summed while streaming), or an empty
/// description when none needs it (no periodic group, no streamed meat, and the in-memory
/// groups' pooled lag-1 autocorrelation is not significant, see Correlation).
/// Periodic groups: by the lines of the DFT (circular noise, one variance per line estimated
/// by |R_l|^2 / N). Other groups: Newey-West with the Bartlett kernel, its bandwidth from the
/// residuals' lag-1 autocorrelation by Andrews' AR(1) rule. Scaled by M / (M - b), M the
/// degrees of freedom of the noise (2 H + 1 per periodic group, the rows of the others, as
/// many independent rows as they are worth when correlated: rows (1 - rho) / (1 + rho)), for
/// the b of them the fit takes.
SandwichCovariance score_covariance(const std::vector<ResidualGroup>& groups,
                                    const std::vector<StreamedMeat>& streamed = {});

/// The sandwich (A^T A)^-1 S (A^T A)^-1 from (A^T A)^-1 and S.
Eigen::MatrixXd sandwich(const Eigen::MatrixXd& AtA_inverse, const Eigen::MatrixXd& meat);

}  // namespace modelgen::detail
