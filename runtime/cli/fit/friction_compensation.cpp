// The friction torque of a first IDIM-WLS, for the projection method (Bona & Curatella 3.4).

#include "runtime/cli/fit/friction_compensation.hpp"

#include <string>
#include <vector>

#include "modelgen/estimation/identify.hpp"

namespace modelgen::internal {

bool is_friction_parameter(const std::string& name) {
  return name.size() > 2 && name[0] == 'F' && (name[1] == 'v' || name[1] == 'c');
}

std::vector<Eigen::MatrixXd> friction_torques(const IdentificationModel& model,
                                              const std::vector<ProjectionRecord>& records,
                                              const std::vector<double>& min_speed) {
  std::vector<Trajectory> prepared;
  IdentifyOptions options;
  options.min_speed = min_speed;
  for (const ProjectionRecord& r : records) {
    prepared.push_back(r.prepared);
    options.decimation.push_back(r.decimation);
  }
  const Identification first = identify(model, prepared, Method::kWls, options);
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(first.fit.value.size());
  for (Eigen::Index k = 0; k < beta.size(); ++k) {
    if (is_friction_parameter(first.names[k])) beta[k] = first.fit.value[k];
  }
  const int n = model.dof();
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> W(n, beta.size());
  std::vector<Eigen::MatrixXd> out;
  for (const ProjectionRecord& r : records) {
    const Trajectory& x = r.prepared;
    Eigen::MatrixXd tau(x.t.size(), n);
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      const Eigen::VectorXd q = x.q.row(s).transpose(), dq = x.dq.row(s).transpose(),
                            ddq = x.ddq.row(s).transpose();
      model.regressor(q.data(), dq.data(), ddq.data(), W.data());
      tau.row(s) = (W * beta).transpose();
    }
    out.push_back(std::move(tau));
  }
  return out;
}

}  // namespace modelgen::internal
