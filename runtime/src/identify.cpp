// From trajectories to base-parameter estimates (Gautier & Briot eq. 14-20): the model's
// regressor (IDIM, eq. 4-7: one equation per joint and sample) or power regressor (PIM,
// eq. 9-10: one per sample) evaluated over blocks of samples into a small buffer and reduced at
// once by a LeastSquaresAccumulator, the samples split in two threads; then OLS or WLS and the
// torque errors per axis. Memory: the accumulators' factors and one block per thread, whatever
// the number of samples; W is never stored.

#include "modelgen/identify.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/decimation.hpp"
#include "runtime/src/two_parts.hpp"

namespace modelgen {

namespace {

// Samples whose regressors are evaluated before their rows are handed to the accumulator: the
// block (samples x dof x base parameters) stays in cache; 128 measured as fast as 64..512.
constexpr Eigen::Index kChunkSamples = 128;
// From this many samples on, the two halves of the samples are processed in two threads.
constexpr Eigen::Index kParallelSamples = 4000;
// Parts of the progress: the pass that builds and reduces the equations ends at kBuilt, the
// PIM's torque-error pass (inverse dynamics per sample) at kPredicted, the fit at 1.
constexpr double kBuilt = 0.9, kPredicted = 0.98;

// A run of samples [begin, end) of one experiment.
struct Piece {
  std::size_t experiment;
  Eigen::Index begin, end;
};

// The samples of the experiments that are streamed (not decimated) in order, cut into two
// halves of (nearly) equal size.
std::array<std::vector<Piece>, 2> split_samples(const std::vector<Trajectory>& data,
                                                const std::vector<int>& decimation) {
  std::array<std::vector<Piece>, 2> parts;
  Eigen::Index samples = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (decimation[e] == 1) samples += data[e].t.size();
  }
  const Eigen::Index half = samples / 2;
  Eigen::Index start = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (decimation[e] != 1) continue;
    const Eigen::Index m = data[e].t.size();
    const Eigen::Index cut = std::clamp<Eigen::Index>(half - start, 0, m);
    if (cut > 0) parts[0].push_back({e, 0, cut});
    if (cut < m) parts[1].push_back({e, cut, m});
    start += m;
  }
  return parts;
}

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

// q, dq, ddq of sample s as the model's functions take them.
struct State {
  explicit State(int n) : values(3 * static_cast<std::size_t>(n)), n(n) {}
  void load(const Trajectory& x, Eigen::Index s) {
    for (int j = 0; j < n; ++j) {
      values[j] = x.q(s, j);
      values[n + j] = x.dq(s, j);
      values[2 * n + j] = x.ddq(s, j);
    }
  }
  const double* q() const { return values.data(); }
  const double* dq() const { return values.data() + n; }
  const double* ddq() const { return values.data() + 2 * n; }
  std::vector<double> values;
  int n;
};

// The equations of `pieces` into `equations`: IDIM rows of joint j of experiment e in group
// e * dof + j, PIM rows of experiment e in group e.
void build_equations(const IdentificationModel& model, const std::vector<Trajectory>& data,
                     const std::vector<Piece>& pieces, bool power,
                     LeastSquaresAccumulator& equations, Progress& progress, bool caller) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index width = power ? nb : static_cast<Eigen::Index>(n) * nb;
  std::vector<double> block(static_cast<std::size_t>(kChunkSamples * width));
  std::vector<double> power_in(static_cast<std::size_t>(kChunkSamples));
  State state(n);
  for (const Piece& piece : pieces) {
    const Trajectory& x = data[piece.experiment];
    const int experiment = static_cast<int>(piece.experiment);
    for (Eigen::Index s0 = piece.begin; s0 < piece.end; s0 += kChunkSamples) {
      if (progress.stopped()) return;
      const Eigen::Index count = std::min(kChunkSamples, piece.end - s0);
      for (Eigen::Index i = 0; i < count; ++i) {
        state.load(x, s0 + i);
        double* row = block.data() + i * width;
        if (power) {
          model.power_regressor(state.q(), state.dq(), state.ddq(), row);
          // Eq. 9: the power delivered by the joints, P = dq . tau.
          double p = 0;
          for (int j = 0; j < n; ++j) p += state.dq()[j] * x.tau(s0 + i, j);
          power_in[static_cast<std::size_t>(i)] = p;
        } else {
          // Eq. 6: tau = W(q, dq, ddq) beta, row-major dof x nb.
          model.regressor(state.q(), state.dq(), state.ddq(), row);
        }
      }
      if (power) {
        equations.add(experiment, count, block.data(), nb, 1, power_in.data(), 1);
      } else {
        for (int j = 0; j < n; ++j) {
          equations.add(experiment * n + j, count, block.data() + static_cast<Eigen::Index>(j) * nb,
                        width, 1, &x.tau(s0, j), 1);
        }
      }
      progress.advance(count, 0.0, kBuilt, caller);
    }
    // The experiment's groups are complete in this part: only their factors need to stay.
    equations.compact();
  }
}

// One experiment's equations after the parallel decimation (eq. 13-14): the IDIM rows
// (decimated samples x dof, rows s * dof + j) and torques, kept for the torque errors.
struct DecimatedExperiment {
  std::size_t experiment = 0;
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
};

// A view of joint j's rows (every dof-th row from row j) of a stacked column-major matrix.
using JointRows = Eigen::Map<Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
JointRows joint_rows(double* data, Eigen::Index stacked_rows, Eigen::Index cols, int n, int j) {
  return JointRows(data + j, stacked_rows / n, cols,
                   Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(stacked_rows, n));
}

// Builds experiment e's whole IDIM W and torques, decimates every column of each joint's rows
// and the torques with the same filter, and adds the result to `equations` (and, for the PIM,
// the power rows dq^T W with the powers dq . tau, decimated the same way: both are linear in
// the rows they combine, so the decimated equations still hold, eq. 14).
DecimatedExperiment build_decimated(const IdentificationModel& model, const Trajectory& x,
                                    std::size_t e, int factor, bool power,
                                    LeastSquaresAccumulator& equations, Progress& progress) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index m = x.t.size(), md = decimated_rows(m, factor);
  Eigen::MatrixXd W(m * n, nb);
  Eigen::VectorXd tau(m * n);
  Eigen::MatrixXd P(power ? m : 0, nb);
  Eigen::VectorXd p(power ? m : 0);
  State state(n);
  std::vector<double> rows(static_cast<std::size_t>(n) * nb);
  for (Eigen::Index s = 0; s < m; ++s) {
    state.load(x, s);
    model.regressor(state.q(), state.dq(), state.ddq(), rows.data());
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        Ws(rows.data(), n, nb);
    W.middleRows(s * n, n) = Ws;
    tau.segment(s * n, n) = x.tau.row(s).transpose();
    if (power) {
      // Eq. 9-10 before decimation: P = dq . tau = dq^T W beta.
      P.row(s) = x.dq.row(s) * Ws;
      p[s] = x.dq.row(s).dot(x.tau.row(s));
    }
    if ((s + 1) % kChunkSamples == 0) progress.advance(kChunkSamples, 0.0, kBuilt, true);
  }
  progress.advance(m % kChunkSamples, 0.0, kBuilt, true);
  DecimatedExperiment out{e, Eigen::MatrixXd(md * n, nb), Eigen::VectorXd(md * n)};
  for (int j = 0; j < n; ++j) {
    decimate(joint_rows(W.data(), W.rows(), nb, n, j), factor,
             joint_rows(out.W.data(), out.W.rows(), nb, n, j));
    decimate(joint_rows(tau.data(), tau.size(), 1, n, j), factor,
             joint_rows(out.tau.data(), out.tau.size(), 1, n, j));
  }
  const int experiment = static_cast<int>(e);
  if (power) {
    const Eigen::MatrixXd Pd = decimate(P, factor);
    const Eigen::MatrixXd pd = decimate(p, factor);
    equations.add(experiment, md, Pd.data(), 1, Pd.rows(), pd.data(), 1);
  } else {
    for (int j = 0; j < n; ++j) {
      equations.add(experiment * n + j, md, out.W.data() + j, n, out.W.rows(), out.tau.data() + j,
                    n);
    }
  }
  equations.compact();
  return out;
}

// Per joint, sums of squares of measured minus predicted torque and of measured torque over
// `pieces`, the prediction from model.inverse_dynamics (the PIM's equations are not torques).
void torque_errors(const IdentificationModel& model, const std::vector<Trajectory>& data,
                   const std::vector<Piece>& pieces, const Eigen::VectorXd& beta,
                   Eigen::VectorXd& error_squares, Eigen::VectorXd& torque_squares,
                   Progress& progress, bool caller) {
  const int n = model.dof();
  State state(n);
  std::vector<double> predicted(static_cast<std::size_t>(n));
  error_squares = Eigen::VectorXd::Zero(n);
  torque_squares = Eigen::VectorXd::Zero(n);
  for (const Piece& piece : pieces) {
    const Trajectory& x = data[piece.experiment];
    for (Eigen::Index s0 = piece.begin; s0 < piece.end; s0 += kChunkSamples) {
      if (progress.stopped()) return;
      const Eigen::Index stop = std::min(piece.end, s0 + kChunkSamples);
      for (Eigen::Index s = s0; s < stop; ++s) {
        state.load(x, s);
        model.inverse_dynamics(state.q(), state.dq(), state.ddq(), beta.data(), predicted.data());
        for (int j = 0; j < n; ++j) {
          const double e = x.tau(s, j) - predicted[static_cast<std::size_t>(j)];
          error_squares[j] += e * e;
          torque_squares[j] += x.tau(s, j) * x.tau(s, j);
        }
      }
      progress.advance(stop - s0, kBuilt, kPredicted, caller);
    }
  }
}

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
        throw EstimationError(x.source + ": sample " + std::to_string(s + 1) + ": '" + name +
                              std::to_string(j + 1) + "' is " +
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

Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& data,
                        Method method, const IdentifyOptions& options) {
  const int n = model.dof(), nb = model.num_base_params();
  if (data.empty()) throw EstimationError("no trajectories: identification needs data");
  std::vector<int> decimation = options.decimation;
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
    if (decimation[e] > 1 && decimated_rows(data[e].t.size(), decimation[e]) < 2) {
      throw EstimationError(data[e].source + ": decimation by " + std::to_string(decimation[e]) +
                            " leaves fewer than 2 of its " + std::to_string(data[e].t.size()) +
                            " samples");
    }
  }
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
  const bool power = method == Method::kPimWls;
  const int groups = static_cast<int>(data.size()) * (power ? 1 : n);
  const bool parallel = samples >= kParallelSamples;
  const std::array<std::vector<Piece>, 2> parts = split_samples(data, decimation);
  Progress progress(options.progress, samples);
  progress.report(0.0);

  std::array<LeastSquaresAccumulator, 2> equations = {LeastSquaresAccumulator(nb, groups),
                                                      LeastSquaresAccumulator(nb, groups)};
  internal::run_two_parts(
      parallel,
      [&](int part, bool caller) {
        build_equations(model, data, parts[part], power, equations[part], progress, caller);
      },
      [&progress] { progress.stop(); });
  equations[0].merge(std::move(equations[1]));
  std::vector<std::string> labels;
  for (const Trajectory& x : data) {
    if (power) {
      labels.push_back(x.source + " (power equations)");
    } else {
      for (int j = 0; j < n; ++j) labels.push_back(x.source + ", joint " + std::to_string(j + 1));
    }
  }
  equations[0].name_groups(std::move(labels));
  // Decimated experiments, one at a time: each needs its whole W before filtering.
  std::vector<DecimatedExperiment> decimated;
  Eigen::Index used_samples = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (decimation[e] == 1) {
      used_samples += data[e].t.size();
      continue;
    }
    decimated.push_back(
        build_decimated(model, data[e], e, decimation[e], power, equations[0], progress));
    used_samples += decimated.back().W.rows() / n;
  }

  Identification out;
  out.names = model.base_param_names();
  out.samples = used_samples;
  try {
    out.fit =
        method == Method::kOls ? equations[0].fit_ols(out.names) : equations[0].fit_wls(out.names);
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
    throw EstimationError(std::string(e.what()) + hint +
                          "; a smaller decimation factor keeps more equations)");
  }
  Eigen::VectorXd error_squares = Eigen::VectorXd::Zero(n), torque_squares = error_squares;
  if (power) {
    progress.start_pass();
    std::array<Eigen::VectorXd, 2> errors, torques;
    internal::run_two_parts(
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
      const double r = equations[0].residual_norm(g, out.fit.value), y = equations[0].y_norm(g);
      error_squares[g % n] += r * r;
      torque_squares[g % n] += y * y;
    }
  }
  // Gautier & Briot Tables III-IV: the relative error norm over all torque equations.
  out.torque_rel_error_norm =
      std::sqrt(error_squares.sum()) / std::max(std::sqrt(torque_squares.sum()), 1e-300);
  out.rms_error = (error_squares / static_cast<double>(used_samples)).cwiseSqrt();
  out.rms_torque = (torque_squares / static_cast<double>(used_samples)).cwiseSqrt();
  if (options.essential_r_sigma) {
    out.essential = essential_parameters(equations[0], method != Method::kOls, out.names,
                                         *options.essential_r_sigma);
  }
  progress.report(1.0);
  return out;
}

}  // namespace modelgen
