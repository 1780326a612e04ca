// The projection method (PM) of Forssell & Ljung, as Bona & Curatella use it on a robot under
// its controller (section 2.2, eq. 10-12; section 3.4): (1) the torque command projected on
// the references by a least-squares non-causal FIR, u^ = S^ r (eq. 10-11), which keeps the part
// of the torque the reference explains and drops the part the loop makes of the noise; (2) the
// base parameters fitted to the projected torque u^ as open-loop data (eq. 12).
//
// The FIR is linear. A multi-joint nonlinear robot makes torque at sums and products of the
// reference's frequencies that no linear filter of the references reproduces: the projection
// discards it along with the noise, and the estimate is biased. Bona moved one joint at a
// time; projection_method() reports the discarded fraction so the user can tell.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen {

/// The references on the grid the torque is fitted on, delayed by k grid samples for
/// k = -max_lag..max_lag (negative k: ahead of the torque, the non-causal half of eq. 10).
struct LaggedReferences {
  int max_lag = 0;
  /// by_lag[k + max_lag]: rows x references, r(t - k) on every row t of the grid.
  std::vector<Eigen::MatrixXd> by_lag;
  /// The constant regressor on the same grid (a column of ones, filtered as the rest).
  Eigen::VectorXd constant;
  const Eigen::MatrixXd& at(int k) const { return by_lag[static_cast<std::size_t>(k + max_lag)]; }
};

/// The decorrelation test that chooses M1 = M2 = M (section 2.2: "M1 and M2 are chosen to
/// avoid correlation between u^ and u~"). Least squares makes u~ = u - u^ orthogonal to every
/// regressor, u^ included, by construction: the correlation Bona reports (2.9e-14) is that
/// rounding, and the test that can fail is the one of Ljung's residual analysis, the normalised
/// cross-correlation of u~_j with every moving reference r_i(t - k) for M < |k| <= 2M + 10
/// (within M it is zero by construction): it finds what the FIR left in u~ that the references
/// explain. One white-noise correlation of N samples stays within 2.58 / sqrt(N) with 99 %
/// probability; of m such correlations (channels x moving references x 2 (M + 10) lags),
/// though, one crosses that band more often than not. The band is therefore the one all m stay
/// within with 99 % probability (Sidak: each at the 1 - 0.01 / m level, computed for the m of
/// the test; about 3.8 / sqrt(N) for m = 74, 4.4 / sqrt(N) for m = 1000), so that white
/// residuals pass 99 times in 100 whatever M.
struct DecorrelationTest {
  int window = 0;          ///< largest |k| tested
  long long tested = 0;    ///< correlations tested (m)
  double worst = 0;        ///< largest |correlation| over channels, references and lags
  double band = 0;         ///< the 99 % band of the largest of m white-noise correlations
  double single_band = 0;  ///< 2.58 / sqrt(N), the band of one correlation
  int worst_channel = -1, worst_reference = -1, worst_lag = 0;
  bool passed() const { return worst <= band; }
};

/// Stage 1 on one grid: u (rows x channels) fitted by the FIR of lags -M..M of every reference
/// of `references` that moves, plus a constant.
struct FirProjection {
  int lags = 0;  ///< M
  /// The references whose lags are regressors (a held reference is a constant: its lags are
  /// the constant column again).
  std::vector<int> moving;
  /// Rows: the constant, then for each moving reference (in `moving` order) its lags -M..M;
  /// one column per channel. Minimum-norm where the regressors are dependent (a reference of
  /// H harmonics spans 2H dimensions, whatever the lags).
  Eigen::MatrixXd coefficients;
  /// Least-squares standard deviations of the coefficients (sigma^2 (Phi^T Phi)^-1 per
  /// channel); NaN when the regressors are dependent.
  Eigen::MatrixXd coefficient_std;
  Eigen::MatrixXd projected;         ///< u^ (eq. 11), rows x channels
  Eigen::VectorXd residual_squares;  ///< ||u - u^||^2 per channel
  Eigen::Index rank = 0;             ///< of the regressor (its independent columns)
  DecorrelationTest test;
  bool full_rank = true;
};

/// The FIR coefficients at most one in kMinRowsPerCoefficient rows: more would fit the noise
/// (each coefficient removes a share 1/N of it from u~, and the discarded fraction would
/// understate what the projection throws away).
inline constexpr int kMinRowsPerCoefficient = 10;

/// The ladder of M the decorrelation test tries, smallest first.
inline constexpr int kFirLagLadder[] = {0, 1, 2, 4, 8, 16, 32};

/// The values of kFirLagLadder a FIR from `moving` references and a constant can have on
/// `rows` rows (kMinRowsPerCoefficient each) and `max_lag` lags of the references can test.
std::vector<int> fir_lag_ladder(Eigen::Index rows, Eigen::Index moving, int max_lag);

/// The lags the test of M needs the references to reach: 2M + 10.
int decorrelation_window(int lags);

/// Stage 1 on several records with one M: the first of `ladder` whose FIR passes the
/// decorrelation test on every record and whose residual the next M of the ladder does not
/// lower significantly (on a channel of a record, by more than the 99 % point of what its extra
/// coefficients take of white noise: the decorrelation test alone has little power when u~ is
/// mostly torque no linear filter makes), else the last.
struct FirChoice {
  std::vector<FirProjection> fits;  ///< per record
  int lags = 0;
  bool decorrelated = false;
  DecorrelationTest test;                     ///< the worst record's
  std::vector<std::pair<int, double>> tried;  ///< per M tried: its largest |correlation|
};
FirChoice choose_fir_projection(const std::vector<Eigen::MatrixXd>& u,
                                const std::vector<LaggedReferences>& references,
                                const std::vector<int>& ladder);

/// Fits u by the FIR of lags -M..M of `references` (which must reach lag 2M + 10 for the test)
/// and a constant. Throws EstimationError for sizes that do not match, M < 0, lags the
/// references do not reach, or fewer than kMinRowsPerCoefficient rows per coefficient.
FirProjection fit_fir_projection(const Eigen::MatrixXd& u, const LaggedReferences& references,
                                 int lags);

/// The references of a prepared closed-loop record on the rows identify() fits: raw reference
/// rows first_row .. first_row + samples - 1 (the prepared rows), delayed by k * decimation raw
/// samples, paired as the torques were (torque_hold: the mean of a sample and the one before,
/// PreparationOptions::torque_hold), then decimated by decimate_interior() exactly as
/// identify() decimates the torque; the constant likewise. Rows the delay takes outside the
/// raw record take its end value (a robot waiting at the start and end of its trajectory).
LaggedReferences lagged_references(const Eigen::MatrixXd& qr, Eigen::Index first_row,
                                   Eigen::Index samples, int decimation, bool torque_hold,
                                   int max_lag);

/// One prepared closed-loop record (joint side).
struct ProjectionRecord {
  Trajectory prepared;  ///< as prepare_experiment() made it; its rows are raw rows first_row...
  int decimation = 1;   ///< the parallel decimation factor identify() applies
  bool torque_hold = false;  ///< the prepared torques were paired (PreparationOptions)
  Eigen::MatrixXd qr;        ///< the reference of every raw sample (samples x dof)
  Eigen::Index first_row = 0;
};

struct ProjectionOptions {
  /// M forced; unset: choose_fir_projection() on fir_lag_ladder() (the smallest M that passes
  /// its tests on every record, or the largest the rows allow when none does).
  std::optional<int> fir_lags;
  std::vector<double> min_speed;  ///< per joint, for stage 2 (IdentifyOptions::min_speed)
};

/// Stage 1 of the projection method on every record.
struct ProjectedRecords {
  /// Per record, u^ at the raw rate on the prepared rows (the FIR applied to the delayed raw
  /// references): identify()'s decimation of it gives the fitted u^ on its rows exactly, since
  /// decimation is linear.
  std::vector<Eigen::MatrixXd> projected;
  int lags = 0;               ///< M
  bool forced = false;        ///< M came from ProjectionOptions::fir_lags
  bool decorrelated = false;  ///< the chosen M passed the test on every record
  DecorrelationTest test;     ///< the worst record's test at the chosen M
  /// ||u - u^|| / ||u|| per joint and over all joints, on the decimated rows of every record.
  Eigen::VectorXd discarded;
  double discarded_total = 0;
  /// Per M tried: its worst correlation (the ladder's search; one entry when forced).
  std::vector<std::pair<int, double>> tried;
};

/// Stage 1 on closed-loop records: fit_fir_projection on lagged_references of each, with one M
/// for all (forced, or by choose_fir_projection on fir_lag_ladder). Throws EstimationError for
/// records that do not have `dof` joints or whose prepared rows are not within the reference's,
/// and as the FIR fit does.
ProjectedRecords project_records(int dof, const std::vector<ProjectionRecord>& records,
                                 const std::optional<int>& fir_lags);

struct ProjectionIdentification {
  ProjectedRecords stage1;
  /// Stage 2: IDIM-WLS on the projected torques. Its rms and relative errors compare the
  /// model with u^, not with the measured torque.
  Identification id;
};

/// Stage 2 (eq. 12): IDIM-WLS (identify()) on `records` with each torque replaced by
/// stage1.projected, leaving out the samples slower than `min_speed` (per joint, empty: none).
/// Throws EstimationError as identify() does (a single record moving one joint is rank
/// deficient: the records of every joint go in together).
Identification identify_projected(const IdentificationModel& model,
                                  const std::vector<ProjectionRecord>& records,
                                  const ProjectedRecords& stage1,
                                  const std::vector<double>& min_speed = {});

/// The projection method on closed-loop records: stage 1 per record (fit_fir_projection on
/// lagged_references, the same M for all), stage 2 identify() with IDIM-WLS, each record's
/// torque replaced by u^ at the raw rate (the FIR applied to the delayed raw references, so
/// that identify()'s decimation of it gives the fitted u^ on its rows exactly).
/// Throws EstimationError for records that do not fit the model, and as the stages do.
ProjectionIdentification projection_method(const IdentificationModel& model,
                                           const std::vector<ProjectionRecord>& records,
                                           const ProjectionOptions& options = {});

}  // namespace modelgen
