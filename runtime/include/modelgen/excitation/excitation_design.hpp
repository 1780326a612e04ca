// Optimal periodic excitation (Swevers et al. 1997; Bona & Curatella eq. 17-20): the Fourier
// coefficients and offsets of the moving axes that minimise a criterion of the base regressor
// stacked over one period, subject to the joint position, velocity and acceleration limits
// times a margin. Solved by NLopt's SLSQP from the best of several random feasible starts;
// the result is checked on a dense grid and, where it leaves a limit between the optimiser's
// constraint points, that joint's oscillation is shrunk until it does not. With a-priori
// parameters, the joint torques they give are held within the effort limits the same way.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/excitation/design_criterion.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

struct ExcitationDesignProblem {
  const IdentificationModel* model = nullptr;
  double period = 10;  ///< s
  int harmonics = 5;
  std::vector<int> moving;          ///< 0-based joints that move; the others are held
  Eigen::VectorXd hold;             ///< dof positions; those of held joints are used
  std::vector<JointLimits> limits;  ///< dof; moving joints need q, dq and ddq
  double margin = 0.95;             ///< fraction of each limit the design may use
  /// A-priori base parameters (model->num_base_params() values), or empty. When given, the
  /// torque of every joint with an effort limit, model->inverse_dynamics at these values, is
  /// held within margin * effort: at the constraint points during the optimisation, on the
  /// dense grid after it (torque_use.hpp). Empty: effort limits are not looked at.
  Eigen::VectorXd a_priori;
  DesignCriterion criterion = DesignCriterion::kCond;
  int samples = 0;          ///< regressor samples per period; 0: 40 per highest harmonic, >= 100
  int random_starts = 100;  ///< random feasible trajectories drawn
  int starts = 3;           ///< the best ones optimised
  int max_evaluations = 1000;  ///< per optimised start
  std::uint64_t seed = 1;
  std::function<void(const std::string&)> progress;  ///< one line per step, may be empty
};

struct ExcitationDesign {
  /// Position form (Swevers 2002 eq. 15): q = q0 + sum a_l sin(l wf t) + b_l cos(l wf t),
  /// dof x harmonics; held joints have q0 = their position and no terms.
  Eigen::VectorXd q0;
  Eigen::MatrixXd a, b;
  double period = 0;
  int samples = 0;                      ///< regressor samples per period used
  std::vector<int> columns;             ///< base parameters the moving axes excite (0-based)
  /// The fixed scale of those columns: their RMS norm over the random feasible starts.
  Eigen::VectorXd scale;
  CriterionValue before;                ///< the best random feasible start
  CriterionValue after;                 ///< the design
  std::vector<double> shrink;           ///< per joint, the dense-grid repair factor (1: none)
  /// The factor every moving joint's oscillation was multiplied by to keep the a-priori
  /// torques within the effort limits on the dense grid (1: none needed).
  double torque_shrink = 1;
  int evaluations = 0;
  Eigen::MatrixXd regressor;            ///< the stacked regressor of the design (all columns)
};

/// The trajectory of position-form coefficients in FourierTrajectory's velocity form.
FourierTrajectory to_trajectory(const Eigen::VectorXd& q0, const Eigen::MatrixXd& a,
                                const Eigen::MatrixXd& b, double period);

/// The base regressor of `model` stacked over `samples` equally spaced instants of one period,
/// (samples * dof) x num_base_params, sample after sample.
Eigen::MatrixXd stacked_regressor(const IdentificationModel& model,
                                  const FourierTrajectory& trajectory, int samples);

/// The objective SLSQP minimises at variables `x` (per moving joint: q0, a_1..a_L, b_1..b_L of
/// the position form) over base-parameter `columns` divided by `scale`, and its gradient when
/// `gradient` is not null: the optimiser's own, exposed for tests.
double design_objective(const ExcitationDesignProblem& problem, const std::vector<int>& columns,
                        const Eigen::VectorXd& scale, const std::vector<double>& x,
                        std::vector<double>* gradient);

/// The inequality constraints c(x) <= 0 SLSQP is given at variables `x` (the limits of the
/// moving joints at 16 points per period of the highest harmonic, then the effort limits when
/// problem.a_priori is set), and their Jacobian (row-major, constraints x variables) when
/// `jacobian` is not null: the optimiser's own, exposed for tests.
std::vector<double> design_constraints(const ExcitationDesignProblem& problem,
                                       const std::vector<double>& x, std::vector<double>* jacobian);

/// Throws std::invalid_argument for an inconsistent problem (the caller checks limits first),
/// std::runtime_error when the effort limits leave no feasible random start or cannot be met
/// on the dense grid (the a-priori torque at rest already exceeds one).
ExcitationDesign design_excitation(const ExcitationDesignProblem& problem);

}  // namespace modelgen
