// Swevers et al. 2002, eq. 18: the experiments stacked and checked, the unknowns resolved by
// name, the fitted axes found, and the samples cut into cost blocks (block_cost.hpp).

#include "modelgen/ml/problem.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "runtime/src/ml/block_cost.hpp"
#include "runtime/src/ml/problem_impl.hpp"

namespace modelgen {
namespace {

[[noreturn]] void fail(const std::string& message) { throw EstimationError(message); }

// One finite value per ml_param_names() entry.
void check_values(const std::vector<std::string>& names, const Eigen::VectorXd& values) {
  if (values.size() != static_cast<Eigen::Index>(names.size())) {
    fail("maximum likelihood: " + std::to_string(values.size()) + " parameter values given, " +
         std::to_string(names.size()) + " expected (ml_param_names order)");
  }
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) {
      fail("maximum likelihood: parameter '" + names[k] + "' has the value '" +
           std::to_string(values[k]) + "'; values must be finite");
    }
  }
}

// The indices of the unknowns, each a parameter of the model and named once.
std::vector<int> resolve_unknowns(const std::vector<std::string>& names,
                                  const std::map<std::string, int>& index,
                                  const std::vector<std::string>& unknown_names) {
  if (unknown_names.empty()) fail("maximum likelihood: no unknown parameter given");
  std::vector<int> unknown;
  for (const std::string& name : unknown_names) {
    const auto found = index.find(name);
    if (found == index.end()) {
      std::string valid;
      for (const std::string& v : names) valid += (valid.empty() ? "" : " ") + v;
      fail("maximum likelihood: unknown parameter '" + name +
           "' is not a parameter of the model; "
           "valid names: " +
           valid);
    }
    if (std::find(unknown.begin(), unknown.end(), found->second) != unknown.end()) {
      fail("maximum likelihood: parameter '" + name + "' is listed twice as unknown");
    }
    unknown.push_back(found->second);
  }
  return unknown;
}

// The drive-parameter indices of the payload link's XXj .. Mj.
std::vector<int> payload_parameters(const std::map<std::string, int>& index, int payload_link,
                                    int P) {
  std::vector<int> payload;
  for (const char* stem : {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"}) {
    const std::string name = stem + std::to_string(payload_link);
    const auto found = index.find(name);
    if (found == index.end() || found->second >= P) {
      fail("maximum likelihood: payload link " + std::to_string(payload_link) +
           " has no parameter '" + name + "' in the drive model");
    }
    payload.push_back(found->second);
  }
  return payload;
}

// The experiments' samples, stacked; every value finite.
struct StackedSamples {
  Eigen::MatrixXd q, dq, ddq, measured, sigma;
};

StackedSamples stack_experiments(const std::vector<MlExperiment>& data, int n) {
  Eigen::Index total = 0;
  for (const MlExperiment& x : data) {
    const Eigen::Index s = x.q.rows();
    if (s == 0 || x.q.cols() != n || x.dq.rows() != s || x.dq.cols() != n || x.ddq.rows() != s ||
        x.ddq.cols() != n || x.tau_M.rows() != s || x.tau_M.cols() != n || x.sigma.size() != n) {
      fail(x.source + ": error: q, dq, ddq and tau_M must be samples x " + std::to_string(n) +
           " (at least one sample) and sigma have " + std::to_string(n) + " entries");
    }
    total += s;
  }
  if (total == 0) fail("maximum likelihood: no data");
  StackedSamples out;
  out.q.resize(total, n);
  out.dq.resize(total, n);
  out.ddq.resize(total, n);
  out.measured.resize(total, n);
  out.sigma.resize(total, n);
  Eigen::Index at = 0;
  for (const MlExperiment& x : data) {
    const Eigen::Index s = x.q.rows();
    const Eigen::MatrixXd* parts[4] = {&x.q, &x.dq, &x.ddq, &x.tau_M};
    const char* stems[4] = {"q", "dq", "ddq", "tau_M"};
    for (int m = 0; m < 4; ++m) {
      for (Eigen::Index r = 0; r < s; ++r) {
        for (int j = 0; j < n; ++j) {
          if (!std::isfinite((*parts[m])(r, j))) {
            fail(x.source + ": sample " + std::to_string(r) + " (column " + stems[m] +
                 std::to_string(j + 1) + "): error: value is NaN or infinite");
          }
        }
      }
    }
    out.q.middleRows(at, s) = x.q;
    out.dq.middleRows(at, s) = x.dq;
    out.ddq.middleRows(at, s) = x.ddq;
    out.measured.middleRows(at, s) = x.tau_M;
    out.sigma.middleRows(at, s) = x.sigma.transpose().replicate(s, 1);
    at += s;
  }
  return out;
}

// A motor moves exactly when d tau_M,i / d Rv_i = dq_M,i (eq. 5) is not zero somewhere;
// motor i's Rv is the i-th parameter named Rv<j>. The model's samples must be set.
std::vector<int> moving_axes(const DriveModel& model, const std::vector<std::string>& names, int P,
                             const Eigen::VectorXd& theta, Eigen::Index total) {
  const int n = model.dof();
  std::vector<int> rv;
  for (int k = 0; k < P; ++k) {
    const std::string& name = names[k];
    if (name.size() > 2 && name.compare(0, 2, "Rv") == 0 &&
        std::all_of(name.begin() + 2, name.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      rv.push_back(k);
    }
  }
  if (static_cast<int>(rv.size()) != n) {
    fail(
        "maximum likelihood: the drive model does not name one Rv parameter per motor; give "
        "the fitted axes explicitly");
  }
  std::vector<double> tau(n), J(static_cast<size_t>(n) * P);
  std::vector<bool> moving(n, false);
  for (Eigen::Index s = 0; s < total; ++s) {
    model.torque_jacobian(s, theta.data(), tau.data(), J.data());
    for (int i = 0; i < n; ++i) {
      if (J[static_cast<size_t>(i) * P + rv[i]] != 0) moving[i] = true;
    }
  }
  std::vector<int> axes;
  for (int i = 0; i < n; ++i) {
    if (moving[i]) axes.push_back(i);
  }
  if (axes.empty()) fail("maximum likelihood: no motor moves in the data");
  return axes;
}

// Every fitted axis exists and has a positive, finite noise standard deviation.
void check_axes(const std::vector<int>& axes, const Eigen::MatrixXd& sigma, int n) {
  for (const int i : axes) {
    if (i < 0 || i >= n) {
      fail("maximum likelihood: axis " + std::to_string(i + 1) + " does not exist (the model has " +
           std::to_string(n) + ")");
    }
    for (Eigen::Index s = 0; s < sigma.rows(); ++s) {
      if (!(sigma(s, i) > 0) || !std::isfinite(sigma(s, i))) {
        fail("maximum likelihood: the noise standard deviation of axis " + std::to_string(i + 1) +
             " is '" + std::to_string(sigma(s, i)) + "'; it must be positive and finite");
      }
    }
  }
}

}  // namespace

MlExperiment ml_experiment(const PreparedExperiment& prepared, const DriveChain& drive) {
  const Trajectory& x = prepared.data;
  const Eigen::Index n = x.q.cols();
  if (prepared.tau_noise_variance.size() == 0) {
    fail(x.source +
         ": error: no torque noise variance; the maximum-likelihood fit needs "
         "periodic data prepared with period averaging (--periodic)");
  }
  if (drive.motor_from_joint.rows() != n || drive.motor_from_joint.cols() != n ||
      prepared.tau_noise_variance.size() != n || x.tau.cols() != n) {
    fail(x.source + ": error: the experiment has " + std::to_string(n) +
         " joints but the drive chain or the noise variance another size");
  }
  const Eigen::MatrixXd K_inv_T = drive.motor_from_joint.inverse().transpose();
  MlExperiment out;
  out.source = x.source;
  out.q = x.q;
  out.dq = x.dq;
  out.ddq = x.ddq;
  // tau_joint = K^T tau_M (power balance), so tau_M = K^-T tau_joint.
  out.tau_M = x.tau * K_inv_T.transpose();
  out.sigma = (K_inv_T.array().square().matrix() * prepared.tau_noise_variance).cwiseSqrt();
  return out;
}

std::vector<std::string> ml_param_names(const DriveModel& model) {
  std::vector<std::string> names = model.param_names();
  names.insert(names.end(), load_param_names().begin(), load_param_names().end());
  return names;
}

MlProblem::MlProblem(DriveModel& model, const std::vector<MlExperiment>& data, MlSetup setup,
                     const Eigen::VectorXd& values)
    : impl_(std::make_unique<Impl>()) {
  Impl& p = *impl_;
  p.model = &model;
  p.P = model.num_params();
  p.names = ml_param_names(model);
  const int n = model.dof();
  check_values(p.names, values);
  p.values = values;
  std::map<std::string, int> index;
  for (size_t k = 0; k < p.names.size(); ++k) index[p.names[k]] = static_cast<int>(k);
  p.unknown = resolve_unknowns(p.names, index, setup.unknown);
  if (setup.payload_link > 0) {
    p.payload = payload_parameters(index, setup.payload_link, p.P);
  } else if (p.unknown_load()) {
    fail("maximum likelihood: load parameters are unknown but no payload link is given");
  }

  StackedSamples stacked = stack_experiments(data, n);
  const Eigen::Index total = stacked.q.rows();
  p.measured = std::move(stacked.measured);
  p.sigma = std::move(stacked.sigma);
  model.set_samples(stacked.q, stacked.dq, stacked.ddq);

  if (setup.axes.empty()) {
    setup.axes = moving_axes(model, p.names, p.P, p.drive_parameters(p.values), total);
  }
  check_axes(setup.axes, p.sigma, n);
  p.setup = std::move(setup);
  p.residuals = total * static_cast<Eigen::Index>(p.setup.axes.size());
  if (p.residuals <= static_cast<Eigen::Index>(p.unknown.size())) {
    fail("maximum likelihood: " + std::to_string(p.residuals) + " residuals for " +
         std::to_string(p.unknown.size()) + " unknowns; more data are needed");
  }
  const Eigen::Index block = std::max(1, p.setup.samples_per_block);
  for (Eigen::Index begin = 0; begin < total; begin += block) {
    p.blocks.push_back(std::make_unique<Impl::BlockCost>(p, begin, std::min(total, begin + block)));
  }
}

MlProblem::~MlProblem() = default;

const DriveModel& MlProblem::model() const { return *impl_->model; }
const std::vector<std::string>& MlProblem::unknown_names() const { return impl_->setup.unknown; }
const std::vector<int>& MlProblem::axes() const { return impl_->setup.axes; }
int MlProblem::num_unknowns() const { return static_cast<int>(impl_->unknown.size()); }
Eigen::Index MlProblem::num_residuals() const { return impl_->residuals; }
Eigen::Index MlProblem::num_samples() const { return impl_->measured.rows(); }
const std::vector<int>& MlProblem::unknown_indices() const { return impl_->unknown; }
const Eigen::VectorXd& MlProblem::values() const { return impl_->values; }
const std::vector<int>& MlProblem::payload_indices() const { return impl_->payload; }
const Eigen::MatrixXd& MlProblem::measured() const { return impl_->measured; }
const Eigen::MatrixXd& MlProblem::sigma() const { return impl_->sigma; }

void MlProblem::set_values(const Eigen::VectorXd& values) {
  if (values.size() != impl_->values.size()) fail("maximum likelihood: wrong number of values");
  impl_->values = values;
}

Eigen::VectorXd MlProblem::initial() const {
  Eigen::VectorXd theta1(num_unknowns());
  for (int u = 0; u < num_unknowns(); ++u) theta1[u] = impl_->values[impl_->unknown[u]];
  return theta1;
}

Eigen::VectorXd MlProblem::with_unknowns(const Eigen::VectorXd& theta1) const {
  return impl_->with_unknowns(theta1.data());
}

Eigen::VectorXd MlProblem::drive_parameters(const Eigen::VectorXd& all_values) const {
  return impl_->drive_parameters(all_values);
}

void MlProblem::evaluate(const Eigen::VectorXd& theta1, Eigen::VectorXd& residuals,
                         Eigen::MatrixXd* J) const {
  const int U = num_unknowns();
  residuals.resize(num_residuals());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows;
  if (J != nullptr) rows.resize(num_residuals(), U);
  const double* parameters[1] = {theta1.data()};
  Eigen::Index at = 0;
  for (const auto& block : impl_->blocks) {
    double* jacobians[1] = {J != nullptr ? rows.data() + at * U : nullptr};
    block->Evaluate(parameters, residuals.data() + at, J != nullptr ? jacobians : nullptr);
    at += block->num_residuals();
  }
  if (J != nullptr) *J = rows;
}

Eigen::MatrixXd MlProblem::torque_errors(const Eigen::VectorXd& all_values) const {
  const Impl& p = *impl_;
  const int n = p.model->dof();
  const Eigen::VectorXd theta = p.drive_parameters(all_values);
  Eigen::MatrixXd errors = Eigen::MatrixXd::Zero(num_samples(), n);
  std::vector<double> tau(n);
  for (Eigen::Index s = 0; s < num_samples(); ++s) {
    p.model->torque(s, theta.data(), tau.data());
    for (const int i : p.setup.axes) errors(s, i) = p.measured(s, i) - tau[i];
  }
  return errors;
}

std::vector<ceres::CostFunction*> detail::MlProblemAccess::cost_functions(
    const MlProblem& problem) {
  std::vector<ceres::CostFunction*> out;
  for (const auto& block : problem.impl_->blocks) out.push_back(block.get());
  return out;
}

}  // namespace modelgen
