// identify()'s standard deviations when its equation errors are correlated (issue 31): periodic
// experiments whose torques were cut at a harmonic, and decimated experiments (filtered,
// often closed-loop records) whose residuals stay correlated from row to row. The weighted
// rows of every joint and experiment are rebuilt (W is not kept by the fit) and the sandwich
// of correlated_covariance.hpp replaces eq. 18.

#include "runtime/src/estimation/identify_covariance.hpp"

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

}  // namespace

void correct_for_correlation(const IdentificationModel& model, const std::vector<Trajectory>& data,
                             const std::vector<int>& decimation,
                             const std::vector<DecimatedExperiment>& decimated,
                             const std::vector<int>& harmonics, LeastSquaresResult& fit) {
  bool needed = false;
  for (std::size_t e = 0; e < data.size(); ++e) {
    needed = needed || decimation[e] > 1 || (e < harmonics.size() && harmonics[e] >= 0);
  }
  if (!needed) return;
  const int n = model.dof();
  const Eigen::Index b = fit.value.size();
  std::vector<ResidualGroup> groups;
  Eigen::MatrixXd AtA = Eigen::MatrixXd::Zero(b, b);
  std::size_t next_decimated = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
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
      AtA += group.X.transpose() * group.X;
      groups.push_back(std::move(group));
    }
  }
  const SandwichCovariance score = score_covariance(groups);
  if (score.description.empty()) return;
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
