// Building identify()'s equations: the model's functions called per sample into a small block,
// the block handed to the accumulator; decimated experiments built whole, then filtered.

#include "runtime/src/estimation/identify_equations.hpp"

#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/reversal_mask.hpp"

namespace modelgen::detail {

namespace {

// Samples whose regressors are evaluated before their rows are handed to the accumulator: the
// block (samples x dof x base parameters) stays in cache; 128 measured as fast as 64..512.
constexpr Eigen::Index kChunkSamples = 128;
// Parts of the progress: the pass that builds and reduces the equations ends at kBuilt, the
// PIM's torque-error pass (inverse dynamics per sample) at kPredicted, the fit at 1.
constexpr double kBuilt = 0.9, kPredicted = 0.98;

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

// A view of joint j's rows (every dof-th row from row j) of a stacked column-major matrix.
using JointRows = Eigen::Map<Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
JointRows joint_rows(double* data, Eigen::Index stacked_rows, Eigen::Index cols, int n, int j) {
  return JointRows(data + j, stacked_rows / n, cols,
                   Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(stacked_rows, n));
}

}  // namespace

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

void build_equations(const IdentificationModel& model, const std::vector<Trajectory>& data,
                     const std::vector<Piece>& pieces, bool power,
                     LeastSquaresAccumulator& equations, Progress& progress, bool caller) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index width = power ? nb : static_cast<Eigen::Index>(n) * nb;
  // Zeroed once here and written by one function only (regressor or power_regressor), so that
  // a regressor storing only its structurally nonzero entries needs no zeroing per sample
  // (GeneratedModel still zeroes its output per call: IdentificationModel's contract is dense).
  std::vector<double> block(static_cast<std::size_t>(kChunkSamples * width), 0.0);
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

DecimatedExperiment build_decimated(const IdentificationModel& model, const Trajectory& x,
                                    std::size_t e, int factor, bool power,
                                    const std::vector<double>& min_speed,
                                    Eigen::Index reversal_guard, LeastSquaresAccumulator& equations,
                                    Progress& progress) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index m = x.t.size();
  Eigen::Index md = decimated_rows(m, factor);
  Eigen::MatrixXd W(m * n, nb);
  Eigen::VectorXd tau(m * n);
  Eigen::MatrixXd P(power ? m : 0, nb);
  Eigen::VectorXd p(power ? m : 0);
  State state(n);
  std::vector<double> rows(static_cast<std::size_t>(n) * nb, 0.0);  // zeroed once, as above
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
  if (!min_speed.empty()) {
    // Zeroing both sides of an equation keeps it exact through the linear decimation filter;
    // dropping decimated rows alone would keep the samples near rest inside each row's window.
    const Eigen::ArrayXXd mask =
        reversal_mask(x.dq, model.drive_chain().motor_from_joint,
                      Eigen::Map<const Eigen::VectorXd>(min_speed.data(), n), reversal_guard);
    for (Eigen::Index s = 0; s < m; ++s) {
      for (int j = 0; j < n; ++j) {
        const double w = mask(s, j);
        if (w == 1) continue;
        if (power) {  // the power equation keeps w of joint j's share, dq_j (W_j beta = tau_j)
          P.row(s) -= (1 - w) * x.dq(s, j) * W.row(s * n + j);
          p[s] -= (1 - w) * x.dq(s, j) * tau[s * n + j];
        }
        W.row(s * n + j) *= w;
        tau[s * n + j] *= w;
      }
    }
  }
  DecimatedExperiment out{e, Eigen::MatrixXd(md * n, nb), Eigen::VectorXd(md * n)};
  for (int j = 0; j < n; ++j) {
    decimate(joint_rows(W.data(), W.rows(), nb, n, j), factor,
             joint_rows(out.W.data(), out.W.rows(), nb, n, j));
    decimate(joint_rows(tau.data(), tau.size(), 1, n, j), factor,
             joint_rows(out.tau.data(), out.tau.size(), 1, n, j));
  }
  // Only the rows the end samples do not dominate (decimated_interior), the same for W, tau
  // and the power equations.
  const DecimatedRange kept = decimated_interior(m, factor);
  // And, with a minimum speed, the rows where a joint is slower, dq decimated alike.
  std::vector<Eigen::Index> rows_kept;
  const Eigen::MatrixXd dq_d =
      min_speed.empty() ? Eigen::MatrixXd() : decimate_interior(x.dq, factor);
  for (Eigen::Index i = 0; i < kept.count; ++i) {
    if (min_speed.empty() || fast_enough(dq_d.row(i), min_speed)) rows_kept.push_back(i);
  }
  md = static_cast<Eigen::Index>(rows_kept.size());
  out.slow_rows = kept.count - md;
  Eigen::MatrixXd W_kept(md * n, nb);
  Eigen::VectorXd tau_kept(md * n);
  for (Eigen::Index r = 0; r < md; ++r) {
    const Eigen::Index from = (kept.first + rows_kept[r]) * n;
    W_kept.middleRows(r * n, n) = out.W.middleRows(from, n);
    tau_kept.segment(r * n, n) = out.tau.segment(from, n);
  }
  out.W = std::move(W_kept);
  out.tau = std::move(tau_kept);
  const int experiment = static_cast<int>(e);
  if (md == 0) return out;  // identify() says which experiment lost every row
  if (power) {
    const Eigen::MatrixXd P_all = decimate_interior(P, factor);
    const Eigen::MatrixXd p_all = decimate_interior(p, factor);
    Eigen::MatrixXd Pd(md, nb);
    Eigen::VectorXd pd(md);
    for (Eigen::Index r = 0; r < md; ++r) {
      Pd.row(r) = P_all.row(rows_kept[r]);
      pd[r] = p_all(rows_kept[r], 0);
    }
    equations.add(experiment, md, Pd.data(), 1, Pd.rows(), pd.data(), 1);
    out.P = std::move(Pd);
    out.p = std::move(pd);
  } else {
    for (int j = 0; j < n; ++j) {
      equations.add(experiment * n + j, md, out.W.data() + j, n, out.W.rows(), out.tau.data() + j,
                    n);
    }
  }
  equations.compact();
  return out;
}

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

}  // namespace modelgen::detail
