// The residual of a fit against the record's own noise floor, joint by joint: the statistics
// are modelgen/signal/residual_noise's, the wording and the likely causes here.

#include "runtime/cli/reports/residual_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "modelgen/data/data_error.hpp"
#include "modelgen/estimation/predict.hpp"
#include "modelgen/signal/residual_noise.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

bool averaged(const Experiments& experiments, std::size_t e) {
  return e < experiments.noise.size() && !experiments.noise[e].empty();
}

// The averaged periods the fit compared (--periodic) with their errors, each with the noise
// its periods' spread left on its torque lines; empty when one is not an averaged period.
std::vector<PeriodRecord> compared_periods(const Experiments& experiments,
                                           const std::vector<Eigen::MatrixXd>& errors) {
  std::vector<PeriodRecord> records;
  for (std::size_t e = 0; e < experiments.data.size(); ++e) {
    if (!averaged(experiments, e) || e >= errors.size()) return {};
    const PeriodicNoise& noise = experiments.noise[e];
    PeriodRecord record;
    record.tau = experiments.data[e].tau;
    record.error = errors[e];
    record.lines = noise.tau_lines;
    record.white = noise.tau;
    record.periods = noise.periods;
    // The motion's harmonics are the positions' re-estimated ones.
    const auto motion = static_cast<double>(std::max<Eigen::Index>(noise.q_lines.rows() - 1, 0));
    record.band = static_cast<int>(std::floor(kTorqueBandFactor * motion));
    records.push_back(std::move(record));
  }
  return records;
}

// The records the fit compared, with their bands; empty when one has no band (too
// short, positions that do not move) or is an averaged period (compared_periods then).
std::vector<ResidualRecord> compared_records(const IdentificationModel& model,
                                             const Experiments& experiments,
                                             const Eigen::VectorXd& beta) {
  std::vector<ResidualRecord> records;
  for (std::size_t e = 0; e < experiments.data.size(); ++e) {
    if (averaged(experiments, e)) return {};
    // At the prepared rate, before the parallel decimation: the band is the same, and whole
    // periods keep whole numbers of samples (the noise from period to period needs them); a
    // decimated record's edges also carry its filter's transients.
    std::vector<Trajectory> one = {experiments.data[e]};
    const TorquePrediction prediction = predict_decimated(model, one, beta, {1});
    const Trajectory& x = one.front();
    if (x.t.size() < 2) return {};
    ResidualRecord record;
    record.dt = (x.t[x.t.size() - 1] - x.t[0]) / static_cast<double>(x.t.size() - 1);
    try {
      record.band = band_of_positions(x);
    } catch (const DataError&) {
      return {};
    }
    record.tau = x.tau;
    record.error = prediction.error.front();
    records.push_back(std::move(record));
  }
  return records;
}

// Above its bound, the residual in excess of the noise must also exceed this fraction of the
// joint's measured torque in the band (rms) to be warned about: a model that misses 1 % of a
// torque misses little. Records simulated in closed loop from the true parameters leave up to
// 0.8 % there (the bundled TX-40 record, joint 3: encoder quantisation that repeats with the
// motion, the controller's sampling), which is not the model's fault.
constexpr double kMaterialExcess = 0.01;

std::string rms(double energy, double values) {
  return fixed(std::sqrt(energy / values), 0, 3) + " N m";
}

// The linear methods' wording: every joint judged, `whose` after "the residual".
ResidualWording plain(const std::string& whose) {
  ResidualWording wording;
  wording.whose = whose;
  return wording;
}

// Why a joint's residual lies above its noise, and what to change.
void explain_excess(std::ostream& err, const ResidualWording& wording) {
  err << "the model misses something on this joint: a friction it lacks (Stribeck, "
         "load-dependent), ";
  if (wording.drive_model) {
    // Swevers eq. 12: efficiencies R_z are fitted only by approach 3; the rest of the drive
    // model and the links are the a-priori values theta2.
    err << "efficiencies below 1 (approaches 1 and 2 fix R_z to 1; --approach 3 fits them), "
           "a wrong a-priori value (the description's known: or --known) or a load elsewhere "
           "than on the payload link, a wrong drive description (gear ratio, coupling, "
           "--motor-side) or a delay between torques and positions (--torque-hold zoh for a "
           "digital controller's held commands); the rms torque errors per motor show how "
           "much\n";
    return;
  }
  err << "coupling or a load not in the description, a wrong drive description (gear ratio, "
         "--motor-side) or a delay between torques and positions (--torque-hold zoh for a "
         "digital controller's held commands), or noise in the regressor's dq and ddq that "
         "biases the estimate (errors in the variables: --cutoff, --decimate); the torque plots "
         "(--plot) show where\n";
}

// Why a joint's residual lies below its noise: `per_parameter` in-band values per unknown.
void explain_shortfall(std::ostream& err, const ResidualWording& wording, double per_parameter) {
  err << "the fit explains noise: " << fixed(per_parameter, 0, 3);
  if (wording.drive_model) {
    err << " in-band values per unknown; longer or more records, or fewer unknowns (--unknown)";
  } else {
    err << " in-band values per base parameter; longer or more records, or fewer parameters "
           "(--essential)";
  }
  err << ", or the noise estimate is too high (periods that differ: drift, a start transient)\n";
}

// One warning per judged joint outside its bounds (see the header), `samples` the values per
// joint the energies were summed over, `parameters` the fit's unknowns.
int warn_joints(std::ostream& err, const std::vector<JointResidual>& joints, double samples,
                Eigen::Index parameters, const ResidualWording& wording) {
  int warnings = 0;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const JointResidual& r = joints[j];
    if (j < wording.judged.size() && !wording.judged[j]) continue;
    if (std::isnan(r.ratio) || (r.ratio <= r.upper && r.ratio >= r.lower)) continue;
    const bool above = r.ratio > r.upper;
    // Significant is not yet material: what lies above the noise must also matter.
    const double excess = std::sqrt(std::max(r.residual - r.noise, 0.0) / r.torque);
    if (above && !(excess > kMaterialExcess)) continue;
    ++warnings;
    err << "modelid fit: warning: joint " << j + 1 << ": in the excitation band the residual"
        << wording.whose << " has " << fixed(r.ratio, 0, 3)
        << " times the energy of the record's noise there (rms " << rms(r.residual, samples)
        << " against " << rms(r.noise, samples) << ", " << r.noise_origin
        << "; a right model stays " << (above ? "below " : "above ")
        << fixed(above ? r.upper : r.lower, 0, 3) << " but for 0.05 %";
    if (above) err << "; the excess is " << fixed(100 * excess, 0, 2) << " % of the torque there";
    err << "): ";
    if (above) {
      explain_excess(err, wording);
    } else {
      explain_shortfall(err, wording,
                        2 * r.in_band_lines * static_cast<double>(joints.size()) /
                            static_cast<double>(std::max<Eigen::Index>(parameters, 1)));
    }
  }
  return warnings;
}

}  // namespace

int warn_period_residual_against_noise(std::ostream& err, const IdentificationModel& model,
                                       const Experiments& experiments,
                                       const std::vector<Eigen::MatrixXd>& errors,
                                       const ResidualWording& wording) {
  const std::vector<PeriodRecord> periods = compared_periods(experiments, errors);
  if (periods.empty()) return 0;
  double samples = 0;
  for (const PeriodRecord& r : periods) samples += static_cast<double>(r.tau.rows());
  return warn_joints(err, period_residual_against_noise(periods), samples,
                     wording.drive_model ? wording.unknowns : model.num_base_params(), wording);
}

int warn_residual_against_noise(std::ostream& err, const IdentificationModel& model,
                                const Experiments& experiments, const Eigen::VectorXd& beta,
                                const std::string& whose) {
  if (averaged(experiments, 0)) {
    std::vector<Eigen::MatrixXd> errors;
    for (const Trajectory& period : experiments.data) {
      std::vector<Trajectory> one = {period};
      errors.push_back(predict_decimated(model, one, beta, {1}).error.front());
    }
    return warn_period_residual_against_noise(err, model, experiments, errors, plain(whose));
  }
  const std::vector<ResidualRecord> records = compared_records(model, experiments, beta);
  if (records.empty()) return 0;
  double samples = 0;
  for (const ResidualRecord& r : records) samples += static_cast<double>(r.tau.rows());
  return warn_joints(err, residual_against_noise(records), samples, model.num_base_params(),
                     plain(whose));
}

}  // namespace modelgen::internal
