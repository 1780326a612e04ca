// Parallel decimation (Gautier & Briot eq. 13-14): Matlab's decimation filter, zero phase, the
// same on every column, then one row in n_d.

#include "modelgen/signal/decimation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/src/signal/filter_sections.hpp"

namespace modelgen {

namespace {

using detail::filtfilt_column;
using detail::settling_samples;

}  // namespace

LowPassFilter decimation_filter(int factor) {
  if (factor < 2) {
    throw std::invalid_argument("decimation factor must be at least 2 for a filter, got " +
                                std::to_string(factor));
  }
  // Matlab's decimate: cheby1(8, 0.05, 0.8 / r), cut-off relative to Nyquist (0.5 here).
  return chebyshev1_lowpass(8, 0.05, 0.4 / factor, 1.0);
}

Eigen::Index decimated_rows(Eigen::Index rows, int factor) {
  if (factor < 1) {
    throw std::invalid_argument("decimation factor must be at least 1, got " +
                                std::to_string(factor));
  }
  return rows == 0 ? 0 : (rows - 1) / factor + 1;
}

void decimate(const ConstStridedMatrixRef& x, int factor, StridedMatrixRef out) {
  const Eigen::Index n = x.rows(), rows = decimated_rows(n, factor);
  if (out.rows() != rows || out.cols() != x.cols()) {
    throw std::invalid_argument("decimate: output is " + std::to_string(out.rows()) + " x " +
                                std::to_string(out.cols()) + ", expected " + std::to_string(rows) +
                                " x " + std::to_string(x.cols()) + " (" + std::to_string(n) +
                                " rows decimated by " + std::to_string(factor) + ")");
  }
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    for (Eigen::Index s = 0; s < n; ++s) {
      if (!std::isfinite(x(s, c))) {
        throw std::invalid_argument("decimate: row " + std::to_string(s + 1) + ", column " +
                                    std::to_string(c + 1) + " is NaN or infinite");
      }
    }
  }
  if (factor == 1) {
    out = x;
    return;
  }
  if (n == 0) return;
  const LowPassFilter filter = decimation_filter(factor);
  const Eigen::Index settling = settling_samples(filter);
  std::vector<double> buffer, state;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    // Gautier & Briot eq. 13-14: the same low-pass on every column, then one row in n_d.
    const Eigen::Index pad = filtfilt_column(filter, x.col(c), settling, buffer, state);
    for (Eigen::Index i = 0; i < rows; ++i) out(i, c) = buffer[pad + i * factor];
  }
}

Eigen::MatrixXd decimate(const ConstStridedMatrixRef& x, int factor) {
  Eigen::MatrixXd out(decimated_rows(x.rows(), factor), x.cols());
  decimate(x, factor, out);
  return out;
}

void decimate_trajectory(Trajectory& x, int factor) {
  if (factor == 1) return;
  Eigen::VectorXd t(decimated_rows(x.t.size(), factor));
  for (Eigen::Index s = 0; s < t.size(); ++s) t[s] = x.t[s * factor];
  x.t = t;
  for (Eigen::MatrixXd* m : {&x.q, &x.dq, &x.ddq, &x.tau}) *m = decimate(*m, factor);
}

}  // namespace modelgen
