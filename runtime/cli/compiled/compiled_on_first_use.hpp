// A description's model that is compiled when it is first evaluated, not when it is loaded: a
// command refuses its bad options, limits and data first (in milliseconds), and only work that
// evaluates the model pays for a first-use compilation. Names and sizes come from the numeric
// reference, which also serves every evaluation when the compiled model cannot be had.
#pragma once

#include <memory>
#include <mutex>
#include <optional>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/model_library.hpp"
#include "runtime/cli/compiled/model_cache.hpp"

namespace modelgen::internal {

class CompiledOnFirstUse final : public IdentificationModel {
 public:
  /// `reference` is the description's numeric reference; `path` and `options` how modelid read
  /// the description (model_cache.hpp).
  CompiledOnFirstUse(std::unique_ptr<IdentificationModel> reference, std::filesystem::path path,
                     LoadOptions options);

  /// The compiled model's library, compiling it now if that has not been tried yet; null when
  /// it cannot be had (evaluations then use the reference).
  const ModelLibrary* library() const;

  std::string name() const override { return reference_->name(); }
  std::string description_sha256() const override { return reference_->description_sha256(); }
  int dof() const override { return reference_->dof(); }
  const std::vector<std::string>& standard_param_names() const override {
    return reference_->standard_param_names();
  }
  const std::vector<std::string>& base_param_names() const override {
    return reference_->base_param_names();
  }
  const DriveChain& drive_chain() const override { return reference_->drive_chain(); }

  void regressor(const double* q, const double* dq, const double* ddq, double* W) const override {
    active().regressor(q, dq, ddq, W);
  }
  void power_regressor(const double* q, const double* dq, const double* ddq,
                       double* dh) const override {
    active().power_regressor(q, dq, ddq, dh);
  }
  void inverse_dynamics(const double* q, const double* dq, const double* ddq, const double* beta,
                        double* tau) const override {
    active().inverse_dynamics(q, dq, ddq, beta, tau);
  }
  void mass_matrix(const double* q, const double* beta, double* M) const override {
    active().mass_matrix(q, beta, M);
  }
  void mass_matrix_and_bias(const double* q, const double* dq, const double* beta, double* M,
                            double* h) const override {
    active().mass_matrix_and_bias(q, dq, beta, M, h);
  }
  void inverse_dynamics_state_jacobian(const double* q, const double* dq, const double* ddq,
                                       const double* beta, double* J) const override {
    active().inverse_dynamics_state_jacobian(q, dq, ddq, beta, J);
  }
  bool exact_state_jacobian() const override { return active().exact_state_jacobian(); }
  void base_from_standard(const double* p_standard, double* beta) const override {
    active().base_from_standard(p_standard, beta);
  }

 private:
  const IdentificationModel& active() const;

  std::unique_ptr<IdentificationModel> reference_;
  std::filesystem::path path_;
  LoadOptions options_;
  mutable std::once_flag tried_;
  mutable std::optional<ModelLibrary> library_;
  mutable std::unique_ptr<IdentificationModel> compiled_;
};

}  // namespace modelgen::internal
