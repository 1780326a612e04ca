// identify()'s standard deviations when its equation errors are correlated (issue 31): periodic
// experiments whose torques were cut at a harmonic, and filtered, decimated or closed-loop
// records whose residuals stay correlated from row to row. The weighted rows of every group
// (a joint of an experiment for the IDIM, an experiment's power equations for the PIM) are
// rebuilt (W is not kept by the fit) and the sandwich of correlated_covariance.hpp replaces
// eq. 18. Undecimated records of any length are streamed: their residuals first, and their
// scores only when some group needs the sandwich.

#include "runtime/src/estimation/identify_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "runtime/src/estimation/correlated_covariance.hpp"

namespace modelgen::detail {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The equations of one sample: a row per joint (IDIM, eq. 6), or the power row (PIM, eq. 9-10:
// dq . tau = dq^T W beta).
class SampleEquations {
 public:
  SampleEquations(const IdentificationModel& model, bool power)
      : model_(model),
        power_(power),
        rows_(RowMajor::Zero(power ? 1 : model.dof(), model.num_base_params())),
        y_(rows_.rows()) {}

  [[nodiscard]] int groups() const { return static_cast<int>(rows_.rows()); }

  void evaluate(const Trajectory& x, Eigen::Index s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    if (power_) {
      model_.power_regressor(q.data(), dq.data(), ddq.data(), rows_.data());
      y_[0] = dq.dot(x.tau.row(s).transpose());
    } else {
      model_.regressor(q.data(), dq.data(), ddq.data(), rows_.data());
      y_ = x.tau.row(s).transpose();
    }
  }
  [[nodiscard]] const RowMajor& rows() const { return rows_; }
  [[nodiscard]] const Eigen::VectorXd& y() const { return y_; }

 private:
  const IdentificationModel& model_;
  bool power_;
  RowMajor rows_;
  Eigen::VectorXd y_;
};

// The standard deviation of experiment e's groups' equation errors: their WLS weights.
Eigen::VectorXd group_sigma(const LeastSquaresResult& fit, std::size_t e, int groups) {
  Eigen::VectorXd sigma = Eigen::VectorXd::Ones(groups);
  for (int j = 0; j < groups; ++j) {
    const std::size_t g = e * static_cast<std::size_t>(groups) + static_cast<std::size_t>(j);
    if (g < fit.group_std_dev.size()) sigma[j] = fit.group_std_dev[g];
  }
  return sigma;
}

// Experiment x's weighted rows and residuals, group by group, one row per sample (a period of
// the periodic route).
std::vector<ResidualGroup> sample_groups(SampleEquations& equations, const Trajectory& x,
                                         const Eigen::VectorXd& beta,
                                         const Eigen::VectorXd& sigma) {
  const int k = equations.groups();
  const Eigen::Index m = x.t.size();
  std::vector<ResidualGroup> groups(static_cast<std::size_t>(k));
  for (ResidualGroup& g : groups) {
    g.X.resize(m, beta.size());
    g.r.resize(m);
  }
  for (Eigen::Index s = 0; s < m; ++s) {
    equations.evaluate(x, s);
    for (int j = 0; j < k; ++j) {
      ResidualGroup& g = groups[static_cast<std::size_t>(j)];
      g.X.row(s) = equations.rows().row(j) / sigma[j];
      g.r[s] = (equations.y()[j] - equations.rows().row(j).dot(beta)) / sigma[j];
    }
  }
  return groups;
}

// A decimated experiment's kept rows (identify_equations.hpp), group by group.
std::vector<ResidualGroup> decimated_groups(const DecimatedExperiment& d, bool power, int n,
                                            const Eigen::VectorXd& beta,
                                            const Eigen::VectorXd& sigma) {
  std::vector<ResidualGroup> groups;
  if (power) {
    groups.push_back({d.P / sigma[0], (d.p - d.P * beta) / sigma[0], -1});
    return groups;
  }
  const Eigen::Index rows = d.W.rows() / n;
  for (int j = 0; j < n; ++j) {
    const Eigen::MatrixXd W = d.W(Eigen::seqN(j, rows, n), Eigen::all);
    const Eigen::VectorXd y = d.tau(Eigen::seqN(j, rows, n));
    groups.push_back({W / sigma[j], (y - W * beta) / sigma[j], -1});
  }
  return groups;
}

// An undecimated, non-periodic experiment's weighted residuals and their correlation.
struct StreamedResiduals {
  std::size_t experiment = 0;
  Eigen::VectorXd sigma;
  Eigen::MatrixXd residual;  ///< samples x groups
  Correlation correlation;
};

StreamedResiduals streamed_residuals(SampleEquations& equations, const Trajectory& x, std::size_t e,
                                     const LeastSquaresResult& fit) {
  const int k = equations.groups();
  StreamedResiduals out{e, group_sigma(fit, e, k), Eigen::MatrixXd(x.t.size(), k), {}};
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    equations.evaluate(x, s);
    out.residual.row(s) =
        ((equations.y() - equations.rows() * fit.value).array() / out.sigma.array()).transpose();
  }
  const Eigen::Index m = out.residual.rows();
  const double lag =
      m < 2 ? 0.0
            : (out.residual.topRows(m - 1).array() * out.residual.bottomRows(m - 1).array()).sum();
  out.correlation = residual_correlation(lag, out.residual.squaredNorm(), m * k, k);
  return out;
}

// Its scores x_t r_t summed with its own bandwidth (0 when its residuals are white), by a second
// pass over the equations: the rows are never held.
StreamedMeat streamed_meat(SampleEquations& equations, const Trajectory& x,
                           const StreamedResiduals& r, Eigen::Index b) {
  const int k = equations.groups();
  const Eigen::Index m = r.residual.rows();
  const int L = static_cast<int>(std::min<Eigen::Index>(r.correlation.bandwidth, m - 1));
  std::vector<BartlettScoreSum> sums(static_cast<std::size_t>(k), BartlettScoreSum(b, L));
  for (Eigen::Index s = 0; s < m; ++s) {
    equations.evaluate(x, s);
    for (int j = 0; j < k; ++j) {
      sums[static_cast<std::size_t>(j)].add(equations.rows().row(j).transpose() *
                                            (r.residual(s, j) / r.sigma[j]));
    }
  }
  StreamedMeat out{Eigen::MatrixXd::Zero(b, b), m * k, r.correlation};
  for (const BartlettScoreSum& sum : sums) out.meat += sum.meat();
  return out;
}

}  // namespace

void correct_for_correlation(const IdentificationModel& model, const std::vector<Trajectory>& data,
                             const std::vector<int>& decimation,
                             const std::vector<DecimatedExperiment>& decimated,
                             const std::vector<int>& harmonics, bool power,
                             LeastSquaresResult& fit) {
  const int n = model.dof();
  const Eigen::Index b = fit.value.size();
  SampleEquations equations(model, power);
  std::vector<ResidualGroup> groups;
  std::vector<StreamedResiduals> streamed;
  std::size_t next_decimated = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Eigen::VectorXd sigma = group_sigma(fit, e, equations.groups());
    // The power of noise cut at harmonic H is not on the harmonics 0..H: dq spreads it.
    const int H = !power && e < harmonics.size() && decimation[e] == 1 ? harmonics[e] : -1;
    std::vector<ResidualGroup> more;
    if (decimation[e] > 1) {
      more = decimated_groups(decimated[next_decimated++], power, n, fit.value, sigma);
    } else if (H >= 0) {
      more = sample_groups(equations, data[e], fit.value, sigma);
      for (ResidualGroup& g : more) g.harmonics = H;
    } else {
      streamed.push_back(streamed_residuals(equations, data[e], e, fit));
    }
    for (ResidualGroup& g : more) groups.push_back(std::move(g));
  }
  // The streamed records' scores are summed (a second pass) only if the sandwich may be needed.
  const bool streamed_correlated =
      std::any_of(streamed.begin(), streamed.end(),
                  [](const StreamedResiduals& r) { return r.correlation.significant; });
  if (groups.empty() && !streamed_correlated) return;
  std::vector<StreamedMeat> meats;
  for (const StreamedResiduals& r : streamed) {
    meats.push_back(streamed_meat(equations, data[r.experiment], r, b));
  }
  const SandwichCovariance score = score_covariance(groups, meats);
  if (score.description.empty()) return;
  // The weighted normal matrix of every group: eq. 18's information is it over sigma^2.
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
