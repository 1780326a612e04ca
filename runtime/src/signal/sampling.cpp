// The sample time of a uniformly sampled trajectory, and linear resampling on a uniform grid.

#include "modelgen/signal/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using detail::fail;
using detail::format;

std::string number(double value, int digits = 4) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

}  // namespace

double uniform_sample_time(const Trajectory& x) {
  const Eigen::Index n = x.t.size();
  if (n < 2) fail(x, "fewer than 2 samples");
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!std::isfinite(x.t[k])) {
      fail(x, "sample " + std::to_string(k + 1) + ", column 't' is NaN or infinite");
    }
  }
  const double dt = (x.t[n - 1] - x.t[0]) / static_cast<double>(n - 1);
  if (!(dt > 0)) fail(x, "time does not increase from the first to the last sample");
  for (Eigen::Index k = 0; k < n; ++k) {
    const double off = (x.t[k] - (x.t[0] + static_cast<double>(k) * dt)) / dt;
    if (std::abs(off) > 0.01) {
      fail(x, "sampling is not uniform: sample " + std::to_string(k + 1) +
                  " (t = " + format(x.t[k]) + " s) is " + format(off) +
                  " samples off the grid t1 + k dt with dt = " + format(dt) +
                  " s (at most 0.01 allowed); resample the data first");
    }
  }
  return dt;
}

Trajectory resample_uniform(const Trajectory& x, double dt) {
  const Eigen::Index n = x.t.size();
  if (n < 2 || !(dt > 0)) {
    throw DataError(x.source + ": error: cannot resample " + std::to_string(n) +
                    " samples with a sample time of " + number(dt) + " s");
  }
  const double span = (x.t[n - 1] - x.t[0]) / dt;
  // A grid far denser than the samples would be mostly invented (and a time stamp far off
  // would ask for more memory than there is).
  if (!(span < 100.0 * static_cast<double>(n))) {
    throw DataError(x.source + ": error: resampling " + std::to_string(n) + " samples over " +
                    number(x.t[n - 1] - x.t[0]) + " s every " + number(dt) + " s would make " +
                    number(span) + " samples, more than 100 per sample: the time stamps have "
                    "holes; split the record at them");
  }
  const Eigen::Index m = static_cast<Eigen::Index>(std::floor(span)) + 1;
  Trajectory out;
  out.source = x.source;
  out.measured = x.measured;
  out.has_velocity = x.has_velocity;
  out.t.resize(m);
  out.q.resize(m, x.q.cols());
  out.dq.setZero(m, x.q.cols());
  out.ddq.setZero(m, x.q.cols());
  out.tau.resize(m, x.q.cols());
  Eigen::Index k = 0;
  for (Eigen::Index s = 0; s < m; ++s) {
    const double t = x.t[0] + static_cast<double>(s) * dt;
    while (k + 2 < n && x.t[k + 1] <= t) ++k;
    const double w = std::clamp((t - x.t[k]) / (x.t[k + 1] - x.t[k]), 0.0, 1.0);
    out.t[s] = t;
    out.q.row(s) = (1 - w) * x.q.row(k) + w * x.q.row(k + 1);
    out.tau.row(s) = (1 - w) * x.tau.row(k) + w * x.tau.row(k + 1);
    if (x.has_velocity) {
      out.dq.row(s) = (1 - w) * x.dq.row(k) + w * x.dq.row(k + 1);
      out.ddq.row(s) = (1 - w) * x.ddq.row(k) + w * x.ddq.row(k + 1);
    }
  }
  return out;
}

}  // namespace modelgen
