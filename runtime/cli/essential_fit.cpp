// The observation equations of IDIM and PIM rebuilt from the model's regressors (Gautier &
// Briot eq. 4-10, 20) for the essential parameter search.

#include "runtime/cli/essential_fit.hpp"

#include <string>

namespace modelgen::internal {

Observations observation_equations(const IdentificationModel& model,
                                   const std::vector<Trajectory>& data, Method method) {
  const int n = model.dof(), nb = model.num_base_params();
  Eigen::Index samples = 0;
  for (const Trajectory& x : data) {
    const Eigen::Index m = x.t.size();
    for (const Eigen::MatrixXd* a : {&x.q, &x.dq, &x.ddq, &x.tau}) {
      if (a->rows() != m || a->cols() != n) {
        throw EstimationError(x.source + ": q, dq, ddq and tau need " + std::to_string(m) +
                              " rows (one per time) and " + std::to_string(n) + " columns");
      }
    }
    samples += m;
  }
  const bool power = method == Method::kPimWls;
  Observations out;
  out.W.resize(power ? samples : samples * n, nb);
  out.y.resize(out.W.rows());
  if (method != Method::kOls) out.group.resize(out.W.rows());
  std::vector<double> Ws(static_cast<std::size_t>(n) * nb);
  Eigen::Index s_all = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Trajectory& x = data[e];
    const int experiment = static_cast<int>(e);
    for (Eigen::Index s = 0; s < x.t.size(); ++s, ++s_all) {
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      model.regressor(q.data(), dq.data(), ddq.data(), Ws.data());
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
          W_sample(Ws.data(), n, nb);
      if (power) {
        // Eq. 9: the power dq . tau = dq^T W beta, one equation per sample.
        out.W.row(s_all) = dq.transpose() * W_sample;
        out.y[s_all] = dq.dot(x.tau.row(s));
        out.group[s_all] = experiment;
        continue;
      }
      out.W.middleRows(s_all * n, n) = W_sample;
      out.y.segment(s_all * n, n) = x.tau.row(s).transpose();
      // Eq. 20: one weight per joint and experiment.
      if (!out.group.empty()) {
        for (int i = 0; i < n; ++i) out.group[s_all * n + i] = experiment * n + i;
      }
    }
  }
  return out;
}

EssentialParameters essential_fit(const IdentificationModel& model,
                                  const std::vector<Trajectory>& data, Method method,
                                  double r_sigma) {
  const Observations equations = observation_equations(model, data, method);
  return essential_parameters(equations.W, equations.y, equations.group, model.base_param_names(),
                              r_sigma);
}

}  // namespace modelgen::internal
