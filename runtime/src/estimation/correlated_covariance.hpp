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

/// S from the groups' residuals, or an empty description when no group needs it (no periodic
/// group, and the residuals' pooled lag-1 autocorrelation rho is within 3 / sqrt(rows) of 0
/// or |rho| <= 0.05).
/// Periodic groups: by the lines of the DFT (circular noise, one variance per line estimated
/// by |R_l|^2 / N). Other groups: Newey-West with the Bartlett kernel, its bandwidth from the
/// residuals' lag-1 autocorrelation by Andrews' AR(1) rule. Scaled by M / (M - b), M the
/// degrees of freedom of the noise (2 H + 1 per periodic group, the rows of the others), for
/// the b of them the fit takes.
SandwichCovariance score_covariance(const std::vector<ResidualGroup>& groups);

/// The sandwich (A^T A)^-1 S (A^T A)^-1 from (A^T A)^-1 and S.
Eigen::MatrixXd sandwich(const Eigen::MatrixXd& AtA_inverse, const Eigen::MatrixXd& meat);

}  // namespace modelgen::detail
