// The two data-preparation routes, chosen by options and by what the file holds.

#include "modelgen/signal/prepare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "modelgen/signal/differentiation.hpp"
#include "modelgen/signal/filter_plan.hpp"
#include "modelgen/signal/fourier_fit.hpp"
#include "modelgen/signal/noise_coupling.hpp"
#include "modelgen/signal/period.hpp"
#include "modelgen/signal/preparation_checks.hpp"
#include "modelgen/signal/reversal_mask.hpp"
#include "modelgen/signal/reversal_speed.hpp"
#include "modelgen/signal/sampling.hpp"

namespace modelgen {

namespace {

// Filter edges dropped after the position filter, in periods of its cut-off frequency.
constexpr double kEdgePeriods = 3.0;

std::string number(double value, int digits = 4) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

// The nominal sample time of jittered time stamps: their mean step, unless samples are missing
// (gaps make the mean more than 1% longer than the median step), then the median step.
double nominal_step(const Eigen::VectorXd& t) {
  std::vector<double> steps(t.size() - 1);
  for (Eigen::Index k = 0; k + 1 < t.size(); ++k) steps[k] = t[k + 1] - t[k];
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double median = steps[steps.size() / 2];
  const double mean = (t[t.size() - 1] - t[0]) / static_cast<double>(t.size() - 1);
  return std::abs(mean - median) <= 0.01 * median ? mean : median;
}

// A command held over [t_k, t_k+1) acts, within the band, as the sampled signal delayed by half
// a sample: at t_k it is best the mean of tau_k-1 and tau_k (linear interpolation half a sample
// back); the first sample is extrapolated from the first two.
void pair_held_torques(Trajectory& x) {
  const Eigen::Index n = x.tau.rows();
  if (n < 2) return;
  const Eigen::RowVectorXd first = 1.5 * x.tau.row(0) - 0.5 * x.tau.row(1);
  for (Eigen::Index k = n - 1; k > 0; --k) x.tau.row(k) = 0.5 * (x.tau.row(k) + x.tau.row(k - 1));
  x.tau.row(0) = first;
}

// Same test as uniform_sample_time: every sample within 1% of dt of the uniform grid.
bool is_uniform(const Eigen::VectorXd& t) {
  const Eigen::Index n = t.size();
  const double dt = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (std::abs(t[k] - (t[0] + static_cast<double>(k) * dt)) > 0.01 * dt) return false;
  }
  return true;
}


// The smooth motion of `prepared` (q, dq, ddq) at the time stamps of `target`, by linear
// interpolation; times outside take the nearest end. With period > 0, times are first
// wrapped into the prepared period (the periodic route's one averaged period).
void motion_at_samples_of(const Trajectory& prepared, double period, Trajectory& target) {
  const Eigen::Index m = prepared.t.size(), n = target.t.size();
  target.dq.resize(n, target.q.cols());
  target.ddq.resize(n, target.q.cols());
  const double first = prepared.t[0];
  for (Eigen::Index s = 0; s < n; ++s) {
    double t = target.t[s];
    if (period > 0) t = first + std::fmod(std::fmod(t - first, period) + period, period);
    const Eigen::Index k = std::clamp<Eigen::Index>(
        std::upper_bound(prepared.t.data(), prepared.t.data() + m, t) - prepared.t.data() - 1, 0,
        m - 2);
    const double w = m < 2 ? 0 : std::clamp((t - prepared.t[k]) / (prepared.t[k + 1] - prepared.t[k]), 0.0, 1.0);
    const Eigen::Index k1 = std::min(k + 1, m - 1);
    target.q.row(s) = (1 - w) * prepared.q.row(k) + w * prepared.q.row(k1);
    target.dq.row(s) = (1 - w) * prepared.dq.row(k) + w * prepared.dq.row(k1);
    target.ddq.row(s) = (1 - w) * prepared.ddq.row(k) + w * prepared.ddq.row(k1);
  }
  target.has_velocity = true;
}

PreparedExperiment prepare_joint_side(Trajectory raw, const PreparationOptions& options,
                                      bool keep_edges);

// Drops the first `rows` samples of every column the record has.
void drop_leading_rows(Trajectory& raw, Eigen::Index rows) {
  const Eigen::Index left = raw.t.size() - rows;
  for (Eigen::MatrixXd* m : {&raw.q, &raw.dq, &raw.ddq, &raw.tau, &raw.qr}) {
    if (m->rows() == raw.t.size()) *m = m->bottomRows(left).eval();
  }
  raw.t = raw.t.tail(left).eval();
}

// Drops the first `periods` whole periods of a uniformly sampled record (its start transient)
// and says so for the summary. Throws DataError when fewer than two periods would be left.
std::string skip_whole_periods(Trajectory& raw, double period, int periods) {
  const double dt = uniform_sample_time(raw);
  const auto skip = static_cast<Eigen::Index>(std::lround(periods * period / dt));
  const Eigen::Index left = raw.t.size() - skip;
  if (left < 2 * static_cast<Eigen::Index>(std::lround(period / dt))) {
    throw DataError(raw.source + ": error: leaving out the first " + std::to_string(periods) +
                    " period(s) of " + number(period, 6) + " s (--skip-periods) leaves " +
                    number(std::max<Eigen::Index>(left, 0) * dt, 6) +
                    " s, fewer than the 2 whole periods averaging needs");
  }
  drop_leading_rows(raw, skip);
  return "first " + std::to_string(periods) + " period(s) (" + std::to_string(skip) +
         " samples) left out as the start transient; ";
}

}  // namespace

PreparedExperiment prepare_experiment(Trajectory raw, const DriveChain& drive,
                                      const PreparationOptions& options) {
  to_joint_side(raw, drive, options.side);
  if (options.torque_hold) pair_held_torques(raw);
  const std::string held = options.torque_hold
                               ? "torque commands held over each sample, paired half a sample "
                                 "later; "
                               : "";
  if (!options.every_sample) {
    PreparedExperiment out = prepare_joint_side(std::move(raw), options, false);
    out.summary = held + out.summary;
    return out;
  }
  // One row per input sample: the motion as the route makes it (filtered positions and their
  // derivatives, or the Fourier series), taken back to the file's own time stamps, with the
  // torques as measured; nothing decimated.
  PreparedExperiment out = prepare_joint_side(raw, options, true);
  const double period = options.periodic ? out.data.t[out.data.t.size() - 1] - out.data.t[0] +
                                               (out.data.t[1] - out.data.t[0])
                                         : 0.0;
  if (options.periodic && options.skip_periods > 0) {
    // The start transient the average left out is left out of the comparison too.
    const double start =
        raw.t[0] + options.skip_periods * period - 0.5 * (out.data.t[1] - out.data.t[0]);
    Eigen::Index first = 0;
    while (first < raw.t.size() && raw.t[first] < start) ++first;
    drop_leading_rows(raw, first);
  }
  if (options.periodic || !raw.has_velocity) {
    motion_at_samples_of(out.data, period, raw);
  }
  out.data = std::move(raw);
  out.decimation = 1;
  const bool skipped = options.periodic && options.skip_periods > 0;
  out.summary = held + out.summary +
                (skipped ? "; every sample after them kept (no decimation"
                         : "; every sample of the file kept (no decimation") +
                 std::string(options.periodic ? ", the series evaluated at each time stamp)"
                                              : ")");
  return out;
}

namespace {

// Every digital filter here (averaging per period, position filter, decimation) assumes a
// uniform sample time: a record that needs one and does not have it is resampled. Returns the
// summary's words for it ("" when nothing was done).
std::string resample_if_needed(Trajectory& raw, const PreparationOptions& options) {
  const bool needs_uniform =
      options.periodic || (!raw.has_velocity && !options.raw) || options.decimation.value_or(1) > 1;
  if (!(needs_uniform && raw.t.size() >= 3 && !is_uniform(raw.t))) return "";
  const double dt = nominal_step(raw.t);
  raw = resample_uniform(raw, dt);
  return "resampled on a uniform grid of " + number(dt * 1e3) +
         " ms (linear interpolation: the time stamps are not uniform); ";
}

// The period to average over: the given one, or the detected one.
double averaging_period(const Trajectory& raw, const PreparationOptions& options) {
  if (options.period) return *options.period;
  // An excitation played on the controller's clock has a whole number of samples per
  // period: the detected period is rounded to it (detect_period's advice).
  const double dt = uniform_sample_time(raw);
  return std::round(detect_period(raw) / dt) * dt;
}

// Swevers 2002, section 4: average whole periods, noise variance of the averages, DFT
// re-estimation of eq. 15 and analytic eq. 16-17.
PreparedExperiment prepare_periodic(Trajectory& raw, const PreparationOptions& options,
                                    const std::string& resampled) {
  PreparedExperiment out;
  const double period = averaging_period(raw, options);
  std::string skipped;
  if (options.skip_periods > 0) skipped = skip_whole_periods(raw, period, options.skip_periods);
  PeriodicAverage average = average_periods(raw, period);
  const int harmonics = options.harmonics ? *options.harmonics : select_harmonics(average);
  const FourierTrajectory fourier = fit_fourier(average.averaged, average.period, harmonics);
  apply_fourier(average.averaged, fourier);
  // Bona & Curatella 3.4: the averaged torques keep the lines that stand out of their noise;
  // the controller's content above them (the D term's encoder noise) is dropped.
  // When every harmonic stands out (noise-free data), nothing is noise: the torques stay whole
  // (projecting them would still drop an even period's Nyquist line).
  const int torque_harmonics = select_torque_harmonics(average, harmonics);
  const bool whole = torque_harmonics >= (average.samples_per_period - 1) / 2;
  if (!whole) keep_harmonics(average.averaged, average.averaged.tau, torque_harmonics);
  const NoiseCoupling coupling = noise_coupling(average);  // before the average moves out
  out.data = std::move(average.averaged);
  out.tau_noise_variance = average.tau_noise_variance;
  out.noise = periodic_noise(average, harmonics, whole ? -1 : torque_harmonics);
  out.noise.coupling = coupling;
  out.decimation = options.decimation.value_or(1);
  out.summary = resampled + skipped + "periodic: " + std::to_string(average.periods) +
                " periods of " + std::to_string(average.samples_per_period) + " samples (period " +
                number(average.period, 6) + " s" + (options.period ? "" : ", detected") +
                ") averaged, " + std::to_string(harmonics) + " harmonics re-estimated, " +
                (whole ? std::string("torques kept whole (every harmonic above their noise)")
                       : "torques kept up to harmonic " + std::to_string(torque_harmonics) + " (" +
                             number(torque_harmonics / average.period, 3) + " Hz)") +
                "; torque noise std of the averages:";
  for (Eigen::Index j = 0; j < out.tau_noise_variance.size(); ++j) {
    out.summary += " " + number(std::sqrt(out.tau_noise_variance[j]), 3);
  }
  if (average.dropped_samples > 0) {
    out.warning = raw.source + ": warning: the record is not a whole number of periods; the " +
                  std::to_string(average.dropped_samples) + " samples (" +
                  number(average.dropped_seconds) + " s) after the last whole period are not used";
  }
  return out;
}

// The excitation bands: given, or estimated from the data. The estimate is made even when
// --cutoff and --decimate set the plan, for the checks; then a record it fails on is still
// prepared (bandwidth 0: no checks).
ExcitationBands excitation_bands(const Trajectory& raw, const PreparationOptions& options) {
  ExcitationBands bands;
  if (options.bandwidth_hz) {
    bands.bandwidth_hz = *options.bandwidth_hz;
    return bands;
  }
  try {
    return estimate_bands(raw);
  } catch (const DataError&) {
    if (!options.cutoff_hz || !options.decimation) throw;
  }
  return bands;
}

// Samples dropped at each end after a position filter at `cutoff_hz` (kEdgePeriods periods).
Eigen::Index edge_samples(double cutoff_hz, double dt) {
  return static_cast<Eigen::Index>(std::ceil(kEdgePeriods / (cutoff_hz * dt)));
}

// Gautier & Briot, section IV.A: position filter well above the dynamics, central
// differences, then the parallel decimation of Y and W (eq. 13-14) in identify(); the plan
// from the band and the rows it must leave (plan_filtering), checked against the data.
void filter_and_differentiate(Trajectory& raw, const PreparationOptions& options, bool keep_edges,
                              const std::string& resampled, PreparedExperiment& out) {
  const double dt = uniform_sample_time(raw);
  const ExcitationBands bands = excitation_bands(raw, options);
  const double bandwidth = bands.bandwidth_hz;
  out.bandwidth_hz = bandwidth;
  FilterPlan plan;
  if (bandwidth > 0) {
    try {
      plan = plan_filtering(1.0 / dt, bandwidth);
      const Eigen::Index edge =
          edge_samples(options.cutoff_hz.value_or(plan.position_cutoff_hz), dt);
      const RowBudget rows{static_cast<long long>(raw.t.size() - 2 * edge),
                           static_cast<int>(raw.q.cols()), options.unknowns};
      plan = plan_filtering(1.0 / dt, bandwidth, rows);
    } catch (const std::invalid_argument& e) {
      throw DataError(raw.source + ": error: " + e.what());
    }
  }
  const FilterPlan planned = plan;
  if (options.cutoff_hz) plan.position_cutoff_hz = *options.cutoff_hz;
  if (options.decimation) plan.decimation_factor = *options.decimation;
  const Eigen::VectorXd q_noise = position_noise_std(raw);
  // Before the filter: the speed below which its velocity's sign is unreliable (issue 31).
  out.reversal_speed = reversal_min_speed(raw, plan.position_cutoff_hz, plan.position_order,
                                          q_noise, edge_samples(plan.position_cutoff_hz, dt))
                           .speed;
  filter_positions(raw, plan.position_cutoff_hz, plan.position_order);
  // The zero-phase filter's start and end are only approximately right (its edges assume
  // the signal continues as its reflection), and differentiating twice amplifies that: the
  // samples within kEdgePeriods cut-off periods of either end are dropped.
  const Eigen::Index edge = edge_samples(plan.position_cutoff_hz, dt);
  const Eigen::Index kept = raw.t.size() - 2 * edge;
  if (kept < 3) {
    throw DataError(raw.source + ": error: too short for a position filter at " +
                    number(plan.position_cutoff_hz, 3) + " Hz: its edges (" + std::to_string(edge) +
                    " samples at each end) leave " +
                    std::to_string(std::max<Eigen::Index>(kept, 0)) + " samples");
  }
  if (bandwidth > 0) {
    PreparationFacts facts{raw.source,
                           1.0 / dt,
                           bandwidth,
                           plan.position_cutoff_hz,
                           plan.decimation_factor,
                           options.cutoff_hz.has_value(),
                           options.decimation.has_value(),
                           planned.decimation_factor,
                           planned.position_cutoff_hz,
                           static_cast<long long>(kept),
                           options.unknowns,
                           bandwidth > 0 ? q_noise : Eigen::VectorXd(),
                           raw.ddq.middleRows(edge, kept),
                           raw.tau.middleRows(edge, kept)};
    for (const std::string& line : check_preparation(facts)) {
      out.warning += (out.warning.empty() ? "" : "\n") + line;
    }
  }
  if (!keep_edges) {
    raw.t = raw.t.segment(edge, kept).eval();
    for (Eigen::MatrixXd* m : {&raw.q, &raw.dq, &raw.ddq, &raw.tau}) {
      *m = m->middleRows(edge, kept).eval();
    }
  }
  out.decimation = plan.decimation_factor;
  out.reversal_guard = reversal_guard_samples(plan.position_cutoff_hz, 1.0 / dt);
  std::string band;
  if (options.bandwidth_hz) {
    band = ", excitation bandwidth " + number(bandwidth, 3) + " Hz (given)";
  } else if (bandwidth > 0) {
    band = ", excitation bandwidth " + number(bandwidth, 3) +
           " Hz (estimated: 99% of the "
           "velocities' energy below " +
           number(bands.velocity_hz, 3) + " Hz" +
           (bands.torque_hz > 0 ? ", of the torques' below " + number(bands.torque_hz, 3) + " Hz"
                                : std::string()) +
           ")";
  }
  out.summary = resampled + "sampled at " + number(1.0 / dt) + " Hz" + band +
                "; positions low-passed at " + number(plan.position_cutoff_hz, 3) +
                " Hz (zero phase), central differences, " + number(edge * dt, 3) +
                (keep_edges ? " s at each end within the filter's edges (approximate)"
                            : " s dropped at each end (filter edges), parallel decimation by " +
                                  std::to_string(out.decimation));
}

PreparedExperiment prepare_joint_side(Trajectory raw, const PreparationOptions& options,
                                      bool keep_edges) {
  const std::string resampled = resample_if_needed(raw, options);
  if (options.periodic) return prepare_periodic(raw, options, resampled);

  PreparedExperiment out;
  const std::string decimated =
      options.decimation.value_or(1) > 1
          ? ", parallel decimation by " + std::to_string(*options.decimation)
          : "";
  if (raw.has_velocity) {
    out.decimation = options.decimation.value_or(1);
    out.summary = resampled + "velocities and accelerations as given in the file" + decimated;
    if (options.bandwidth_hz || options.cutoff_hz) {
      out.warning = raw.source +
                    ": warning: the file gives dq and ddq, so no position filter is applied: "
                    "--bandwidth and --cutoff are not used for it";
    }
  } else if (options.raw) {
    differentiate(raw);
    out.decimation = options.decimation.value_or(1);
    out.summary = resampled + "central differences of the positions, no filter" + decimated;
  } else {
    filter_and_differentiate(raw, options, keep_edges, resampled, out);
  }
  out.data = std::move(raw);
  return out;
}

}  // namespace

}  // namespace modelgen
