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
  double whiten = 0;     ///< AR(1) prewhitening coefficient, 0: none
  Correlation whitened;  ///< of the prewhitened residuals
};

// Sum over rows and columns of x_t y_(t - lag).
double lagged_products(const Eigen::MatrixXd& x, Eigen::Index lag) {
  const Eigen::Index m = x.rows();
  if (m <= lag) return 0;
  return (x.bottomRows(m - lag).array() * x.topRows(m - lag).array()).sum();
}

// A correlated residual is prewhitened before its scores are summed (Andrews & Monahan 1992):
// the Bartlett sum then needs a short bandwidth, whose window in frequency is wide, so the few
// lines where the fit took the noise out of the residual (its slow columns) weigh little; with
// the long bandwidth of the raw residual (180 rows at rho 0.95) the window held few lines and
// the fit had emptied many of them: the PIM's sd were 0.74 of their spread, IDIM's 0.84 (now
// 1.11 and 1.00, covariance_monte_carlo_test).
void prewhiten(StreamedResiduals& r, Eigen::Index rows, Eigen::Index groups) {
  if (!r.correlation.significant || !(r.correlation.rho > 0)) return;
  const Eigen::MatrixXd& e = r.residual;
  const Eigen::Index m = e.rows(), K = prewhitening_lag(r.correlation.rho, m);
  if (m < K + 3) return;
  // Autocovariances as means over the products each lag has.
  const auto g = [&](Eigen::Index lag) {
    return lagged_products(e, lag) / static_cast<double>(m - lag);
  };
  r.whiten = prewhitening_coefficient(g(0), g(1), g(K), g(K + 1));
  if (r.whiten == 0) return;
  const Eigen::MatrixXd w = e.bottomRows(m - 1) - r.whiten * e.topRows(m - 1);
  r.whitened = residual_correlation(lagged_products(w, 1), w.squaredNorm(), rows, groups);
}

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
  prewhiten(out, m * k, k);
  return out;
}

// Its scores x_t r_t summed with its own bandwidth (0 when its residuals are white), by a second
// pass over the equations: the rows are never held. Prewhitened: the scores
// g_t - c g_(t-1) summed, and recoloured by 1 / (1 - c)^2 (their sum over the record is
// (1 - c) times g's, up to the ends).
StreamedMeat streamed_meat(SampleEquations& equations, const Trajectory& x,
                           const StreamedResiduals& r, Eigen::Index b) {
  const int k = equations.groups();
  const Eigen::Index m = r.residual.rows();
  const Correlation& c = r.whiten != 0 ? r.whitened : r.correlation;
  const int L = static_cast<int>(std::min<Eigen::Index>(c.bandwidth, m - 2));
  std::vector<BartlettScoreSum> sums(static_cast<std::size_t>(k), BartlettScoreSum(b, L));
  Eigen::MatrixXd previous = Eigen::MatrixXd::Zero(b, k);
  Eigen::VectorXd score(b);
  for (Eigen::Index s = 0; s < m; ++s) {
    equations.evaluate(x, s);
    for (int j = 0; j < k; ++j) {
      score = equations.rows().row(j).transpose() * (r.residual(s, j) / r.sigma[j]);
      if (r.whiten == 0) {
        sums[static_cast<std::size_t>(j)].add(score);
        continue;
      }
      if (s > 0) sums[static_cast<std::size_t>(j)].add(score - r.whiten * previous.col(j));
      previous.col(j) = score;
    }
  }
  StreamedMeat out{Eigen::MatrixXd::Zero(b, b), m * k, r.correlation, r.whiten, r.whitened};
  for (const BartlettScoreSum& sum : sums) out.meat += sum.meat();
  if (r.whiten != 0) {
    // m - 1 prewhitened rows stand for the m of the record.
    out.meat *=
        static_cast<double>(m) / static_cast<double>(m - 1) / ((1 - r.whiten) * (1 - r.whiten));
  }
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
