// The residual in the band against the record's noise floor there, joint by joint.

#include "modelgen/signal/residual_noise.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
    if (std::isnan(noise) || !(noise > 0) || r.noise_dof < kMinNoiseDof) continue;
    r.noise = noise;
    r.ratio = r.residual / noise;
    const double z = kResidualCheckZ;
    const double noise_low = chi_square_point(-z, r.noise_dof) / r.noise_dof;
    const double noise_high = chi_square_point(z, r.noise_dof) / r.noise_dof;
    r.upper = noise_low > 0 ? chi_square_point(z, r.residual_dof) / r.residual_dof / noise_low
                            : std::numeric_limits<double>::infinity();
    r.lower = chi_square_point(-z, r.residual_dof) / r.residual_dof / noise_high;
  }
  return out;
}

}  // namespace modelgen
