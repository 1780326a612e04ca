// Parallel decimation (Gautier & Briot eq. 13-14): Matlab's decimation filter, zero phase, the
// same on every column, then one row in n_d; stages of at most 10; the rows clear of the ends.

#include "modelgen/signal/decimation.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/src/signal/filter_sections.hpp"

namespace modelgen {

namespace {

using detail::filtfilt_column;
using detail::settling_samples;

// The largest prime of `factor` (>= 2).
int largest_prime(int factor) {
  int largest = 1;
  for (int p = 2; p * p <= factor; ++p) {
    while (factor % p == 0) {
      largest = p;
      factor /= p;
    }
  }
  return std::max(largest, factor);
}

bool stageable(int factor) { return factor == 1 || largest_prime(factor) <= kMaxStageFactor; }

// One column through the stages: filtfilt of each stage, then one sample in its factor.
template <typename Column>
void decimate_column(const Column& x, const std::vector<LowPassFilter>& filters,
                     const std::vector<Eigen::Index>& settling, const std::vector<int>& stages,
                     std::vector<double>& current, std::vector<double>& buffer,
                     std::vector<double>& state) {
  const Eigen::Index n = x.size();
  current.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) current[k] = x(k);
  for (std::size_t s = 0; s < stages.size(); ++s) {
    const Eigen::Map<const Eigen::VectorXd> in(current.data(),
                                               static_cast<Eigen::Index>(current.size()));
    const Eigen::Index pad = filtfilt_column(filters[s], in, settling[s], buffer, state);
    const Eigen::Index rows = decimated_rows(in.size(), stages[s]);
    current.resize(rows);
    for (Eigen::Index i = 0; i < rows; ++i) current[i] = buffer[pad + i * stages[s]];
  }
}

}  // namespace

std::vector<int> decimation_stages(int factor) {
  if (factor < 1) {
    throw std::invalid_argument("decimation factor must be at least 1, got " +
                                std::to_string(factor));
  }
  if (!stageable(factor)) {
    int above = factor + 1;
    while (!stageable(above)) ++above;
    throw std::invalid_argument(
        "decimation factor " + std::to_string(factor) + " has the prime factor " +
        std::to_string(largest_prime(factor)) + ", above " + std::to_string(kMaxStageFactor) +
        ": decimation runs in stages of at most " + std::to_string(kMaxStageFactor) +
        " (an order-8 Chebyshev filter per stage, as Matlab's decimate advises); use " +
        std::to_string(decimation_factor_below(factor)) + " or " + std::to_string(above));
  }
  // Primes (all <= 7), largest first, packed first-fit into stages of at most 10: as few
  // stages as the primes allow (ceil(log10(factor)) for every factor tried up to 10^4 but
  // those where no packing reaches it).
  std::vector<int> primes;
  for (int p : {7, 5, 3, 2}) {
    for (int rest = factor; rest % p == 0; rest /= p) primes.push_back(p);
  }
  std::vector<int> stages;
  for (int p : primes) {
    auto fits = std::find_if(stages.begin(), stages.end(),
                             [&](int s) { return s * p <= kMaxStageFactor; });
    if (fits == stages.end()) {
      stages.push_back(p);
    } else {
      *fits *= p;
    }
  }
  std::sort(stages.rbegin(), stages.rend());
  return stages;
}

int decimation_factor_below(int factor) {
  int f = std::max(factor, 1);
  while (!stageable(f)) --f;
  return f;
}

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
  const std::vector<int> stages = decimation_stages(factor);
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
  std::vector<LowPassFilter> filters;
  std::vector<Eigen::Index> settling;
  for (int stage : stages) {
    filters.push_back(decimation_filter(stage));
    settling.push_back(settling_samples(filters.back()));
  }
  std::vector<double> current, buffer, state;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    // Gautier & Briot eq. 13-14: the same low-pass on every column, then one row in n_d.
    decimate_column(x.col(c), filters, settling, stages, current, buffer, state);
    for (Eigen::Index i = 0; i < rows; ++i) out(i, c) = current[i];
  }
}

Eigen::MatrixXd decimate(const ConstStridedMatrixRef& x, int factor) {
  Eigen::MatrixXd out(decimated_rows(x.rows(), factor), x.cols());
  decimate(x, factor, out);
  return out;
}

DecimatedRange decimated_interior(Eigen::Index samples, int factor) {
  const Eigen::Index rows = decimated_rows(samples, factor);
  if (factor == 1 || rows < 3) return {0, rows};
  const std::vector<int> stages = decimation_stages(factor);
  // White-noise gain of a row in the middle: sqrt(int_0^1/2 2 |H(f)|^4 df) (each stage's
  // zero-phase response |H_s|^2 at its own rate; aliasing between stages neglected, the stage
  // filters being far down there). The integrand is negligible past a few cut-offs.
  const double top = std::min(0.5, 4.0 / factor);
  const int points = 4096;
  double power = 0;
  std::vector<LowPassFilter> filters;
  for (int stage : stages) filters.push_back(decimation_filter(stage));
  for (int k = 0; k < points; ++k) {
    const double f = (k + 0.5) * top / points;
    double h2 = 1, rate = 1;  // |H|^2 of the chain; f in cycles per sample of each stage
    for (std::size_t s = 0; s < stages.size(); ++s) {
      if (f * rate < 0.5) h2 *= std::norm(filters[s].response(f * rate));
      rate *= stages[s];
    }
    power += 2 * h2 * h2 * top / points;
  }
  const double gain = std::sqrt(power);
  // The weight of the first and of the last sample in every decimated row.
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(samples);
  impulse[0] = 1;
  const Eigen::VectorXd first = decimate(impulse, factor);
  impulse[0] = 0;
  impulse[samples - 1] = 1;
  const Eigen::VectorXd last = decimate(impulse, factor);
  Eigen::Index begin = 0, end = rows;
  for (Eigen::Index i = 0; i < rows / 2; ++i) {
    if (std::abs(first[i]) > gain) begin = i + 1;
    if (std::abs(last[rows - 1 - i]) > gain) end = rows - 1 - i;
  }
  return {begin, std::max<Eigen::Index>(end - begin, 0)};
}

Eigen::MatrixXd decimate_interior(const ConstStridedMatrixRef& x, int factor) {
  const DecimatedRange kept = decimated_interior(x.rows(), factor);
  return decimate(x, factor).middleRows(kept.first, kept.count);
}

void decimate_trajectory(Trajectory& x, int factor) {
  if (factor == 1) return;
  const DecimatedRange kept = decimated_interior(x.t.size(), factor);
  Eigen::VectorXd t(kept.count);
  for (Eigen::Index s = 0; s < t.size(); ++s) t[s] = x.t[(kept.first + s) * factor];
  x.t = t;
  for (Eigen::MatrixXd* m : {&x.q, &x.dq, &x.ddq, &x.tau}) *m = decimate_interior(*m, factor);
}

}  // namespace modelgen
