// identify()'s standard deviations when its equation errors are correlated (issue 31): periodic
// experiments whose torques were cut at a harmonic, and filtered, decimated or closed-loop
// records whose residuals stay correlated from row to row. The weighted rows of every joint and
// experiment are rebuilt (W is not kept by the fit) and the sandwich of
// correlated_covariance.hpp replaces eq. 18. Undecimated records of any length are streamed:
// their residuals first, and their scores only when some group needs the sandwich.

#include "runtime/src/estimation/identify_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "runtime/src/estimation/correlated_covariance.hpp"

namespace modelgen::detail {

namespace {

// Experiment e's IDIM rows of joint j, one per sample, from the model's regressor.
std::vector<Eigen::MatrixXd> sample_rows(const IdentificationModel& model, const Trajectory& x) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index m = x.t.size();
  std::vector<Eigen::MatrixXd> W(static_cast<std::size_t>(n), Eigen::MatrixXd(m, nb));
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows =
      Eigen::MatrixXd::Zero(n, nb);
  for (Eigen::Index s = 0; s < m; ++s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    model.regressor(q.data(), dq.data(), ddq.data(), rows.data());
    for (int j = 0; j < n; ++j) W[static_cast<std::size_t>(j)].row(s) = rows.row(j);
  }
  return W;
}

// Each joint's weighted residual of experiment x, one row per sample.
Eigen::MatrixXd sample_residuals(const IdentificationModel& model, const Trajectory& x,
                                 const Eigen::VectorXd& beta, const Eigen::VectorXd& sigma) {
  const int n = model.dof(), nb = model.num_base_params();
  Eigen::MatrixXd residual(x.t.size(), n);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(n, nb);
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    model.regressor(q.data(), dq.data(), ddq.data(), rows.data());
    residual.row(s) =
        ((x.tau.row(s).transpose() - rows * beta).array() / sigma.array()).transpose();
  }
  return residual;
}

// An undecimated, non-periodic experiment's residuals and their correlation.
struct StreamedResiduals {
  std::size_t experiment = 0;
  Eigen::VectorXd sigma;
  Eigen::MatrixXd residual;
  Correlation correlation;
};

StreamedResiduals streamed_residuals(const IdentificationModel& model, const Trajectory& x,
                                     std::size_t e, const LeastSquaresResult& fit) {
  const int n = model.dof();
  StreamedResiduals out;
  out.experiment = e;
  out.sigma = Eigen::VectorXd::Ones(n);
  for (int j = 0; j < n; ++j) {
    const std::size_t g = e * static_cast<std::size_t>(n) + static_cast<std::size_t>(j);
    if (g < fit.group_std_dev.size()) out.sigma[j] = fit.group_std_dev[g];
  }
  out.residual = sample_residuals(model, x, fit.value, out.sigma);
  const Eigen::Index m = out.residual.rows();
  const double lag =
      m < 2 ? 0.0
            : (out.residual.topRows(m - 1).array() * out.residual.bottomRows(m - 1).array()).sum();
  out.correlation = residual_correlation(lag, out.residual.squaredNorm(), m * n, n);
  return out;
}

// Its scores x_t r_t summed with its own bandwidth (0 when its residuals are white), by a second
// regressor pass: the rows are never held.
StreamedMeat streamed_meat(const IdentificationModel& model, const Trajectory& x,
                           const StreamedResiduals& r) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index m = r.residual.rows();
  const int L = static_cast<int>(std::min<Eigen::Index>(r.correlation.bandwidth, m - 1));
  std::vector<BartlettScoreSum> sums(static_cast<std::size_t>(n), BartlettScoreSum(nb, L));
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(n, nb);
  for (Eigen::Index s = 0; s < m; ++s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    model.regressor(q.data(), dq.data(), ddq.data(), rows.data());
    for (int j = 0; j < n; ++j) {
      sums[static_cast<std::size_t>(j)].add(rows.row(j).transpose() *
                                            (r.residual(s, j) / r.sigma[j]));
    }
  }
  StreamedMeat out;
  out.rows = m * n;
  out.correlation = r.correlation;
  out.meat = Eigen::MatrixXd::Zero(nb, nb);
  for (const BartlettScoreSum& sum : sums) out.meat += sum.meat();
  return out;
}

}  // namespace

void correct_for_correlation(const IdentificationModel& model, const std::vector<Trajectory>& data,
                             const std::vector<int>& decimation,
                             const std::vector<DecimatedExperiment>& decimated,
                             const std::vector<int>& harmonics, LeastSquaresResult& fit) {
  const int n = model.dof();
  const Eigen::Index b = fit.value.size();
  std::vector<ResidualGroup> groups;
  std::vector<StreamedResiduals> streamed;
  std::size_t next_decimated = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (decimation[e] == 1 && !(e < harmonics.size() && harmonics[e] >= 0)) {
      streamed.push_back(streamed_residuals(model, data[e], e, fit));
      continue;
    }
    std::vector<Eigen::MatrixXd> W;
    std::vector<Eigen::VectorXd> y;
    if (decimation[e] > 1) {
      const DecimatedExperiment& d = decimated[next_decimated++];
      for (int j = 0; j < n; ++j) {
        const Eigen::Index rows = d.W.rows() / n;
        W.push_back(d.W(Eigen::seqN(j, rows, n), Eigen::all));
        y.push_back(d.tau(Eigen::seqN(j, rows, n)));
      }
    } else {
      W = sample_rows(model, data[e]);
      for (int j = 0; j < n; ++j) y.push_back(data[e].tau.col(j));
    }
    for (int j = 0; j < n; ++j) {
      const std::size_t g = e * static_cast<std::size_t>(n) + static_cast<std::size_t>(j);
      const double sigma = g < fit.group_std_dev.size() ? fit.group_std_dev[g] : 1.0;
      ResidualGroup group;
      group.X = W[static_cast<std::size_t>(j)] / sigma;
      group.r =
          (y[static_cast<std::size_t>(j)] - W[static_cast<std::size_t>(j)] * fit.value) / sigma;
      // The lines of a period only for a whole, undecimated period.
      group.harmonics = e < harmonics.size() && decimation[e] == 1 ? harmonics[e] : -1;
      groups.push_back(std::move(group));
    }
  }
  // The streamed records' scores are summed (a second pass) only if the sandwich is needed.
  const bool streamed_correlated =
      std::any_of(streamed.begin(), streamed.end(),
                  [](const StreamedResiduals& r) { return r.correlation.significant; });
  if (groups.empty() && !streamed_correlated) return;
  std::vector<StreamedMeat> meats;
  for (const StreamedResiduals& r : streamed) {
    meats.push_back(streamed_meat(model, data[r.experiment], r));
  }
  const SandwichCovariance score = score_covariance(groups, meats);
  if (score.description.empty()) return;
  // The weighted normal matrix of every group (eq. 18's information is it over sigma^2).
  const Eigen::MatrixXd AtA = fit.information * (fit.residual_std_dev * fit.residual_std_dev);
  const Eigen::MatrixXd AtA_inverse = AtA.ldlt().solve(Eigen::MatrixXd::Identity(b, b));
  const Eigen::MatrixXd covariance = sandwich(AtA_inverse, score.meat);
  fit.std_dev = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index k = 0; k < b; ++k) {
    fit.rel_std_dev[k] = fit.value[k] != 0.0 ? 100.0 * fit.std_dev[k] / std::abs(fit.value[k])
                                             : std::numeric_limits<double>::infinity();
  }
  // fit.information stays eq. 18's: --physical projects the estimate in the metric of the
  // weighted least-squares cost it moves along (its "cost increase"); the sandwich corrects
  // the uncertainty reported, and from the sandwich's inverse the consistent fit of the real
  // Panda run no longer converged.
  fit.covariance = score.description;
}

}  // namespace modelgen::detail
