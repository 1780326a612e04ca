// The identification model on a loaded library's table: GeneratedModel's adapter (the
// compiled-in one, identification_model.hpp) with the sizes read at run time and the functions
// called through the table's pointers, keeping its contract (every output entry written).

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "modelgen/model/model_library.hpp"

namespace modelgen {

namespace {

class LoadedModel final : public IdentificationModel {
 public:
  explicit LoadedModel(ModelLibrary library)
      : library_(std::move(library)),
        t_(library_.table()),
        standard_(t_.standard_param_names, t_.standard_param_names + t_.standard_params),
        base_(t_.base_param_names, t_.base_param_names + t_.base_params) {
    const int n = t_.dof;
    drive_.motor_from_joint =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            t_.motor_from_joint, n, n);
    drive_.torque_constant = Eigen::Map<const Eigen::VectorXd>(t_.torque_constant, n);
    drive_.joint_offset = Eigen::Map<const Eigen::VectorXd>(t_.joint_offset, n);
  }

  std::string name() const override { return t_.name; }
  std::string description_sha256() const override { return t_.input_sha256; }
  int dof() const override { return t_.dof; }
  const std::vector<std::string>& standard_param_names() const override { return standard_; }
  const std::vector<std::string>& base_param_names() const override { return base_; }
  void regressor(const double* q, const double* dq, const double* ddq, double* W) const override {
    std::fill_n(W, t_.dof * t_.base_params, 0.0);
    t_.idim_regressor(q, dq, ddq, W);
  }
  void power_regressor(const double* q, const double* dq, const double* ddq,
                       double* dh) const override {
    std::fill_n(dh, t_.base_params, 0.0);
    t_.power_regressor(q, dq, ddq, dh);
  }
  void inverse_dynamics(const double* q, const double* dq, const double* ddq, const double* beta,
                        double* tau) const override {
    t_.inverse_dynamics(q, dq, ddq, beta, tau);
  }
  void mass_matrix(const double* q, const double* beta, double* M) const override {
    std::fill_n(M, t_.dof * t_.dof, 0.0);
    t_.mass_matrix(q, beta, M);
  }
  void mass_matrix_and_bias(const double* q, const double* dq, const double* beta, double* M,
                            double* h) const override {
    std::fill_n(M, t_.dof * t_.dof, 0.0);
    std::fill_n(h, t_.dof, 0.0);
    t_.mass_matrix_and_bias(q, dq, beta, M, h);
  }
  void inverse_dynamics_state_jacobian(const double* q, const double* dq, const double* ddq,
                                       const double* beta, double* J) const override {
    std::fill_n(J, 3 * t_.dof * t_.dof, 0.0);
    t_.inverse_dynamics_state_jacobian(q, dq, ddq, beta, J);
  }
  bool exact_state_jacobian() const override { return true; }
  void base_from_standard(const double* p_standard, double* beta) const override {
    t_.base_from_standard(p_standard, beta);
  }
  const DriveChain& drive_chain() const override { return drive_; }

 private:
  ModelLibrary library_;  // keeps the code below t_'s pointers loaded
  const modelgen_loadable_table& t_;
  std::vector<std::string> standard_, base_;
  DriveChain drive_;
};

}  // namespace

std::unique_ptr<IdentificationModel> ModelLibrary::identification_model() const {
  return std::make_unique<LoadedModel>(*this);
}

}  // namespace modelgen
