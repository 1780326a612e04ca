// The residual in the band against the record's noise floor there, joint by joint.

#include "modelgen/signal/residual_noise.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace modelgen {

namespace {

// Below these degrees of freedom an estimate of the noise says too little to judge by.
constexpr double kMinNoiseDof = 4;

}  // namespace

double chi_square_point(double z, double dof) {
  if (!(dof > 0)) return 0;
  const double a = 2 / (9 * dof);
  const double root = 1 - a + z * std::sqrt(a);
  return root > 0 ? dof * root * root * root : 0;
}

namespace {

// The ratio of a joint with its energies and degrees of freedom set, and its bounds.
void judge(JointResidual& r, double noise) {
  if (std::isnan(noise) || !(noise > 0) || r.noise_dof < kMinNoiseDof) return;
  r.noise = noise;
  r.ratio = r.residual / noise;
  const double z = kResidualCheckZ;
  const double noise_low = chi_square_point(-z, r.noise_dof) / r.noise_dof;
  const double noise_high = chi_square_point(z, r.noise_dof) / r.noise_dof;
  r.upper = noise_low > 0 ? chi_square_point(z, r.residual_dof) / r.residual_dof / noise_low
                          : std::numeric_limits<double>::infinity();
  r.lower = chi_square_point(-z, r.residual_dof) / r.residual_dof / noise_high;
}

// (|X_0|^2 + 2 sum_{l=1..L} |X_l|^2) / N of one column over a period: its energy in the lines.
double line_energy(const Eigen::VectorXd& x, int L) {
  const Eigen::Index N = x.size();
  double sum = 0;
  for (int l = 0; l <= L; ++l) {
    double re = 0, im = 0;
    for (Eigen::Index k = 0; k < N; ++k) {
      const double angle = 2 * std::numbers::pi * l * static_cast<double>(k) / N;
      re += x[k] * std::cos(angle);
      im -= x[k] * std::sin(angle);
    }
    sum += (l == 0 ? 1.0 : 2.0) * (re * re + im * im);
  }
  return sum / static_cast<double>(N);
}

}  // namespace

std::vector<JointResidual> period_residual_against_noise(const std::vector<PeriodRecord>& records) {
  if (records.empty()) throw std::invalid_argument("period_residual_against_noise: no record");
  const Eigen::Index joints = records.front().tau.cols();
  std::vector<JointResidual> out(static_cast<std::size_t>(joints));
  for (Eigen::Index j = 0; j < joints; ++j) {
    JointResidual& r = out[static_cast<std::size_t>(j)];
    double noise = 0;
    for (const PeriodRecord& p : records) {
      if (p.tau.cols() != joints || p.error.cols() != joints || p.error.rows() != p.tau.rows()) {
        throw std::invalid_argument("period_residual_against_noise: records of different shapes");
      }
      const Eigen::Index N = p.tau.rows();
      int L = std::min<int>(p.band, static_cast<int>((N - 1) / 2));
      if (p.lines.rows() > 0) L = std::min<int>(L, static_cast<int>(p.lines.rows()) - 1);
      if (p.periods < 2 || L < 1) {
        noise = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      const double values = 2.0 * L + 1;
      r.residual += line_energy(p.error.col(j), L);
      r.torque += line_energy(p.tau.col(j), L);
      if (p.lines.rows() > 0) {
        const Eigen::VectorXd v = p.lines.col(j).head(L + 1);
        noise += (v[0] + 2 * v.tail(L).sum()) / static_cast<double>(N);
      } else {
        noise += values * p.white[j];
      }
      r.in_band_lines += L;
      r.residual_dof += values;
      r.noise_dof += values * (p.periods - 1);
      r.noise_origin = "from the spread of " + std::to_string(p.periods) + " periods";
    }
    judge(r, noise);
  }
  return out;
}

std::vector<JointResidual> residual_against_noise(const std::vector<ResidualRecord>& records) {
  if (records.empty()) throw std::invalid_argument("residual_against_noise: no record");
  const Eigen::Index joints = records.front().tau.cols();
  std::vector<JointResidual> out(static_cast<std::size_t>(joints));
  for (Eigen::Index j = 0; j < joints; ++j) {
    JointResidual& r = out[static_cast<std::size_t>(j)];
    double noise = 0;
    for (const ResidualRecord& record : records) {
      if (record.tau.cols() != joints || record.error.cols() != joints) {
        throw std::invalid_argument("residual_against_noise: records with different joints");
      }
      const BandEnergies e =
          band_energies(record.tau.col(j), record.error.col(j), record.dt, record.band);
      const double lines = record.band.band_hz * static_cast<double>(record.tau.rows()) * record.dt;
      r.residual += std::max(e.error - e.error_above, 0.0);
      r.torque += std::max(e.torque - e.torque_above, 0.0);
      noise += e.noise_in_band;  // NaN stays NaN
      r.in_band_lines += lines;
      r.residual_dof += lines;
      r.noise_dof += e.noise_periods >= 2 ? lines * static_cast<double>(e.noise_periods - 1) /
                                                static_cast<double>(e.noise_periods)
                                          : lines / 4;
      if (r.noise_origin.empty()) r.noise_origin = e.noise_origin;
    }
    judge(r, noise);
  }
  return out;
}

}  // namespace modelgen
