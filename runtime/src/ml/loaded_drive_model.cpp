// GeneratedDriveModel's adapter with the loaded table's sizes and function pointers.

#include "modelgen/ml/loaded_drive_model.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace modelgen {

namespace {

class LoadedDriveModel final : public DriveModel {
 public:
  explicit LoadedDriveModel(ModelLibrary library)
      : library_(std::move(library)),
        t_(library_.table()),
        names_(t_.drive_param_names, t_.drive_param_names + t_.drive_params) {}

  int dof() const override { return t_.dof; }
  const std::vector<std::string>& param_names() const override { return names_; }
  void set_samples(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                   const Eigen::MatrixXd& ddq) override {
    const Eigen::Index n = q.rows();
    const int dof = t_.dof;
    if (q.cols() != dof || dq.cols() != dof || ddq.cols() != dof || dq.rows() != n ||
        ddq.rows() != n) {
      throw std::invalid_argument("drive model: q, dq, ddq must be samples x " +
                                  std::to_string(dof) + " matrices of equal size");
    }
    // Zero-filled before drive_regressor writes each sample: the entries it leaves unwritten
    // (always zero) stay zero.
    Y_.assign(static_cast<std::size_t>(n * t_.drive_regressor_entries), 0.0);
    std::vector<double> x(3 * static_cast<std::size_t>(dof));  // one sample's q, dq, ddq
    for (Eigen::Index s = 0; s < n; ++s) {
      for (int j = 0; j < dof; ++j) {
        x[j] = q(s, j);
        x[dof + j] = dq(s, j);
        x[2 * dof + j] = ddq(s, j);
      }
      t_.drive_regressor(x.data(), x.data() + dof, x.data() + 2 * dof, regressor(s));
    }
    samples_ = n;
  }
  Eigen::Index num_samples() const override { return samples_; }
  void torque(Eigen::Index s, const double* theta, double* tau_M) const override {
    t_.drive_torque_given_regressor(regressor(s), theta, tau_M);
  }
  void torque_jacobian(Eigen::Index s, const double* theta, double* tau_M,
                       double* J) const override {
    t_.drive_torque_jacobian_given_regressor(regressor(s), theta, tau_M, J);
  }

 private:
  double* regressor(Eigen::Index s) {
    return &Y_[static_cast<std::size_t>(s * t_.drive_regressor_entries)];
  }
  const double* regressor(Eigen::Index s) const {
    return &Y_[static_cast<std::size_t>(s * t_.drive_regressor_entries)];
  }

  ModelLibrary library_;  // keeps the code below t_'s pointers loaded
  const modelgen_loadable_table& t_;
  std::vector<std::string> names_;
  Eigen::Index samples_ = 0;
  std::vector<double> Y_;  // per sample: the packed Y, drive_regressor_entries values
};

}  // namespace

std::unique_ptr<DriveModel> make_drive_model(const ModelLibrary& library) {
  return std::make_unique<LoadedDriveModel>(library);
}

}  // namespace modelgen
