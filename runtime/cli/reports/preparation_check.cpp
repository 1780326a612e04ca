// The out-of-band residual test of a fit's preparation.

#include "runtime/cli/reports/preparation_check.hpp"

#include <vector>

#include "modelgen/estimation/predict.hpp"
#include "modelgen/signal/band_power.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

int warn_residual_outside_band(std::ostream& err, const IdentificationModel& model,
                               const Experiments& experiments, const Eigen::VectorXd& beta) {
  int warnings = 0;
  for (std::size_t e = 0; e < experiments.data.size(); ++e) {
    const double band = experiments.bandwidth_hz[e];
    if (!(band > 0)) continue;
    std::vector<Trajectory> one = {experiments.data[e]};
    const TorquePrediction prediction =
        predict_decimated(model, one, beta, {experiments.decimation[e]});
    const Trajectory& x = one.front();
    if (x.t.size() < 4) continue;
    const double dt = (x.t[x.t.size() - 1] - x.t[0]) / static_cast<double>(x.t.size() - 1);
    const double torque = power_above(x.tau, dt, band);
    const double residual = power_above(prediction.error.front(), dt, band);
    if (!(residual > kOutOfBandExcess * torque)) continue;
    ++warnings;
    err << "modelid fit: warning: " << x.source << ": above the " << fixed(band, 0, 3)
        << " Hz excitation bandwidth the residual has " << fixed(residual / torque, 0, 3)
        << " times the power of the measured torques: the regressor carries content the torques "
           "do not (differentiated position noise); the positions were likely filtered too "
           "little for this excitation: check --bandwidth/--cutoff, or the bandwidth estimate\n";
  }
  return warnings;
}

}  // namespace modelgen::internal
