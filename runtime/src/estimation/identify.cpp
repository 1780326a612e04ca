// From trajectories to base-parameter estimates (Gautier & Briot eq. 14-20): the model's
// regressor (IDIM, eq. 4-7: one equation per joint and sample) or power regressor (PIM,
// eq. 9-10: one per sample) evaluated over blocks of samples into a small buffer and reduced at
// once by a LeastSquaresAccumulator, the samples split in two threads; then OLS or WLS and the
// torque errors per axis. Memory: the accumulators' factors and one block per thread, whatever
// the number of samples; W is never stored.

#include "modelgen/estimation/identify.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "modelgen/signal/decimation.hpp"
#include "runtime/src/estimation/identify_covariance.hpp"
#include "runtime/src/estimation/identify_equations.hpp"
#include "runtime/src/estimation/two_parts.hpp"

namespace modelgen {

namespace {

// From this many samples on, the two halves of the samples are processed in two threads.
constexpr Eigen::Index kParallelSamples = 4000;

using detail::build_decimated;
using detail::build_equations;
using detail::DecimatedExperiment;
using detail::Piece;
using detail::Progress;
using detail::split_samples;
using detail::torque_errors;

// The first non-finite value of a trajectory, as an error naming source, sample and column.
void check_finite(const Trajectory& x, int n) {
  const std::pair<const Eigen::MatrixXd*, const char*> columns[] = {
      {&x.q, "q"}, {&x.dq, "dq"}, {&x.ddq, "ddq"}, {&x.tau, "tau"}};
  for (const auto& [a, name] : columns) {
    if (a->allFinite()) continue;
    for (Eigen::Index s = 0; s < a->rows(); ++s) {
      for (int j = 0; j < n; ++j) {
        const double v = (*a)(s, j);
        if (std::isfinite(v)) continue;
        const std::string column = name + std::to_string(j + 1);
        throw EstimationError(SourceLocation{x.source, 0, 0, column},
                              x.source + ": sample " + std::to_string(s + 1) + ": '" + column +
                                  "' is " +
                                  (std::isnan(v) ? "nan"
                                   : v > 0       ? "inf"
                                                 : "-inf") +
                                  "; measured data must be finite");
      }
    }
  }
}

}  // namespace

Method parse_method(const std::string& text) {
  if (text == "ols") return Method::kOls;
  if (text == "wls") return Method::kWls;
  if (text == "pim-wls") return Method::kPimWls;
  throw EstimationError("unknown method '" + text + "': expected ols, wls or pim-wls");
}

Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& data,
                        Method method, const ProgressCallback& progress_callback) {
  IdentifyOptions options;
  options.progress = progress_callback;
  return identify(model, data, method, options);
}

namespace {

// The largest |dq| of each joint of `x`, for messages.
std::string largest_speeds(const Trajectory& x) {
  std::string text;
  for (Eigen::Index j = 0; j < x.dq.cols(); ++j) {
    char value[32];
    std::snprintf(value, sizeof value, "%.3g", x.dq.col(j).cwiseAbs().maxCoeff());
    text += (j == 0 ? "" : ", ") + std::string(value);
  }
  return text;
}

std::string slow_error(const Trajectory& x, const std::vector<double>& min_speed,
                       const std::string& rows) {
  std::string speeds;
  for (std::size_t j = 0; j < min_speed.size(); ++j) {
    char value[32];
    std::snprintf(value, sizeof value, "%.3g", min_speed[j]);
    speeds += (j == 0 ? "" : ", ") + std::string(value);
  }
  return x.source + ": the minimum speed (" + speeds + ") leaves out every " + rows +
         ": in each, some joint is slower (largest |dq| per joint: " + largest_speeds(x) +
         "); give a smaller one";
}

// One finite, nonnegative minimum speed per joint, or none.
void check_min_speed(const std::vector<double>& min_speed, int n) {
  if (min_speed.empty()) return;
  if (static_cast<int>(min_speed.size()) != n) {
    throw EstimationError(std::to_string(min_speed.size()) + " minimum speeds for " +
                          std::to_string(n) + " joints: give one per joint");
  }
  for (const double v : min_speed) {
    if (!(v >= 0) || !std::isfinite(v)) {
      throw EstimationError("a minimum speed must be a finite number >= 0");
    }
  }
}

// Experiments streamed sample by sample lose their slow samples here (counted into
// `slow_samples`); decimated ones lose their slow decimated rows in build_decimated (after
// eq. 13-14).
std::vector<Trajectory> fast_samples(const std::vector<Trajectory>& all,
                                     const IdentifyOptions& options, int n,
                                     Eigen::Index& slow_samples) {
  const std::vector<double>& min_speed = options.min_speed;
  std::vector<Trajectory> fast;
  fast.reserve(all.size());
  for (std::size_t e = 0; e < all.size(); ++e) {
    const Trajectory& x = all[e];
    const bool decimated = e < options.decimation.size() && options.decimation[e] > 1;
    if (decimated || x.dq.rows() != x.t.size() || x.dq.cols() != n) {
      fast.push_back(x);  // decimated, or malformed: the checks below say what is wrong
      continue;
    }
    std::vector<Eigen::Index> kept;
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      if (detail::fast_enough(x.dq.row(s), min_speed)) kept.push_back(s);
    }
    if (kept.empty() && x.t.size() > 0) throw EstimationError(slow_error(x, min_speed, "sample"));
    slow_samples += x.t.size() - static_cast<Eigen::Index>(kept.size());
    Trajectory y = x;
    y.t = x.t(kept);
    for (Eigen::MatrixXd* m : {&y.q, &y.dq, &y.ddq, &y.tau}) *m = (*m)(kept, Eigen::all).eval();
    fast.push_back(std::move(y));
  }
  return fast;
}

// One decimation factor per experiment (1 for all when none are given), each one the filters
// can make and that leaves samples clear of their edges.
std::vector<int> checked_decimation(const std::vector<Trajectory>& data,
                                    const std::vector<int>& given) {
  std::vector<int> decimation = given;
  if (decimation.empty()) decimation.assign(data.size(), 1);
  if (decimation.size() != data.size()) {
    throw EstimationError(std::to_string(decimation.size()) + " decimation factors for " +
                          std::to_string(data.size()) + " experiments: give one per experiment");
  }
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (decimation[e] < 1) {
      throw EstimationError(data[e].source + ": decimation factor " +
                            std::to_string(decimation[e]) + ": it must be at least 1");
    }
    if (decimation[e] > 1) {
      try {
        decimation_stages(decimation[e]);
      } catch (const std::invalid_argument& error) {
        throw EstimationError(data[e].source + ": " + error.what());
      }
    }
    if (decimation[e] > 1 && decimated_interior(data[e].t.size(), decimation[e]).count < 2) {
      throw EstimationError(data[e].source + ": decimation by " + std::to_string(decimation[e]) +
                            " leaves fewer than 2 of its " + std::to_string(data[e].t.size()) +
                            " samples clear of the filter's edges");
    }
  }
  return decimation;
}

// The number of samples of all experiments, each checked for its shape and finite values.
Eigen::Index checked_samples(const std::vector<Trajectory>& data, int n) {
  Eigen::Index samples = 0;
  for (const Trajectory& x : data) {
    if (x.q.cols() != n) {
      throw EstimationError(x.source + ": " + std::to_string(x.q.cols()) +
                            " joints, the model has " + std::to_string(n));
    }
    const Eigen::Index m = x.t.size();
    if (m == 0) throw EstimationError(x.source + ": no samples");
    for (const Eigen::MatrixXd* a : {&x.q, &x.dq, &x.ddq, &x.tau}) {
      if (a->rows() != m || a->cols() != n) {
        throw EstimationError(x.source + ": q, dq, ddq and tau need " + std::to_string(m) +
                              " rows (one per time) and " + std::to_string(n) + " columns");
      }
    }
    check_finite(x, n);
    samples += m;
  }
  return samples;
}

// The accumulator's group names: one per experiment for PIM, one per experiment and joint else.
std::vector<std::string> group_labels(const std::vector<Trajectory>& data, bool power, int n) {
  std::vector<std::string> labels;
  for (const Trajectory& x : data) {
    if (power) {
      labels.push_back(x.source + " (power equations)");
    } else {
      for (int j = 0; j < n; ++j) labels.push_back(x.source + ", joint " + std::to_string(j + 1));
    }
  }
  return labels;
}

// Decimated experiments, one at a time: each needs its whole W before filtering. Returns the
// samples used (decimated rows count per sample), adds the slow rows to `slow_samples`.
Eigen::Index add_decimated(const IdentificationModel& model, const std::vector<Trajectory>& data,
                           const std::vector<int>& decimation, bool power,
                           const std::vector<double>& min_speed,
                           const std::vector<Eigen::Index>& reversal_guard,
                           LeastSquaresAccumulator& equations, Progress& progress,
                           std::vector<DecimatedExperiment>& decimated,
                           Eigen::Index& slow_samples) {
  const int n = model.dof();
  Eigen::Index used_samples = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (decimation[e] == 1) {
      used_samples += data[e].t.size();
      continue;
    }
    decimated.push_back(build_decimated(model, data[e], e, decimation[e], power, min_speed,
                                        e < reversal_guard.size() ? reversal_guard[e] : 0,
                                        equations, progress));
    if (decimated.back().W.rows() == 0) {
      throw EstimationError(slow_error(data[e], min_speed, "decimated row"));
    }
    used_samples += decimated.back().W.rows() / n;
    slow_samples += decimated.back().slow_rows;
  }
  return used_samples;
}

// OLS or WLS on the accumulated equations; an error that may come from the decimation says so.
LeastSquaresResult fit_equations(LeastSquaresAccumulator& equations, Method method,
                                 const std::vector<std::string>& names,
                                 const std::vector<Trajectory>& data,
                                 const std::vector<int>& decimation) {
  try {
    return method == Method::kOls ? equations.fit_ols(names) : equations.fit_wls(names);
  } catch (const EstimationError& e) {
    // Too few equations or an unexcited column may come from the decimation: say so.
    std::string hint;
    for (std::size_t k = 0; k < data.size(); ++k) {
      if (decimation[k] > 1) {
        hint += (hint.empty() ? " (decimated: " : ", ") + data[k].source + " by " +
                std::to_string(decimation[k]);
      }
    }
    if (hint.empty()) throw;
    throw EstimationError(e.where(), std::string(e.what()) + hint +
                          "; a smaller decimation factor keeps more equations)");
  }
}

// The estimate's torque errors and torques per axis, and the error norms of `out`.
void torque_statistics(const IdentificationModel& model, const std::vector<Trajectory>& data,
                       const std::array<std::vector<Piece>, 2>& parts,
                       const std::vector<DecimatedExperiment>& decimated,
                       const LeastSquaresAccumulator& equations, int groups, bool power,
                       bool parallel, Eigen::Index used_samples, Progress& progress,
                       Identification& out) {
  const int n = model.dof();
  Eigen::VectorXd error_squares = Eigen::VectorXd::Zero(n), torque_squares = error_squares;
  if (power) {
    progress.start_pass();
    std::array<Eigen::VectorXd, 2> errors, torques;
    detail::run_two_parts(
        parallel,
        [&](int part, bool caller) {
          torque_errors(model, data, parts[part], out.fit.value, errors[part], torques[part],
                        progress, caller);
        },
        [&progress] { progress.stop(); });
    error_squares = errors[0] + errors[1];
    torque_squares = torques[0] + torques[1];
    // Decimated experiments: their decimated torques against their decimated IDIM rows.
    for (const DecimatedExperiment& d : decimated) {
      const Eigen::VectorXd residual = d.tau - d.W * out.fit.value;
      for (Eigen::Index r = 0; r < residual.size(); ++r) {
        error_squares[r % n] += residual[r] * residual[r];
        torque_squares[r % n] += d.tau[r] * d.tau[r];
      }
    }
  } else {
    // The IDIM's groups are the torque equations of one joint and experiment: their residual
    // norms come from the factors, ||tau_g - W_g beta|| = ||R_g [beta; -1]||.
    for (int g = 0; g < groups; ++g) {
      const double r = equations.residual_norm(g, out.fit.value), y = equations.y_norm(g);
      error_squares[g % n] += r * r;
      torque_squares[g % n] += y * y;
    }
  }
  // Gautier & Briot Tables III-IV: the relative error norm over all torque equations.
  out.torque_rel_error_norm =
      std::sqrt(error_squares.sum()) / std::max(std::sqrt(torque_squares.sum()), 1e-300);
  out.rms_error = (error_squares / static_cast<double>(used_samples)).cwiseSqrt();
  out.rms_torque = (torque_squares / static_cast<double>(used_samples)).cwiseSqrt();
}

}  // namespace

Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& all,
                        Method method, const IdentifyOptions& options) {
  const int n = model.dof(), nb = model.num_base_params();
  if (all.empty()) throw EstimationError("no trajectories: identification needs data");
  const std::vector<double>& min_speed = options.min_speed;
  check_min_speed(min_speed, n);
  std::vector<Trajectory> fast;
  Eigen::Index slow_samples = 0;
  if (!min_speed.empty()) fast = fast_samples(all, options, n, slow_samples);
  const std::vector<Trajectory>& data = min_speed.empty() ? all : fast;
  const std::vector<int> decimation = checked_decimation(data, options.decimation);
  const Eigen::Index samples = checked_samples(data, n);
  const bool power = method == Method::kPimWls;
  const int groups = static_cast<int>(data.size()) * (power ? 1 : n);
  const bool parallel = samples >= kParallelSamples;
  const std::array<std::vector<Piece>, 2> parts = split_samples(data, decimation);
  Progress progress(options.progress, samples);
  progress.report(0.0);

  std::array<LeastSquaresAccumulator, 2> equations = {LeastSquaresAccumulator(nb, groups),
                                                      LeastSquaresAccumulator(nb, groups)};
  detail::run_two_parts(
      parallel,
      [&](int part, bool caller) {
        build_equations(model, data, parts[part], power, equations[part], progress, caller);
      },
      [&progress] { progress.stop(); });
  equations[0].merge(std::move(equations[1]));
  equations[0].name_groups(group_labels(data, power, n));
  std::vector<DecimatedExperiment> decimated;
  const Eigen::Index used_samples =
      add_decimated(model, data, decimation, power, min_speed, options.reversal_guard, equations[0],
                    progress, decimated, slow_samples);

  Identification out;
  out.names = model.base_param_names();
  out.samples = used_samples;
  out.slow_samples = slow_samples;
  out.fit = fit_equations(equations[0], method, out.names, data, decimation);
  torque_statistics(model, data, parts, decimated, equations[0], groups, power, parallel,
                    used_samples, progress, out);
  // Periodic cut torques, filters and decimation make correlated equation errors (issue 31).
  std::vector<int> harmonics = options.torque_harmonics;
  // Samples left out by min_speed break a period: its rows are then no longer circular.
  for (std::size_t e = 0; e < harmonics.size() && e < data.size(); ++e) {
    if (data[e].t.size() != all[e].t.size()) harmonics[e] = -1;
  }
  detail::correct_for_correlation(model, data, decimation, decimated, harmonics, power, out.fit);
  if (options.essential_r_sigma) {
    out.essential = essential_parameters(equations[0], method != Method::kOls, out.names,
                                         *options.essential_r_sigma);
  }
  progress.report(1.0);
  return out;
}

}  // namespace modelgen
