// The equations identify() reduces, built sample block by sample block from the model's
// regressor (IDIM, Gautier & Briot eq. 4-7) or power regressor (PIM, eq. 9-10), whole and
// decimated for the parallel decimation (eq. 13-14); the torque errors of the PIM fit; and the
// progress both threads report to.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/accumulator.hpp"
#include "modelgen/estimation/progress.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::detail {

// A run of samples [begin, end) of one experiment.
struct Piece {
  std::size_t experiment;
  Eigen::Index begin, end;
};

// The samples of the experiments that are streamed (not decimated) in order, cut into two
// halves of (nearly) equal size.
std::array<std::vector<Piece>, 2> split_samples(const std::vector<Trajectory>& data,
                                                const std::vector<int>& decimation);

// Samples done by both threads, a stop flag, and the reports to the caller's callback, made by
// the calling thread only, once per percent at most.
class Progress {
 public:
  Progress(const ProgressCallback& callback, Eigen::Index samples)
      : callback_(callback), samples_(static_cast<double>(std::max<Eigen::Index>(samples, 1))) {}

  // Adds `count` samples to the pass that spans [from, to) of the work; reports if `caller`.
  void advance(Eigen::Index count, double from, double to, bool caller) {
    const Eigen::Index done = done_.fetch_add(count) + count;
    if (caller) report(from + (to - from) * static_cast<double>(done) / samples_);
  }
  void start_pass() { done_ = 0; }
  void report(double fraction) {
    if (!callback_) return;
    const int percent = static_cast<int>(std::floor(100 * std::min(fraction, 1.0)));
    if (percent <= last_percent_) return;
    last_percent_ = percent;
    callback_(fraction);
  }
  void stop() { stop_ = true; }
  bool stopped() const { return stop_; }

 private:
  const ProgressCallback& callback_;
  double samples_;
  std::atomic<Eigen::Index> done_{0};
  std::atomic<bool> stop_{false};
  int last_percent_ = -1;
};

// The equations of `pieces` into `equations`: IDIM rows of joint j of experiment e in group
// e * dof + j, PIM rows of experiment e in group e.
void build_equations(const IdentificationModel& model, const std::vector<Trajectory>& data,
                     const std::vector<Piece>& pieces, bool power,
                     LeastSquaresAccumulator& equations, Progress& progress, bool caller);

// One experiment's equations after the parallel decimation (eq. 13-14): the IDIM rows
// (decimated samples x dof, rows s * dof + j) and torques, kept for the torque errors.
struct DecimatedExperiment {
  std::size_t experiment = 0;
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  Eigen::MatrixXd P;  ///< PIM: the decimated power rows kept (eq. 9-10), else empty
  Eigen::VectorXd p;
  Eigen::Index slow_rows = 0;
};

// Whether every joint of `dq` (one row) moves at least at its min_speed (empty: true).
inline bool fast_enough(const Eigen::Ref<const Eigen::RowVectorXd>& dq,
                        const std::vector<double>& min_speed) {
  for (std::size_t j = 0; j < min_speed.size(); ++j) {
    if (std::abs(dq[static_cast<Eigen::Index>(j)]) < min_speed[j]) return false;
  }
  return true;
}

// Builds experiment e's whole IDIM W and torques, decimates every column of each joint's rows
// and the torques with the same filter, and adds the result to `equations` (and, for the PIM,
// the power rows dq^T W with the powers dq . tau, decimated the same way: both are linear in
// the rows they combine, so the decimated equations still hold, eq. 14).
// With `min_speed` (one per joint, or empty), the decimated rows where a joint's decimated
// |dq| is below its value are left out too (DecimatedExperiment::slow_rows counts them), and
// before the decimation each joint's equations near a reversal are zeroed on both sides
// (reversal_mask with `reversal_guard`, modelgen/signal/reversal_mask.hpp).
DecimatedExperiment build_decimated(const IdentificationModel& model, const Trajectory& x,
                                    std::size_t e, int factor, bool power,
                                    const std::vector<double>& min_speed,
                                    Eigen::Index reversal_guard, LeastSquaresAccumulator& equations,
                                    Progress& progress);

// Per joint, sums of squares of measured minus predicted torque and of measured torque over
// `pieces`, the prediction from model.inverse_dynamics (the PIM's equations are not torques).
void torque_errors(const IdentificationModel& model, const std::vector<Trajectory>& data,
                   const std::vector<Piece>& pieces, const Eigen::VectorXd& beta,
                   Eigen::VectorXd& error_squares, Eigen::VectorXd& torque_squares,
                   Progress& progress, bool caller);

}  // namespace modelgen::detail
