// The records of fit --method pm: prepared rows located in the raw samples, the reference from
// the raw file; the FIR's order, decorrelation test and discarded torque reported.

#include "runtime/cli/fit/projection_fit.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

#include "modelgen/closed_loop/projection_method.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/fit/friction_compensation.hpp"

namespace modelgen::internal {

namespace {

// --fir-lags M: an integer >= 0.
int fir_lags(const std::string& text) {
  std::size_t used = 0;
  int value = -1;
  try {
    value = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || value < 0) {
    throw UsageError{
        "--fir-lags must be a whole number >= 0 (the FIR's lags M on each side), "
        "not '" +
        text + "'"};
  }
  return value;
}

}  // namespace

Identification fit_projection(const CommandLine& args, const IdentificationModel& model,
                              const Experiments& experiments, const std::vector<double>& min_speed,
                              std::ostream& report, std::ostream& log) {
  ProjectionOptions options;
  if (args.has("--fir-lags")) options.fir_lags = fir_lags(args.one("--fir-lags"));
  options.min_speed = min_speed;
  const std::vector<std::string>& paths = args.all("--data");
  std::vector<ProjectionRecord> records;
  for (std::size_t e = 0; e < paths.size(); ++e) {
    const Trajectory& raw = experiments.raw[e];  // read with the preparation, not again
    if (raw.qr.size() == 0) {
      throw DataError(paths[e] +
                      ": error: the projection method (--method pm) needs the "
                      "reference positions of the record, columns qr1..qr" +
                      std::to_string(model.dof()) + " (modelid simulate --controller writes them)");
    }
    ProjectionRecord record;
    record.prepared = experiments.data[e];
    record.decimation = experiments.decimation[e];
    record.torque_hold = args.has("--torque-hold") && args.one("--torque-hold") == "zoh";
    record.qr = raw.qr;
    // The prepared rows are raw rows first_row...: the reference is delayed and decimated on
    // the same rows as the torque. A record preparation resampled has no such rows.
    const Eigen::Index samples = raw.t.size(), used = record.prepared.t.size();
    const double dt = (raw.t[samples - 1] - raw.t[0]) / static_cast<double>(samples - 1);
    record.first_row = std::lround((record.prepared.t[0] - raw.t[0]) / dt);
    const Eigen::Index last = record.first_row + used - 1;
    if (record.first_row < 0 || last >= samples ||
        std::abs(raw.t[record.first_row] - record.prepared.t[0]) > 0.01 * dt ||
        std::abs(raw.t[last] - record.prepared.t[used - 1]) > 0.01 * dt) {
      throw DataError(paths[e] +
                      ": error: the projection method needs uniformly sampled "
                      "records (the preparation resampled this one), to delay the reference "
                      "on the torque's own samples");
    }
    records.push_back(std::move(record));
  }
  // Bona & Curatella 3.4: friction compensated before projecting (no FIR from the references
  // makes sign(dq)), with the friction of a first IDIM-WLS; added back to u^ for stage 2.
  const std::vector<Eigen::MatrixXd> friction = friction_torques(model, records, min_speed);
  for (std::size_t e = 0; e < records.size(); ++e) records[e].prepared.tau -= friction[e];
  const auto start = std::chrono::steady_clock::now();
  ProjectedRecords result = project_records(model.dof(), records, options.fir_lags);
  for (std::size_t e = 0; e < records.size(); ++e) {
    records[e].prepared.tau += friction[e];
    result.projected[e] += friction[e];
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream stage1;
  const DecorrelationTest& test = result.test;
  stage1 << "  friction compensated first (Bona & Curatella 3.4): the viscous and Coulomb "
            "friction of a first IDIM-WLS taken out of the torque before the projection and "
            "added back to u^\n";
  stage1 << "  projection (Bona & Curatella eq. 10-12): non-causal FIR of lags -" << result.lags
         << ".." << result.lags << " (decimated samples) from the references, "
         << (result.forced ? "M given by --fir-lags"
                           : "M chosen by the decorrelation and residual tests")
         << ", fitted in " << fixed(seconds, 0, 3) << " s; then IDIM-WLS on the projected torque\n"
         << "  decorrelation test: largest |correlation| of u - u^ with a reference at lags up "
            "to "
         << test.window << " is " << fixed(test.worst, 0, 4) << " (joint " << test.worst_channel + 1
         << ", reference " << test.worst_reference + 1 << ", lag " << test.worst_lag << "); band "
         << fixed(test.band, 0, 4) << " (the largest of " << test.tested
         << " white-noise correlations stays within it 99 times in 100; one "
         << "stays within " << fixed(test.single_band, 0, 4)
         << "): " << (test.passed() ? "passed" : "NOT passed") << "\n";
  if (!result.forced && result.tried.size() > 1) {
    stage1 << "    M tried (largest |correlation|):";
    for (const auto& [lags, worst] : result.tried)
      stage1 << " " << lags << " (" << fixed(worst, 0, 4) << ")";
    stage1 << "\n";
  }
  stage1 << "  torque discarded by the projection, ||u - u^|| / ||u|| per joint (u friction-"
            "compensated):";
  for (Eigen::Index j = 0; j < result.discarded.size(); ++j) {
    stage1 << " " << fixed(100 * result.discarded[j], 0, 3) << "%";
  }
  stage1 << "; all joints " << fixed(100 * result.discarded_total, 0, 3) << "%\n"
         << "  (the rms and relative errors below compare the model with the projected torque)\n";
  if (!result.decorrelated) {
    log << "modelid: warning: the projection's residual stays correlated with the references ("
        << fixed(test.worst, 0, 3) << " above the band " << fixed(test.band, 0, 3) << ") "
        << (result.forced ? "at the M of --fir-lags" : "at the largest M the samples allow")
        << ": the FIR misses part of what the references explain\n";
  }
  if (result.discarded_total > kDiscardedWarning) {
    log << "modelid: warning: the projection discards " << fixed(100 * result.discarded_total, 0, 3)
        << "% of the torque norm (more than " << fixed(100 * kDiscardedWarning, 0, 3)
        << "%): a linear FIR from the references keeps only the torque at the references' "
           "harmonics; on a multi-joint nonlinear robot the rest of the torque is lost and the "
           "estimate is biased, even with the friction compensated first as here. Move one "
           "joint at a time, as Bona & Curatella did (section 3.2), or use --method iv or "
           "didim\n";
  }
  // Stage 2; when it fails, what stage 1 found is still worth seeing.
  try {
    Identification id = identify_projected(model, records, result, options.min_speed);
    report << stage1.str();
    return id;
  } catch (const EstimationError&) {
    log << "modelid fit: the projection (stage 1) before the identification failed:\n"
        << stage1.str();
    throw;
  }
}

}  // namespace modelgen::internal
