// The closed loop sample by sample: measure, command, hold, integrate (RK4 with substeps).

#include "modelgen/closed_loop/closed_loop_simulation.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

#include "modelgen/closed_loop/forward_dynamics.hpp"
#include "modelgen/signal/gaussian_noise.hpp"
#include "runtime/src/closed_loop/coulomb_friction.hpp"

namespace modelgen {

namespace {

void check_vector(const Eigen::VectorXd& v, int n, const char* what) {
  if (v.size() != 0 && v.size() != n) {
    throw std::invalid_argument(std::string("closed-loop simulation: ") + what + " has " +
                                std::to_string(v.size()) + " values, the robot " +
                                std::to_string(n) + " joints");
  }
  if (v.size() != 0 && (!v.allFinite() || (v.array() < 0).any())) {
    throw std::invalid_argument(std::string("closed-loop simulation: ") + what +
                                " must be finite and >= 0");
  }
}

// The plant: accelerations from (q, dq) under a held torque, Coulomb friction smoothed.
class Plant {
 public:
  Plant(const IdentificationModel& model, const std::vector<double>& beta,
        const Eigen::VectorXd& q0, const ClosedLoopOptions& options, double substep)
      : terms_(detail::coulomb_terms(model, beta)),
        dynamics_(model, without_coulomb(beta)),
        friction_(model.dof()),
        applied_(model.dof()) {
    if (!options.smooth_coulomb) return;
    const int n = model.dof();
    Eigen::MatrixXd M(n, n);
    model.mass_matrix(q0.data(), beta.data(), M.data());
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    for (detail::CoulombTerm& term : terms_) {
      const double mobility =
          llt.info() == Eigen::Success ? term.a.dot(llt.solve(term.a)) : 0.0;
      term.smoothing =
          std::max(options.min_smoothing, 2.0 * substep * std::abs(term.value) * mobility);
    }
  }

  void accelerations(const double* q, const double* dq, const Eigen::VectorXd& tau,
                     double* ddq) {
    detail::smoothed_coulomb_torque(terms_, dq, friction_);
    applied_ = tau - friction_;
    dynamics_.accelerations(q, dq, applied_.data(), ddq);
  }

 private:
  std::vector<double> without_coulomb(std::vector<double> beta) const {
    for (const detail::CoulombTerm& term : terms_) beta[static_cast<std::size_t>(term.param)] = 0;
    return beta;
  }

  std::vector<detail::CoulombTerm> terms_;
  ForwardDynamics dynamics_;
  Eigen::VectorXd friction_, applied_;
};

}  // namespace

ClosedLoopRun simulate_closed_loop(const IdentificationModel& model, const std::vector<double>& beta,
                                   PidController& controller, const Eigen::MatrixXd& qr,
                                   const Eigen::VectorXd& q0, const Eigen::VectorXd& dq0,
                                   const ClosedLoopOptions& options, double t0) {
  const int n = model.dof();
  if (controller.dof() != n || qr.cols() != n || q0.size() != n || dq0.size() != n) {
    throw std::invalid_argument("closed-loop simulation: the controller, the reference and the "
                                "initial state must have " + std::to_string(n) +
                                " joints like " + model.name());
  }
  if (static_cast<int>(beta.size()) != model.num_base_params()) {
    throw std::invalid_argument("closed-loop simulation: " + std::to_string(beta.size()) +
                                " base parameters given, " + model.name() + " has " +
                                std::to_string(model.num_base_params()));
  }
  if (options.substeps < 1) {
    throw std::invalid_argument("closed-loop simulation: substeps must be at least 1");
  }
  check_vector(options.encoder_resolution, n, "the encoder resolution");
  check_vector(options.q_noise, n, "the position noise");
  check_vector(options.tau_noise, n, "the torque noise");
  if (!qr.allFinite() || !q0.allFinite() || !dq0.allFinite()) {
    throw std::invalid_argument("closed-loop simulation: the reference or the initial state is "
                                "not finite");
  }
  const double ts = controller.gains().sample_time;
  const double h = ts / options.substeps;
  Plant plant(model, beta, q0, options, h);
  controller.reset();
  GaussianNoise gaussian(options.seed);

  const Eigen::Index samples = qr.rows();
  ClosedLoopRun run;
  run.t.resize(samples);
  for (Eigen::Index k = 0; k < samples; ++k) run.t[k] = t0 + ts * static_cast<double>(k);
  run.qr = qr;
  for (Eigen::MatrixXd* m : {&run.q_measured, &run.tau_command, &run.tau_recorded, &run.q,
                             &run.dq, &run.ddq}) {
    m->resize(samples, n);
  }
  Eigen::VectorXd q = q0, dq = dq0, measured(n), tau(n);
  Eigen::VectorXd k1q(n), k1v(n), k2q(n), k2v(n), k3q(n), k3v(n), k4q(n), k4v(n), qs(n), vs(n);
  for (Eigen::Index k = 0; k < samples; ++k) {
    // Measure: the encoder's counts, then its noise.
    for (int j = 0; j < n; ++j) {
      double value = q[j];
      if (options.encoder_resolution.size() != 0 && options.encoder_resolution[j] > 0) {
        value = options.encoder_resolution[j] * std::round(value / options.encoder_resolution[j]);
      }
      if (options.q_noise.size() != 0) value += options.q_noise[j] * gaussian();
      measured[j] = value;
    }
    tau = controller.command(qr.row(k).transpose(), measured);
    run.q_measured.row(k) = measured.transpose();
    run.tau_command.row(k) = tau.transpose();
    run.q.row(k) = q.transpose();
    run.dq.row(k) = dq.transpose();
    try {
      plant.accelerations(q.data(), dq.data(), tau, k1v.data());
      run.ddq.row(k) = k1v.transpose();
      if (k + 1 == samples) break;
      // Hold tau over the sample; classical RK4 on (q, dq) per substep.
      for (int step = 0; step < options.substeps; ++step) {
        if (step > 0) plant.accelerations(q.data(), dq.data(), tau, k1v.data());
        k1q = dq;
        qs = q + 0.5 * h * k1q;
        vs = dq + 0.5 * h * k1v;
        k2q = vs;
        plant.accelerations(qs.data(), vs.data(), tau, k2v.data());
        qs = q + 0.5 * h * k2q;
        vs = dq + 0.5 * h * k2v;
        k3q = vs;
        plant.accelerations(qs.data(), vs.data(), tau, k3v.data());
        qs = q + h * k3q;
        vs = dq + h * k3v;
        k4q = vs;
        plant.accelerations(qs.data(), vs.data(), tau, k4v.data());
        q += h / 6.0 * (k1q + 2 * k2q + 2 * k3q + k4q);
        dq += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
      }
    } catch (const std::domain_error& e) {
      std::ostringstream message;
      message << "closed-loop simulation of " << model.name() << " stopped at t = " << run.t[k]
              << " s (the loop is unstable or the parameters are not physical): " << e.what();
      throw std::domain_error(message.str());
    }
  }
  run.tau_recorded = run.tau_command;
  if (options.tau_noise.size() != 0) {
    for (Eigen::Index k = 0; k < samples; ++k) {
      for (int j = 0; j < n; ++j) run.tau_recorded(k, j) += options.tau_noise[j] * gaussian();
    }
  }
  return run;
}

}  // namespace modelgen
