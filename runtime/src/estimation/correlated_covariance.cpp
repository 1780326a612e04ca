// The score covariance of a least-squares fit on correlated equation errors (issue 31).
//
// For e with covariance Omega, the estimate's covariance is (A^T A)^-1 A^T Omega A (A^T A)^-1
// (the "sandwich"); eq. 18 of Gautier & Briot takes Omega = s^2 I. Two cases break that:
// - the periodic route averages the periods and keeps the torques up to harmonic H: the noise
//   left is circular, on 2 H + 1 of the N lines of the period. Circular noise has a circulant
//   Omega, diagonal in the DFT: Omega = F^* diag(lambda_l) F / N, so
//   A^T Omega A = (1/N) sum_l lambda_l Re(conj(a_l) a_l^T), a_l the DFT of A's columns at
//   line l, and E|R_l|^2 = N lambda_l for the residual's DFT (up to the fit's leverage): the
//   same line-wise estimate as the noise lines of ML-EIV (errors_in_variables_score.cpp), here
//   from the residual (smoothed over neighbouring lines) because IDIM has no per-period
//   spread to hand;
// - a filtered, decimated or closed-loop record: a stationary correlated sequence, for which
//   Newey & West (1987) sum the lagged score products with Bartlett weights 1 - l / (L + 1),
//   the bandwidth L from Andrews (1991, eq. 6.4 with the AR(1) plug-in):
//   L = 1.1447 (alpha n)^(1/3), alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2); the sum is taken
//   by overlapping batch means, which weigh the lags the same and cost nothing per lag (an
//   undecimated record has L in the hundreds).

#include "runtime/src/estimation/correlated_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>

namespace modelgen::detail {

namespace {

// sum_l lambda_l Re(conj(a_l) a_l^T) / N over the lines 0..H of one period (each line l > 0
// stands for l and N - l, hence 2), lambda_l N estimated by |R_m|^2 averaged over the lines m
// within H / 4 of l: a single line's |R_l|^2 has as much spread as value, and the fit takes
// most of the noise on the few lines where a parameter's column lives (its leverage), which
// alone would make that parameter's sd several times too small.
Eigen::MatrixXd periodic_meat(const ResidualGroup& g) {
  const Eigen::Index N = g.r.size(), b = g.X.cols();
  const int top = static_cast<int>(std::min<Eigen::Index>(g.harmonics, (N - 1) / 2));
  const int window = std::max(2, top / 4);
  Eigen::MatrixXd re(b, top + 1), im(b, top + 1);
  Eigen::VectorXd power(top + 1);
  Eigen::VectorXd c(N), s(N);
  for (int l = 0; l <= top; ++l) {
    for (Eigen::Index k = 0; k < N; ++k) {
      const double angle = 2 * std::numbers::pi * l * static_cast<double>(k) / N;
      c[k] = std::cos(angle);
      s[k] = std::sin(angle);
    }
    re.col(l) = g.X.transpose() * c;
    im.col(l) = g.X.transpose() * s;
    power[l] = std::pow(c.dot(g.r), 2) + std::pow(s.dot(g.r), 2);
  }
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(b, b);
  for (int l = 0; l <= top; ++l) {
    const int from = std::max(0, l - window), to = std::min(top, l + window);
    const double line = power.segment(from, to - from + 1).mean();
    const double weight = (l == 0 ? 1.0 : 2.0) * line / (static_cast<double>(N) * N);
    meat += weight * (re.col(l) * re.col(l).transpose() + im.col(l) * im.col(l).transpose());
  }
  return meat;
}

// Newey-West with Bartlett weights and bandwidth L on one group's score rows x_t r_t.
Eigen::MatrixXd newey_west_meat(const ResidualGroup& g, int L) {
  const Eigen::MatrixXd G = g.X.array().colwise() * g.r.array();
  BartlettScoreSum sum(G.cols(), static_cast<int>(std::min<Eigen::Index>(L, G.rows() - 1)));
  for (Eigen::Index t = 0; t < G.rows(); ++t) sum.add(G.row(t).transpose());
  return sum.meat();
}

// The independent rows a correlated sequence is worth, rows (1 - rho) / (1 + rho) for an AR(1):
// the fit's b parameters take b of these, not b of the rows. Its columns are slow signals,
// where correlated noise has most of its power, so the residual is short of noise there, and
// the meat with it; with rho 0.95 over 10 000 power equations that is 256 rows, and 61
// parameters take a quarter of them (the sd a seventh too small without this).
double effective_rows(Eigen::Index rows, const Correlation& c) {
  const double share = c.significant && c.rho > 0 ? (1 - c.rho) / (1 + c.rho) : 1.0;
  return static_cast<double>(rows) * share;
}

// Rows of window sums collected before one product into the meat.
constexpr Eigen::Index kBlockRows = 256;

}  // namespace

Correlation residual_correlation(double lag_products, double squares, Eigen::Index rows,
                                 Eigen::Index sequences) {
  Correlation out;
  out.rho = squares > 0 ? std::clamp(lag_products / squares, -0.97, 0.97) : 0.0;
  // Significant (3 sd of a white sequence's) and material: below |rho| = 0.05 an AR(1) changes
  // the sd by under 5 % (sqrt((1 + rho) / (1 - rho))), less than Newey-West's own spread.
  out.significant = rows > 0 && std::abs(out.rho) > 0.05 &&
                    std::abs(out.rho) * std::sqrt(static_cast<double>(rows)) > 3;
  if (out.significant) {
    const double rho = out.rho;
    const double alpha = 4 * rho * rho / std::pow((1 - rho) * (1 + rho), 2);
    const double per_sequence = static_cast<double>(rows) / static_cast<double>(sequences);
    out.bandwidth = static_cast<int>(std::ceil(1.1447 * std::cbrt(alpha * per_sequence)));
  }
  return out;
}

double prewhitening_coefficient(double g0, double g1, double gk, double gk1) {
  const double span = g0 - gk;
  if (!(span > 0)) return 0;
  return std::clamp((g1 - gk1) / span, 0.0, 0.97);
}

Eigen::Index prewhitening_lag(double rho, Eigen::Index rows) {
  if (!(rho > 0)) return 1;
  const auto lag = static_cast<Eigen::Index>(std::ceil(1 / (1 - std::min(rho, 0.99))));
  return std::clamp<Eigen::Index>(lag, 1, std::max<Eigen::Index>(rows / 20, 1));
}

BartlettScoreSum::BartlettScoreSum(Eigen::Index b, int bandwidth)
    : window_(std::max(bandwidth, 0) + 1),
      recent_(Eigen::MatrixXd::Zero(window_, b)),
      sum_(Eigen::VectorXd::Zero(b)),
      block_(kBlockRows, b),
      meat_(Eigen::MatrixXd::Zero(b, b)) {}

void BartlettScoreSum::add(const Eigen::Ref<const Eigen::VectorXd>& score) {
  const Eigen::Index slot = rows_ % window_;
  sum_ += score - recent_.row(slot).transpose();
  recent_.row(slot) = score.transpose();
  if (++rows_ < window_) return;
  block_.row(filled_++) = sum_.transpose();
  if (filled_ == kBlockRows) {
    meat_.selfadjointView<Eigen::Lower>().rankUpdate(block_.transpose());
    filled_ = 0;
  }
}

Eigen::MatrixXd BartlettScoreSum::meat() const {
  Eigen::MatrixXd meat = meat_;
  meat.selfadjointView<Eigen::Lower>().rankUpdate(block_.topRows(filled_).transpose());
  meat = meat.selfadjointView<Eigen::Lower>();
  // rows - L windows cover the rows; each whole window stands for one row's share of the lags.
  const Eigen::Index windows = std::max<Eigen::Index>(rows_ - window_ + 1, 1);
  return meat *
         (static_cast<double>(rows_) / static_cast<double>(windows) / static_cast<double>(window_));
}

SandwichCovariance score_covariance(const std::vector<ResidualGroup>& groups,
                                    const std::vector<StreamedMeat>& streamed) {
  SandwichCovariance out;
  if (groups.empty() && streamed.empty()) return out;
  const Eigen::Index b = groups.empty() ? streamed.front().meat.rows() : groups.front().X.cols();
  // Pooled lag-1 autocorrelation of the non-periodic groups' residuals.
  double lag = 0, zero = 0;
  Eigen::Index rows = 0, periodic = 0;
  for (const ResidualGroup& g : groups) {
    if (g.harmonics >= 0) {
      ++periodic;
      continue;
    }
    const Eigen::Index n = g.r.size();
    if (n < 2) continue;
    lag += g.r.head(n - 1).dot(g.r.tail(n - 1));
    zero += g.r.squaredNorm();
    rows += n;
  }
  const auto sequences = static_cast<Eigen::Index>(groups.size()) - periodic;
  const Correlation correlation =
      residual_correlation(lag, zero, rows, std::max<Eigen::Index>(sequences, 1));
  const bool streamed_correlated =
      std::any_of(streamed.begin(), streamed.end(),
                  [](const StreamedMeat& s) { return s.correlation.significant; });
  if (periodic == 0 && !correlation.significant && !streamed_correlated) return out;
  out.meat = Eigen::MatrixXd::Zero(b, b);
  double freedom = 0;
  for (const ResidualGroup& g : groups) {
    if (g.harmonics >= 0) {
      out.meat += periodic_meat(g);
      freedom += static_cast<double>(std::min<Eigen::Index>(2 * g.harmonics + 1, g.r.size()));
    } else {
      out.meat += newey_west_meat(g, correlation.bandwidth);
      freedom += effective_rows(g.r.size(), correlation);
    }
  }
  for (const StreamedMeat& s : streamed) {
    out.meat += s.meat;
    freedom += effective_rows(s.rows, s.whiten != 0 ? s.whitened : s.correlation);
  }
  if (freedom > static_cast<double>(b)) out.meat *= freedom / (freedom - static_cast<double>(b));
  std::ostringstream text;
  text << "sandwich covariance (the equation errors are correlated):";
  const char* separator = " ";
  if (periodic > 0) {
    text << separator << periodic
         << " periodic group(s) by the residual's DFT lines up to the kept harmonic";
    separator = "; ";
  }
  if (correlation.significant) {
    text << separator << "Newey-West, Bartlett bandwidth " << correlation.bandwidth
         << " rows (residual lag-1 autocorrelation " << std::round(correlation.rho * 100) / 100
         << ")";
    separator = "; ";
  }
  for (const StreamedMeat& s : streamed) {
    if (!s.correlation.significant) continue;
    text << separator << "Newey-West over " << s.rows << " undecimated rows";
    if (s.whiten != 0) {
      text << " prewhitened by AR(1) " << std::round(s.whiten * 1000) / 1000 << ", bandwidth "
           << s.whitened.bandwidth;
    } else {
      text << ", bandwidth " << s.correlation.bandwidth;
    }
    text << " (lag-1 autocorrelation " << std::round(s.correlation.rho * 100) / 100 << ")";
    separator = "; ";
  }
  out.description = text.str();
  return out;
}

Eigen::MatrixXd sandwich(const Eigen::MatrixXd& AtA_inverse, const Eigen::MatrixXd& meat) {
  return AtA_inverse * meat * AtA_inverse;
}

}  // namespace modelgen::detail
