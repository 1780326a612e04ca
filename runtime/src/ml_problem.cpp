// Swevers et al. 2002, eq. 18: weighted motor-torque residuals of the drive model F (eq. 12) as
// ceres::CostFunctions over blocks of samples. The Jacobian is analytic: the drive model's
// d tau_M / d theta columns of the unknowns, and for the load the payload link's columns times
// the 10 x 10 Jacobian of standard_from_load (chain rule through eq. 3).

#include "modelgen/ml_problem.hpp"

#include <ceres/cost_function.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "modelgen/estimate.hpp"
#include "modelgen/load_parameters.hpp"

namespace modelgen {
namespace {

[[noreturn]] void fail(const std::string& message) { throw EstimationError(message); }

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

struct MlProblem::Impl {
  class BlockCost;

  DriveModel* model = nullptr;
  MlSetup setup;
  std::vector<std::string> names;  // ml_param_names
  std::vector<int> unknown;        // indices into names
  std::vector<int> payload;        // drive-parameter indices of XXj .. Mj
  int P = 0;                       // drive model parameters
  Eigen::VectorXd values;
  Eigen::MatrixXd measured, sigma;  // stacked samples x dof
  std::vector<std::unique_ptr<BlockCost>> blocks;
  Eigen::Index residuals = 0;

  bool unknown_load() const {
    return std::any_of(unknown.begin(), unknown.end(), [&](int k) { return k >= P; });
  }

  Eigen::VectorXd drive_parameters(const Eigen::VectorXd& all) const {
    Eigen::VectorXd theta = all.head(P);
    if (!payload.empty()) {
      double standard[10];
      standard_from_load(all.data() + P, standard);
      for (int m = 0; m < 10; ++m) theta[payload[m]] += standard[m];
    }
    return theta;
  }

  Eigen::VectorXd with_unknowns(const double* theta1) const {
    Eigen::VectorXd all = values;
    for (size_t u = 0; u < unknown.size(); ++u) all[unknown[u]] = theta1[u];
    return all;
  }
};

// Residuals of samples [begin, end): (tau_M measured - F) / sigma on the fitted axes.
class MlProblem::Impl::BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const Impl& problem, Eigen::Index begin, Eigen::Index end)
      : problem_(problem), begin_(begin), end_(end) {
    set_num_residuals(static_cast<int>((end - begin) * problem.setup.axes.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(problem.unknown.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Impl& p = problem_;
    const int n = p.model->dof(), P = p.P, U = static_cast<int>(p.unknown.size());
    const Eigen::VectorXd all = p.with_unknowns(parameters[0]);
    const Eigen::VectorXd theta = p.drive_parameters(all);
    double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
    // d standard / d load for the chain rule, once per block.
    Eigen::MatrixXd S;
    if (jacobian != nullptr && !p.payload.empty() && p.unknown_load()) {
      S = standard_from_load_jacobian(LoadParameters::from_vector(all.data() + P));
    }
    std::vector<double> tau(n), J(jacobian != nullptr ? static_cast<size_t>(n) * P : 0);
    int row = 0;
    for (Eigen::Index s = begin_; s < end_; ++s) {
      if (jacobian != nullptr) {
        p.model->torque_jacobian(s, theta.data(), tau.data(), J.data());
      } else {
        p.model->torque(s, theta.data(), tau.data());
      }
      for (const int i : p.setup.axes) {
        const double w = 1.0 / p.sigma(s, i);
        residuals[row] = (p.measured(s, i) - tau[i]) * w;
        if (jacobian != nullptr) {
          const double* dF = &J[static_cast<size_t>(i) * P];
          double* out = jacobian + static_cast<size_t>(row) * U;
          for (int u = 0; u < U; ++u) {
            const int k = p.unknown[u];
            double d = 0;
            if (k < P) {
              d = dF[k];
            } else {
              for (int m = 0; m < 10; ++m) d += dF[p.payload[m]] * S(m, k - P);
            }
            out[u] = -w * d;
          }
        }
        ++row;
      }
    }
    return true;
  }

 private:
  const Impl& problem_;
  Eigen::Index begin_, end_;
};

MlProblem::MlProblem(DriveModel& model, const std::vector<MlExperiment>& data, MlSetup setup,
                     const Eigen::VectorXd& values)
    : impl_(std::make_unique<Impl>()) {
  Impl& p = *impl_;
  p.model = &model;
  p.P = model.num_params();
  p.names = ml_param_names(model);
  const int n = model.dof();
  if (values.size() != static_cast<Eigen::Index>(p.names.size())) {
    fail("maximum likelihood: " + std::to_string(values.size()) + " parameter values given, " +
         std::to_string(p.names.size()) + " expected (ml_param_names order)");
  }
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) {
      fail("maximum likelihood: parameter '" + p.names[k] + "' has the value '" +
           std::to_string(values[k]) + "'; values must be finite");
    }
  }
  p.values = values;
  std::map<std::string, int> index;
  for (size_t k = 0; k < p.names.size(); ++k) index[p.names[k]] = static_cast<int>(k);
  if (setup.unknown.empty()) fail("maximum likelihood: no unknown parameter given");
  for (const std::string& name : setup.unknown) {
    const auto found = index.find(name);
    if (found == index.end()) {
      std::string valid;
      for (const std::string& v : p.names) valid += (valid.empty() ? "" : " ") + v;
      fail("maximum likelihood: unknown parameter '" + name +
           "' is not a parameter of the model; "
           "valid names: " +
           valid);
    }
    if (std::find(p.unknown.begin(), p.unknown.end(), found->second) != p.unknown.end()) {
      fail("maximum likelihood: parameter '" + name + "' is listed twice as unknown");
    }
    p.unknown.push_back(found->second);
  }
  if (setup.payload_link > 0) {
    for (const char* stem : {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"}) {
      const std::string name = stem + std::to_string(setup.payload_link);
      const auto found = index.find(name);
      if (found == index.end() || found->second >= p.P) {
        fail("maximum likelihood: payload link " + std::to_string(setup.payload_link) +
             " has no parameter '" + name + "' in the drive model");
      }
      p.payload.push_back(found->second);
    }
  } else if (p.unknown_load()) {
    fail("maximum likelihood: load parameters are unknown but no payload link is given");
  }

  // Stack the experiments.
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
  Eigen::MatrixXd q(total, n), dq(total, n), ddq(total, n);
  p.measured.resize(total, n);
  p.sigma.resize(total, n);
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
    q.middleRows(at, s) = x.q;
    dq.middleRows(at, s) = x.dq;
    ddq.middleRows(at, s) = x.ddq;
    p.measured.middleRows(at, s) = x.tau_M;
    p.sigma.middleRows(at, s) = x.sigma.transpose().replicate(s, 1);
    at += s;
  }

  model.set_samples(q, dq, ddq);

  if (setup.axes.empty()) {
    // A motor moves exactly when d tau_M,i / d Rv_i = dq_M,i (eq. 5) is not zero somewhere;
    // motor i's Rv is the i-th parameter named Rv<j>.
    std::vector<int> rv;
    for (int k = 0; k < p.P; ++k) {
      const std::string& name = p.names[k];
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
    std::vector<double> tau(n), J(static_cast<size_t>(n) * p.P);
    const Eigen::VectorXd theta = p.drive_parameters(p.values);
    std::vector<bool> moving(n, false);
    for (Eigen::Index s = 0; s < total; ++s) {
      model.torque_jacobian(s, theta.data(), tau.data(), J.data());
      for (int i = 0; i < n; ++i) {
        if (J[static_cast<size_t>(i) * p.P + rv[i]] != 0) moving[i] = true;
      }
    }
    for (int i = 0; i < n; ++i) {
      if (moving[i]) setup.axes.push_back(i);
    }
    if (setup.axes.empty()) fail("maximum likelihood: no motor moves in the data");
  }
  for (const int i : setup.axes) {
    if (i < 0 || i >= n) {
      fail("maximum likelihood: axis " + std::to_string(i + 1) + " does not exist (the model has " +
           std::to_string(n) + ")");
    }
    for (Eigen::Index s = 0; s < total; ++s) {
      if (!(p.sigma(s, i) > 0) || !std::isfinite(p.sigma(s, i))) {
        fail("maximum likelihood: the noise standard deviation of axis " + std::to_string(i + 1) +
             " is '" + std::to_string(p.sigma(s, i)) + "'; it must be positive and finite");
      }
    }
  }
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

std::vector<ceres::CostFunction*> MlProblem::cost_functions() const {
  std::vector<ceres::CostFunction*> out;
  for (const auto& block : impl_->blocks) out.push_back(block.get());
  return out;
}

}  // namespace modelgen
