// The simulated KR150 load identification of Swevers et al. 2002 (sections 4-5), shared by
// tests/runtime/ml/ml_fit_test.cpp and tests/benchmarks/ml_benchmark.cpp: the Table 1 excitation
// (eq. 15, period 36.96 s, 1540 samples) of axes 3-6 or of the wrist, the Table 2 load on link 7,
// transmission efficiencies below 1, and Gaussian noise on the averaged motor torques, all built
// in-process through the numeric reference drive model.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::test {

/// Swevers Table 2: the load of the real experiments (centre of gravity in m).
LoadParameters table2_load();

/// Swevers Table 1 in eq. 15 form (q = q0 + sum a sin + b cos): joint positions, velocities and
/// accelerations (6 each) at time `t` (s), axes 1 and 2 held; `move_axis3` false holds axis 3 at
/// its offset too (the wrist-only experiment).
void table1_state(double t, bool move_axis3, Eigen::VectorXd& q, Eigen::VectorXd& dq,
                  Eigen::VectorXd& ddq);

struct Kr150LoadScenario {
  static constexpr double kPeriod = 36.96;  ///< s, Table 1
  static constexpr int kSamples = 1540;     ///< per period (24 ms)
  /// Noise on the averaged motor torques (N m), axes 1-6.
  static constexpr double kSigma[6] = {5, 5, 5, 2, 2, 1.5};
  /// The true drive parameters per motor 1-6: JM (kg m^2), Rv (N m s/rad), Rc (N m), Rz.
  static constexpr double kJM[6] = {20, 20, 8, 2, 2, 1};
  static constexpr double kRv[6] = {80, 80, 40, 12, 10, 8};
  static constexpr double kRc[6] = {150, 150, 90, 30, 25, 20};
  static constexpr double kRz[6] = {0.9, 0.9, 0.85, 0.88, 0.9, 0.87};

  modelgen::RobotModel description;            ///< robots/kr150.yaml
  std::unique_ptr<ReferenceDriveModel> model;  ///< the drive model the torques come from
  std::vector<std::string> names;              ///< ml_param_names(*model)
  /// Every ml_param_names() value: known link parameters physical and random (seed 2002), link
  /// 7 (the flange) zero but for the load, JM, Rv, Rc, Rz per motor, the Table 2 load.
  Eigen::VectorXd truth;
  /// One period: q, dq, ddq of Table 1, tau_M of the true model plus noise of kSigma.
  MlExperiment data;

  /// `move_axis3` false holds axis 3 at its offset (the wrist-only experiment).
  explicit Kr150LoadScenario(bool move_axis3, int samples = kSamples);

  /// Approach 3's unknowns (Swevers section 3.2): the load, then Rv, Rc, Rz of the 0-based
  /// `axes`.
  std::vector<std::string> unknowns(const std::vector<int>& axes) const;

  /// The known values of `truth` and a starting point far from it for `unknown`.
  Eigen::VectorXd start(const std::vector<std::string>& unknown) const;
};

}  // namespace modelgen::test
