// Building the observation matrix from the model's regressors, sample by sample, and the
// torque errors of the estimate. Memory: W is (equations x base parameters), nothing larger.

#include "modelgen/identify.hpp"

#include <cmath>

namespace modelgen {

Method parse_method(const std::string& text) {
  if (text == "ols") return Method::kOls;
  if (text == "wls") return Method::kWls;
  if (text == "pim-wls") return Method::kPimWls;
  throw EstimationError("unknown method '" + text + "': expected ols, wls or pim-wls");
}

Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& data,
                        Method method) {
  const int n = model.dof(), nb = model.num_base_params();
  Eigen::Index samples = 0;
  for (const Trajectory& x : data) {
    if (x.q.cols() != n) {
      throw EstimationError(x.source + ": " + std::to_string(x.q.cols()) + " joints, the model has " +
                            std::to_string(n));
    }
    const Eigen::Index m = x.t.size();
    for (const Eigen::MatrixXd* a : {&x.q, &x.dq, &x.ddq, &x.tau}) {
      if (a->rows() != m || a->cols() != n) {
        throw EstimationError(x.source + ": q, dq, ddq and tau need " + std::to_string(m) +
                              " rows (one per time) and " + std::to_string(n) + " columns");
      }
    }
    samples += x.t.size();
  }
  const bool power = method == Method::kPimWls;
  const Eigen::Index rows = power ? samples : samples * n;
  Eigen::MatrixXd W_torque(samples * n, nb);  // the IDIM; also for the PIM's torque errors
  Eigen::MatrixXd W_power(power ? samples : 0, nb);
  Eigen::VectorXd y_power(power ? samples : 0), tau_all(samples * n);
  std::vector<int> group(rows);
  std::vector<double> Ws(static_cast<std::size_t>(n) * nb);
  Eigen::Index s_all = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Trajectory& x = data[e];
    for (Eigen::Index s = 0; s < x.t.size(); ++s, ++s_all) {
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      model.regressor(q.data(), dq.data(), ddq.data(), Ws.data());
      for (int i = 0; i < n; ++i) {
        for (int b = 0; b < nb; ++b) W_torque(s_all * n + i, b) = Ws[i * nb + b];
        tau_all[s_all * n + i] = x.tau(s, i);
      }
      if (power) {
        // Eq. 9: P = dq . tau = dq^T W beta.
        W_power.row(s_all) = dq.transpose() * W_torque.middleRows(s_all * n, n);
        y_power[s_all] = dq.dot(x.tau.row(s));
        group[s_all] = static_cast<int>(e);
      } else {
        for (int i = 0; i < n; ++i) group[s_all * n + i] = static_cast<int>(e) * n + i;
      }
    }
  }
  Identification out;
  out.names = model.base_param_names();
  if (power) {
    out.fit = fit_wls(W_power, y_power, group, out.names);
  } else if (method == Method::kOls) {
    out.fit = fit_ols(W_torque, tau_all, out.names);
  } else {
    out.fit = fit_wls(W_torque, tau_all, group, out.names);
  }
  out.samples = samples;
  const Eigen::VectorXd residual = tau_all - W_torque * out.fit.value;
  out.torque_rel_error_norm = residual.norm() / std::max(tau_all.norm(), 1e-300);
  out.rms_error = Eigen::VectorXd::Zero(n);
  out.rms_torque = Eigen::VectorXd::Zero(n);
  for (Eigen::Index r = 0; r < residual.size(); ++r) {
    out.rms_error[r % n] += residual[r] * residual[r];
    out.rms_torque[r % n] += tau_all[r] * tau_all[r];
  }
  out.rms_error = (out.rms_error / static_cast<double>(samples)).cwiseSqrt();
  out.rms_torque = (out.rms_torque / static_cast<double>(samples)).cwiseSqrt();
  return out;
}

}  // namespace modelgen
