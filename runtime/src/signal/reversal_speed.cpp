// The minimum speed of the reversal weighting, chosen from the record (issue 31).

#include "modelgen/signal/reversal_speed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "modelgen/signal/differentiation.hpp"
#include "modelgen/signal/lowpass.hpp"
#include "modelgen/signal/sampling.hpp"

namespace modelgen {

namespace {

// Beyond this many standard deviations a velocity's sign is taken as known (0.13 % one-sided).
constexpr double kSignSigmas = 3.0;
// The impulse response is summed over this many cut-off periods each side (its tail beyond
// is below 1e-9 of its peak for the orders used).
constexpr double kImpulsePeriods = 20.0;

// The prepared velocity: the positions low-passed at `cutoff_hz` and differentiated, as
// filter_and_differentiate does (one sample fewer at each end).
Eigen::MatrixXd prepared_velocity(const Trajectory& raw, double cutoff_hz, int order) {
  Trajectory x;
  x.source = raw.source;
  x.t = raw.t;
  x.q = raw.q;
  x.tau = Eigen::MatrixXd::Zero(raw.q.rows(), raw.q.cols());
  filter_positions(x, cutoff_hz, order);
  return x.dq;
}

// Per joint, the median of |dq_s+1 - dq_s| over the sign changes of dq (the velocity's step
// per sample at a reversal, |ddq| dt), away from the edges; infinite for a joint that never
// reverses (no reversal for noise to blur).
Eigen::VectorXd reversal_steps(const Eigen::MatrixXd& dq, Eigen::Index edge) {
  Eigen::VectorXd out(dq.cols());
  std::vector<double> steps;
  for (Eigen::Index j = 0; j < dq.cols(); ++j) {
    steps.clear();
    for (Eigen::Index s = edge; s + 1 < dq.rows() - edge; ++s) {
      if (dq(s, j) * dq(s + 1, j) < 0) steps.push_back(std::abs(dq(s + 1, j) - dq(s, j)));
    }
    if (steps.empty()) {
      out[j] = std::numeric_limits<double>::infinity();
      continue;
    }
    auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
    std::nth_element(steps.begin(), middle, steps.end());
    out[j] = *middle;
  }
  return out;
}

}  // namespace

double velocity_noise_gain(double cutoff_hz, int order, double sample_rate_hz) {
  const Eigen::Index half =
      static_cast<Eigen::Index>(std::ceil(kImpulsePeriods * sample_rate_hz / cutoff_hz));
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2 * half + 1, 1);
  h(half, 0) = 1.0;
  filtfilt(butterworth_lowpass(order, cutoff_hz, sample_rate_hz), h);
  // Central difference of white noise through the filter: g_k = (h_k+1 - h_k-1) fs / 2, and
  // var(v) = sigma_q^2 sum_k g_k^2.
  double sum = 0;
  for (Eigen::Index k = 1; k + 1 < h.rows(); ++k) {
    const double g = 0.5 * sample_rate_hz * (h(k + 1, 0) - h(k - 1, 0));
    sum += g * g;
  }
  return std::sqrt(sum);
}

ReversalSpeed reversal_min_speed(const Trajectory& raw, double cutoff_hz, int order,
                                 const Eigen::VectorXd& q_noise_std, Eigen::Index edge) {
  ReversalSpeed out;
  const Eigen::Index n = raw.q.cols(), m = raw.t.size() - 2;  // rows of the prepared dq
  if (m - 2 * edge < 1 || q_noise_std.size() != n) return out;
  const double rate = 1.0 / uniform_sample_time(raw);
  const double noise_gain = velocity_noise_gain(cutoff_hz, order, rate);
  out.noise = kSignSigmas * noise_gain * q_noise_std;
  out.lag = Eigen::VectorXd::Zero(n);
  // The reference needs a band clearly wider than the filter's, below Nyquist.
  const double reference_hz = std::min(kReferenceBand * cutoff_hz, 0.4 * rate);
  const Eigen::MatrixXd dq = prepared_velocity(raw, cutoff_hz, order);
  out.step = reversal_steps(dq, edge);
  if (reference_hz > 1.5 * cutoff_hz) {
    const Eigen::MatrixXd reference = prepared_velocity(raw, reference_hz, order);
    const Eigen::VectorXd reference_known =
        kSignSigmas * velocity_noise_gain(reference_hz, order, rate) * q_noise_std;
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index s = edge; s < m - edge; ++s) {
        // The filtered velocity's error, v - r within r's noise, against its magnitude: where
        // it exceeds half of it the sign is not to be trusted (a sign r contradicts, or a joint
        // at rest by r that the filter has moving).
        const double v = dq(s, j), r = reference(s, j);
        ++out.compared;
        if (std::abs(v - r) - reference_known[j] > 0.5 * std::abs(v)) {
          out.lag[j] = std::max(out.lag[j], std::abs(v));
        }
      }
    }
  }
  // Noise that flips the sign for less than a sample per reversal leaves isolated samples,
  // whose ramps would weight out two cut-off periods each for nothing: then the lag alone.
  out.speed = out.lag;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (out.noise[j] > out.step[j]) out.speed[j] = std::max(out.speed[j], out.noise[j]);
  }
  return out;
}

}  // namespace modelgen
