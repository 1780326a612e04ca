// The projection method: a least-squares non-causal FIR from the references to the torque on
// the decimated rows (Bona & Curatella eq. 10-11, fitted in fir_projection.cpp), its order by
// a decorrelation test, then IDIM-WLS on the projected torque (eq. 12).

#include "modelgen/closed_loop/projection_method.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/signal/decimation.hpp"
#include "runtime/src/closed_loop/fir_projection.hpp"

namespace modelgen {

namespace {

using detail::kHeld;

// Lags the test looks beyond 2M: u~ left correlated with the references shows at the lags
// just past the FIR's support.
constexpr int kTestMargin = 10;

// Raw reference rows first_row + s - shift, s = 0..samples-1, paired as held torques were
// (the mean of a sample and the one before) when `hold`; rows outside the record take its
// end value.
Eigen::MatrixXd shifted_reference(const Eigen::MatrixXd& qr, Eigen::Index first_row,
                                  Eigen::Index samples, bool hold, Eigen::Index shift) {
  const Eigen::Index last = qr.rows() - 1;
  auto row = [&](Eigen::Index r) { return qr.row(std::clamp<Eigen::Index>(r, 0, last)); };
  Eigen::MatrixXd out(samples, qr.cols());
  for (Eigen::Index s = 0; s < samples; ++s) {
    const Eigen::Index r = first_row + s - shift;
    out.row(s) =
        hold ? Eigen::RowVectorXd(0.5 * (row(r) + row(r - 1))) : Eigen::RowVectorXd(row(r));
  }
  return out;
}

// The one-sided 99 % point of chi-square with `dof` degrees of freedom (Wilson-Hilferty).
double chi_square_99(double dof) {
  const double z = 2.326, a = 2 / (9 * dof);
  return dof * std::pow(1 - a + z * std::sqrt(a), 3);
}

// Whether `larger` (more lags) lowers some channel's residual by more than its extra
// coefficients take of white noise: (RSS_s - RSS_l) / (RSS_l / (N - p_l)) above the 99 % point
// of chi-square with p_l - p_s degrees of freedom.
bool explains_more(const FirProjection& smaller, const FirProjection& larger) {
  const Eigen::Index rows = larger.residual_squares.size() ? larger.projected.rows() : 0;
  const Eigen::Index extra = larger.rank - smaller.rank;
  if (extra <= 0 || rows <= larger.rank) return false;
  for (Eigen::Index j = 0; j < larger.residual_squares.size(); ++j) {
    const double variance = larger.residual_squares[j] / static_cast<double>(rows - larger.rank);
    if (!(variance > 0)) continue;
    const double drop = smaller.residual_squares[j] - larger.residual_squares[j];
    if (drop / variance > chi_square_99(static_cast<double>(extra))) return true;
  }
  return false;
}

// Each record's torques on its decimated rows, after checking the record against the robot.
std::vector<Eigen::MatrixXd> decimated_torques(int n,
                                               const std::vector<ProjectionRecord>& records) {
  std::vector<Eigen::MatrixXd> torques;  // u on each record's decimated rows
  for (std::size_t e = 0; e < records.size(); ++e) {
    const ProjectionRecord& r = records[e];
    const std::string name = r.prepared.source.empty()
                                 ? "closed-loop record " + std::to_string(e + 1)
                                 : r.prepared.source;
    const Eigen::Index samples = r.prepared.t.size();
    if (r.qr.cols() != n || r.prepared.tau.cols() != n || r.prepared.tau.rows() != samples) {
      throw EstimationError(name + ": the record does not have the robot's " + std::to_string(n) +
                            " joints (reference or torques)");
    }
    if (r.first_row < 0 || r.first_row + samples > r.qr.rows() || samples < 2) {
      throw EstimationError(name + ": the prepared samples are not within the reference's");
    }
    if (r.decimation < 1) throw EstimationError(name + ": decimation factor below 1");
    torques.push_back(decimate_interior(r.prepared.tau, r.decimation));
  }
  return torques;
}

// The most references that move in one record (on its prepared samples).
Eigen::Index most_moving_references(int n, const std::vector<ProjectionRecord>& records) {
  Eigen::Index moving = 0;
  for (const ProjectionRecord& r : records) {
    const Eigen::MatrixXd used = r.qr.middleRows(r.first_row, r.prepared.t.size());
    Eigen::Index count = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double range = used.col(i).maxCoeff() - used.col(i).minCoeff();
      if (range > kHeld * std::max(1.0, used.col(i).cwiseAbs().maxCoeff())) ++count;
    }
    moving = std::max(moving, count);
  }
  return moving;
}

// The M to try: the one given, if `fewest` rows allow it, else the ladder they allow.
std::vector<int> lags_to_try(const std::optional<int>& fir_lags, Eigen::Index fewest,
                             Eigen::Index moving) {
  std::vector<int> ladder;
  if (fir_lags) {
    if (*fir_lags < 0) {
      throw EstimationError("the FIR's lags M must be >= 0, not " + std::to_string(*fir_lags));
    }
    // Checked before the lagged references are built: their 4M + 21 shifted copies of a
    // reference would take memory (and 2M + 10 overflow) long before the fit could refuse M.
    const Eigen::Index coefficients = 1 + moving * (2 * static_cast<Eigen::Index>(*fir_lags) + 1);
    if (fewest < kMinRowsPerCoefficient * coefficients) {
      // The largest M with 1 + moving (2M + 1) coefficients of kMinRowsPerCoefficient rows.
      const Eigen::Index largest =
          moving == 0 ? -1 : (fewest / kMinRowsPerCoefficient - 1 - moving) / (2 * moving);
      throw EstimationError("the projection method: M = " + std::to_string(*fir_lags) +
                            " lags need " + std::to_string(kMinRowsPerCoefficient * coefficients) +
                            " decimated rows (" + std::to_string(kMinRowsPerCoefficient) +
                            " per coefficient), the records have " + std::to_string(fewest) +
                            (largest < 0 ? std::string("; record longer or decimate less")
                                         : "; choose M <= " + std::to_string(largest)));
    }
    ladder.push_back(*fir_lags);
  } else {
    ladder = fir_lag_ladder(fewest, moving, std::numeric_limits<int>::max());
    if (ladder.empty()) {
      throw EstimationError("the projection method: " + std::to_string(fewest) +
                            " decimated rows are too few for a FIR from " + std::to_string(moving) +
                            " moving references (" + std::to_string(kMinRowsPerCoefficient) +
                            " rows per coefficient); record longer or decimate less");
    }
  }
  return ladder;
}

// u^ at the raw rate: decimation is linear, so identify()'s decimation of it is the fitted
// u^ on the same rows.
Eigen::MatrixXd projected_at_raw_rate(const ProjectionRecord& r, const FirProjection& fir) {
  const Eigen::Index samples = r.prepared.t.size();
  Eigen::MatrixXd u_hat = Eigen::MatrixXd::Ones(samples, 1) * fir.coefficients.row(0);
  Eigen::Index row = 1;
  for (const int i : fir.moving) {
    for (int k = -fir.lags; k <= fir.lags; ++k, ++row) {
      const Eigen::VectorXd delayed = shifted_reference(r.qr, r.first_row, samples, r.torque_hold,
                                                        static_cast<Eigen::Index>(k) * r.decimation)
                                          .col(i);
      u_hat += delayed * fir.coefficients.row(row);
    }
  }
  return u_hat;
}

}  // namespace

int decorrelation_window(int lags) { return 2 * lags + kTestMargin; }

std::vector<int> fir_lag_ladder(Eigen::Index rows, Eigen::Index moving, int max_lag) {
  std::vector<int> out;
  for (const int lags : kFirLagLadder) {
    if (rows >= kMinRowsPerCoefficient * (1 + moving * (2 * lags + 1)) &&
        decorrelation_window(lags) <= max_lag) {
      out.push_back(lags);
    }
  }
  return out;
}

FirChoice choose_fir_projection(const std::vector<Eigen::MatrixXd>& u,
                                const std::vector<LaggedReferences>& references,
                                const std::vector<int>& ladder) {
  if (ladder.empty() || u.size() != references.size() || u.empty()) {
    throw EstimationError("FIR projection: no M to try, or not one reference set per record");
  }
  auto fit_all = [&](int lags) {
    std::vector<FirProjection> fits;
    for (std::size_t e = 0; e < u.size(); ++e) {
      fits.push_back(fit_fir_projection(u[e], references[e], lags));
    }
    return fits;
  };
  FirChoice out;
  std::vector<FirProjection> next = fit_all(ladder.front());
  for (std::size_t l = 0; l < ladder.size(); ++l) {
    std::vector<FirProjection> fits = std::move(next);
    bool passed = true;
    DecorrelationTest worst;
    for (std::size_t e = 0; e < fits.size(); ++e) {
      const DecorrelationTest& test = fits[e].test;
      passed = passed && test.passed();
      if (e == 0 || test.worst - test.band > worst.worst - worst.band) worst = test;
    }
    // The decorrelation test has little power when u~ is mostly torque no linear filter of the
    // references makes (a multi-joint robot's): measured on the TX-40, M = 0 passes it with
    // 57 % of the torque left in u~ where M = 1 leaves 22 %. So M must also explain as much as
    // the next M of the ladder, within what the next M's extra coefficients take of white
    // noise (an F test at 99 %, per channel and record).
    if (l + 1 < ladder.size()) {
      next = fit_all(ladder[l + 1]);
      for (std::size_t e = 0; e < fits.size() && passed; ++e) {
        passed = !explains_more(fits[e], next[e]);
      }
    }
    out.tried.emplace_back(ladder[l], worst.worst);
    out.lags = ladder[l];
    out.test = worst;
    out.fits = std::move(fits);
    out.decorrelated = passed;
    if (passed) break;
  }
  return out;
}

LaggedReferences lagged_references(const Eigen::MatrixXd& qr, Eigen::Index first_row,
                                   Eigen::Index samples, int decimation, bool torque_hold,
                                   int max_lag) {
  if (max_lag < 0 || decimation < 1 || samples < 2 || first_row < 0 ||
      first_row + samples > qr.rows()) {
    throw EstimationError("lagged references: rows " + std::to_string(first_row) + " to " +
                          std::to_string(first_row + samples) + " are not within the " +
                          std::to_string(qr.rows()) + " reference samples");
  }
  LaggedReferences out;
  out.max_lag = max_lag;
  for (int k = -max_lag; k <= max_lag; ++k) {
    out.by_lag.push_back(
        decimate_interior(shifted_reference(qr, first_row, samples, torque_hold,
                                            static_cast<Eigen::Index>(k) * decimation),
                          decimation));
  }
  out.constant = decimate_interior(Eigen::MatrixXd::Ones(samples, 1), decimation).col(0);
  return out;
}

ProjectedRecords project_records(int n, const std::vector<ProjectionRecord>& records,
                                 const std::optional<int>& fir_lags) {
  if (records.empty()) throw EstimationError("the projection method needs a record");
  const std::vector<Eigen::MatrixXd> torques = decimated_torques(n, records);

  // The M the rows allow: every moving reference's 2M + 1 lags and the constant, at least
  // kMinRowsPerCoefficient rows each.
  Eigen::Index fewest = std::numeric_limits<Eigen::Index>::max();
  for (const Eigen::MatrixXd& u : torques) fewest = std::min(fewest, u.rows());
  const std::vector<int> ladder = lags_to_try(fir_lags, fewest, most_moving_references(n, records));
  std::vector<LaggedReferences> references;
  for (const ProjectionRecord& r : records) {
    references.push_back(lagged_references(r.qr, r.first_row, r.prepared.t.size(), r.decimation,
                                           r.torque_hold, decorrelation_window(ladder.back())));
  }
  FirChoice choice = choose_fir_projection(torques, references, ladder);
  ProjectedRecords out;
  out.forced = fir_lags.has_value();
  out.lags = choice.lags;
  out.decorrelated = choice.decorrelated;
  out.test = choice.test;
  out.tried = choice.tried;
  const std::vector<FirProjection>& chosen = choice.fits;

  // Discarded fraction on the decimated rows; u^ at the raw rate.
  Eigen::VectorXd lost = Eigen::VectorXd::Zero(n), total = Eigen::VectorXd::Zero(n);
  for (std::size_t e = 0; e < records.size(); ++e) {
    lost += (torques[e] - chosen[e].projected).colwise().squaredNorm().transpose();
    total += torques[e].colwise().squaredNorm().transpose();
    out.projected.push_back(projected_at_raw_rate(records[e], chosen[e]));
  }
  out.discarded = (lost.array() / total.array().max(1e-300)).sqrt();
  out.discarded_total = std::sqrt(lost.sum() / std::max(total.sum(), 1e-300));
  return out;
}

Identification identify_projected(const IdentificationModel& model,
                                  const std::vector<ProjectionRecord>& records,
                                  const ProjectedRecords& stage1,
                                  const std::vector<double>& min_speed) {
  if (stage1.projected.size() != records.size()) {
    throw EstimationError("the projection method: stage 1 has " +
                          std::to_string(stage1.projected.size()) + " records, stage 2 " +
                          std::to_string(records.size()));
  }
  std::vector<Trajectory> projected;
  IdentifyOptions options;
  options.min_speed = min_speed;
  for (std::size_t e = 0; e < records.size(); ++e) {
    Trajectory x = records[e].prepared;
    x.tau = stage1.projected[e];
    projected.push_back(std::move(x));
    options.decimation.push_back(records[e].decimation);
  }
  // Bona fits eq. 12 by maximum likelihood. With independent Gaussian torque noise of one
  // variance per joint, the likelihood of the torques is maximal at the weighted least squares
  // of eq. 20 (each joint weighted by the inverse of its noise's standard deviation), which is
  // what IDIM-WLS computes.
  return identify(model, projected, Method::kWls, options);
}

ProjectionIdentification projection_method(const IdentificationModel& model,
                                           const std::vector<ProjectionRecord>& records,
                                           const ProjectionOptions& options) {
  ProjectionIdentification out;
  out.stage1 = project_records(model.dof(), records, options.fir_lags);
  out.id = identify_projected(model, records, out.stage1, options.min_speed);
  return out;
}

}  // namespace modelgen
