// The one interface identification works through: a robot's base-parameter regressor, power
// regressor and regrouping, from generated code compiled in (GeneratedModel) or from the
// numeric reference built from any description at run time (ReferenceModel). Both give the
// same numbers; tests/model/identification_model_test.cpp checks it.
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "modelgen/model/drive_chain.hpp"
#include "modelgen/model/generated_format.hpp"

namespace modelgen {

class IdentificationModel {
 public:
  virtual ~IdentificationModel() = default;

  virtual std::string name() const = 0;
  /// SHA-256 of the description the model was made from (hex), for estimates to name the
  /// model they belong to; empty when unknown.
  virtual std::string description_sha256() const = 0;
  virtual int dof() const = 0;
  virtual const std::vector<std::string>& standard_param_names() const = 0;
  virtual const std::vector<std::string>& base_param_names() const = 0;
  int num_base_params() const { return static_cast<int>(base_param_names().size()); }
  int num_standard_params() const { return static_cast<int>(standard_param_names().size()); }

  /// Base regressor: q, dq, ddq have dof() entries; W receives dof() x num_base_params()
  /// values, row-major, with tau = W beta (Gautier & Briot eq. 4-6).
  virtual void regressor(const double* q, const double* dq, const double* ddq, double* W) const = 0;
  /// Power regressor: dh receives num_base_params() values with dq . tau = dh beta (eq. 9-10).
  virtual void power_regressor(const double* q, const double* dq, const double* ddq,
                               double* dh) const = 0;
  /// Joint torques from base parameters: tau receives dof() values.
  virtual void inverse_dynamics(const double* q, const double* dq, const double* ddq,
                                const double* beta, double* tau) const = 0;
  /// Joint-space inertia matrix from base parameters: M receives dof() x dof() values,
  /// row-major, drive inertias on its diagonal. This default builds it column by column from
  /// inverse_dynamics at zero velocity (M e_k = tau(q, 0, e_k) - tau(q, 0, 0): gravity and the
  /// torque offsets cancel, Coulomb friction is 0 at rest); generated models override it.
  virtual void mass_matrix(const double* q, const double* beta, double* M) const;
  /// What forward dynamics needs at one state: mass_matrix into M and inverse_dynamics at
  /// zero acceleration into h (dof() values). This default calls the two; generated models
  /// call their mass_matrix_and_bias (or share the joints' sines and cosines between the two).
  virtual void mass_matrix_and_bias(const double* q, const double* dq, const double* beta,
                                    double* M, double* h) const;
  /// d tau / d x at one state x = [q, dq, ddq], for errors in variables (Bona & Curatella
  /// eq. 15-16): J receives dof() x 3 dof() values, row-major, J[i * 3 dof() + k] = d tau_i / d x_k.
  /// It is linear in beta, like tau. This default takes central differences of
  /// inverse_dynamics, step h_k = 6e-6 max(1, |x_k|) (about the cube root of the machine
  /// epsilon, balancing the h^2 truncation against the eps |tau| / h round-off): errors of order
  /// 1e-10 of the Jacobian's scale expected in the q and dq columns, round-off only in the ddq
  /// columns (tau is linear in ddq); tests/model/state_jacobian_interface_test.cpp bounds it by
  /// 1e-7 of the largest entry on four shipped robots. Coulomb friction jumps at dq = 0: a dq column whose stencil
  /// crosses a zero velocity is wrong there. Generated models override it with their generated
  /// inverse_dynamics_state_jacobian (exact, same friction convention) when they have one.
  virtual void inverse_dynamics_state_jacobian(const double* q, const double* dq,
                                               const double* ddq, const double* beta,
                                               double* J) const;
  /// Whether inverse_dynamics_state_jacobian is generated (exact) rather than this interface's
  /// differences. A caller that needs it for several beta at one state can then pick the
  /// cheaper route: the excitation design takes differences of one regressor instead when it
  /// is not (the reference's inverse dynamics builds the whole regressor each call).
  virtual bool exact_state_jacobian() const { return false; }
  /// The regrouping relations: beta (num_base_params()) from standard parameters
  /// (num_standard_params()).
  virtual void base_from_standard(const double* p_standard, double* beta) const = 0;
  /// The description's drive chain, for motor-side data and current measurements.
  virtual const DriveChain& drive_chain() const = 0;
};

/// The numeric reference as an identification model: any description, slower than generated
/// code (one Newton-Euler pass per standard parameter for the regressor).
class ReferenceModel final : public IdentificationModel {
 public:
  /// Validates `tree` and derives its base parameters; throws std::invalid_argument for a
  /// malformed tree.
  /// `drive` defaults to the identity drive chain.
  ReferenceModel(std::string name, RigidBodyTree tree, std::string description_sha256 = "",
                 std::optional<DriveChain> drive = std::nullopt);

  std::string name() const override { return name_; }
  std::string description_sha256() const override { return sha256_; }
  int dof() const override { return dynamics_.dof(); }
  const std::vector<std::string>& standard_param_names() const override { return standard_; }
  const std::vector<std::string>& base_param_names() const override { return base_names_; }
  void regressor(const double* q, const double* dq, const double* ddq, double* W) const override;
  void power_regressor(const double* q, const double* dq, const double* ddq,
                       double* dh) const override;
  void inverse_dynamics(const double* q, const double* dq, const double* ddq, const double* beta,
                        double* tau) const override;
  void base_from_standard(const double* p_standard, double* beta) const override;
  const DriveChain& drive_chain() const override { return drive_; }

  const BaseParameterSet& base() const { return base_; }

 private:
  std::string name_;
  std::string sha256_;
  DriveChain drive_;
  ReferenceDynamics dynamics_;
  BaseParameterSet base_;
  std::vector<std::string> standard_, base_names_;
};

/// A generated model compiled in: GeneratedModel<modelgen::tx40::Model>. Generated functions
/// leave the entries that are zero for every input unwritten (their callers zero the arrays
/// once); this adapter keeps the interface's contract (every entry written) by zeroing each
/// output first, one memset of the array per call. A loop that wants to avoid it calls the
/// generated function directly on an array it zeroed once.
template <class Generated>
class GeneratedModel final : public IdentificationModel {
  static_assert(Generated::kFormatVersion == kGeneratedFormatVersion,
                "this generated model was made by a modelgen whose generated format differs "
                "from this runtime's: regenerate it with the modelgen of this runtime");

 public:
  GeneratedModel()
      : standard_(Generated::standard_param_names(),
                  Generated::standard_param_names() + Generated::kStandardParams),
        base_(Generated::base_param_names(),
              Generated::base_param_names() + Generated::kBaseParams) {
    constexpr int n = Generated::kDof;
    drive_.motor_from_joint = Eigen::Map<const Eigen::Matrix<double, n, n, Eigen::RowMajor>>(
        Generated::motor_from_joint());
    drive_.torque_constant = Eigen::Map<const Eigen::VectorXd>(Generated::torque_constant(), n);
    drive_.joint_offset = Eigen::Map<const Eigen::VectorXd>(Generated::joint_offset(), n);
  }

  std::string name() const override { return Generated::name(); }
  std::string description_sha256() const override { return Generated::input_sha256(); }
  int dof() const override { return Generated::kDof; }
  const std::vector<std::string>& standard_param_names() const override { return standard_; }
  const std::vector<std::string>& base_param_names() const override { return base_; }
  void regressor(const double* q, const double* dq, const double* ddq, double* W) const override {
    std::fill_n(W, Generated::kDof * Generated::kBaseParams, 0.0);
    Generated::idim_regressor(q, dq, ddq, W);
  }
  void power_regressor(const double* q, const double* dq, const double* ddq,
                       double* dh) const override {
    std::fill_n(dh, Generated::kBaseParams, 0.0);
    Generated::power_regressor(q, dq, ddq, dh);
  }
  void inverse_dynamics(const double* q, const double* dq, const double* ddq, const double* beta,
                        double* tau) const override {
    Generated::inverse_dynamics(q, dq, ddq, beta, tau);
  }
  void mass_matrix(const double* q, const double* beta, double* M) const override {
    std::fill_n(M, Generated::kDof * Generated::kDof, 0.0);
    Generated::mass_matrix(q, beta, M);
  }
  void mass_matrix_and_bias(const double* q, const double* dq, const double* beta, double* M,
                            double* h) const override {
    if constexpr (requires { Generated::mass_matrix_and_bias(q, dq, beta, M, h); }) {
      // One generated pass; models generated before it have the two functions below.
      std::fill_n(M, Generated::kDof * Generated::kDof, 0.0);
      std::fill_n(h, Generated::kDof, 0.0);
      Generated::mass_matrix_and_bias(q, dq, beta, M, h);
    } else if constexpr (requires { Generated::mass_matrix_sincos(q, q, q, beta, M); }) {
      double sin_q[Generated::kDof], cos_q[Generated::kDof], zero[Generated::kDof] = {};
      Generated::joint_sincos(q, sin_q, cos_q);
      std::fill_n(M, Generated::kDof * Generated::kDof, 0.0);
      Generated::mass_matrix_sincos(q, sin_q, cos_q, beta, M);
      Generated::inverse_dynamics_sincos(q, sin_q, cos_q, dq, zero, beta, h);
    } else {
      IdentificationModel::mass_matrix_and_bias(q, dq, beta, M, h);
    }
  }
  void inverse_dynamics_state_jacobian(const double* q, const double* dq, const double* ddq,
                                       const double* beta, double* J) const override {
    if constexpr (requires { Generated::inverse_dynamics_state_jacobian(q, dq, ddq, beta, J); }) {
      std::fill_n(J, 3 * Generated::kDof * Generated::kDof, 0.0);
      Generated::inverse_dynamics_state_jacobian(q, dq, ddq, beta, J);
    } else {
      IdentificationModel::inverse_dynamics_state_jacobian(q, dq, ddq, beta, J);
    }
  }
  bool exact_state_jacobian() const override {
    return requires(const double* x, double* J) {
      Generated::inverse_dynamics_state_jacobian(x, x, x, x, J);
    };
  }
  void base_from_standard(const double* p_standard, double* beta) const override {
    Generated::base_from_standard(p_standard, beta);
  }
  const DriveChain& drive_chain() const override { return drive_; }

 private:
  std::vector<std::string> standard_, base_;
  DriveChain drive_;
};

}  // namespace modelgen
