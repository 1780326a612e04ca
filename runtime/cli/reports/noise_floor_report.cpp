// The relative error norm in the excitation band, next to the full-band one and the record's
// noise floor: on closed-loop data most of the measured torque can be the controller's answer
// to encoder noise, far above the band, and the full-band figure then says nothing of the model.

#include "runtime/cli/reports/noise_floor_report.hpp"

#include <cmath>

#include "modelgen/io/experiment/fourier_file.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

// An error in the band within this factor of the floor is all the record can tell.
constexpr double kAtTheFloor = 1.1;

std::string percent(double fraction) { return fixed(100.0 * fraction, 0, 3) + "%"; }

std::string band_text(const ExcitationBand& band) {
  return "0 to " + fixed(band.band_hz, 0, 3) + " Hz (" + band.origin + ")";
}

}  // namespace

BandComparison compare_in_band(const std::vector<Trajectory>& motion,
                               const std::vector<Eigen::MatrixXd>& tau,
                               const std::vector<Eigen::MatrixXd>& error,
                               const std::optional<std::string>& trajectory_path, int dof) {
  BandComparison out;
  std::optional<ExcitationBand> from_file;
  if (trajectory_path) {
    from_file = band_of_fourier(io::read_fourier(*trajectory_path, dof), *trajectory_path);
  }
  for (std::size_t e = 0; e < motion.size(); ++e) {
    const Eigen::VectorXd& t = motion[e].t;
    if (t.size() < 2) {
      out.records.clear();
      out.missing = motion[e].source + " has fewer than 2 samples";
      return out;
    }
    const double dt = (t[t.size() - 1] - t[0]) / static_cast<double>(t.size() - 1);
    ExcitationBand band;
    try {
      band = from_file ? *from_file : band_of_positions(motion[e]);
    } catch (const DataError& problem) {
      // Not an error of the run: the comparison goes on in full band only, and says why.
      const std::string what = problem.what();
      const std::size_t at = what.find("error: ");
      out.records.clear();
      out.missing = motion[e].source + ": " +
                    (at == std::string::npos ? what : what.substr(at + 7));
      return out;
    }
    out.records.push_back(band_energies(tau[e], error[e], dt, band));
  }
  out.floor = noise_floor(out.records);
  return out;
}

void print_relative_errors(std::ostream& out, double full_band, const BandComparison& comparison,
                           const std::vector<std::string>& sources) {
  out << "  relative error norm ||tau - tau_pred|| / ||tau||: " << fixed(full_band, 0, 6);
  if (comparison.records.empty()) {
    out << "\n  no excitation band to compare in: " << comparison.missing << "\n";
    return;
  }
  const NoiseFloor& f = comparison.floor;
  const std::string above = percent(f.out_of_band_fraction) +
                            " of the measured torque's energy lies above the excitation band";
  if (!f.in_band_headline) out << " <- headline (" << above << ")";
  out << "\n  relative error norm in the band: " << fixed(f.in_band, 0, 6) << " (rms "
      << fixed(f.in_band_rms, 0, 4) << " N m)";
  if (f.in_band_headline) {
    out << " <- headline: " << above << ", beyond any model of the excitation (full band "
        << fixed(full_band, 0, 6) << ")";
  }
  out << "\n  noise floor in the band: ";
  if (std::isnan(f.floor)) {
    out << "not estimated (" << comparison.records.front().noise_origin << ")\n";
  } else {
    out << fixed(f.floor, 0, 6) << ", rms " << fixed(f.floor_rms, 0, 4) << " N m ("
        << comparison.records.front().noise_origin
        << (comparison.records.size() > 1 ? " and the like in each record" : "") << ")\n";
    if (f.in_band <= kAtTheFloor * f.floor) {
      out << "  the error in the band is at the noise floor: these data cannot tell a better "
             "model\n";
    }
  }
  if (comparison.records.size() == 1) {
    out << "  excitation band: " << band_text(comparison.records.front().band) << "\n";
    return;
  }
  for (std::size_t e = 0; e < comparison.records.size(); ++e) {
    out << "  excitation band of " << sources[e] << ": " << band_text(comparison.records[e].band)
        << "\n";
  }
}

}  // namespace modelgen::internal
