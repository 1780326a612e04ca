// The inertial parameters of a payload as Swevers et al. 2002 write them (eq. 3: mass, centre of
// gravity, inertia about the centre of gravity) and the ten standard parameters of the link that
// carries it (Gautier & Briot eq. 3), both ways, with the analytic Jacobian, and the
// physical-consistency checks an estimated load must pass before anyone trusts it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace modelgen {

/// Number of load parameters (Swevers eq. 3).
constexpr int kLoadParams = 10;

/// A rigid load in the frame of the link carrying it (the payload link).
/// As a vector (to_vector) in Swevers eq. 3 order: m, cx, cy, cz, Ixx, Iyy, Izz, Ixy, Ixz, Iyz.
struct LoadParameters {
  double mass = 0;              ///< kg
  std::array<double, 3> com{};  ///< centre of gravity x, y, z in m
  /// Inertia tensor about the centre of gravity, kg m^2, entries xx yy zz xy xz yz. Off-diagonal
  /// entries are tensor entries (Ixy = -integral of x y dm, as XY in the standard parameters).
  std::array<double, 6> inertia{};

  std::array<double, kLoadParams> to_vector() const;
  /// From 10 values in to_vector() order.
  static LoadParameters from_vector(const double* values);
};

/// Names of the load parameters in to_vector() order: load_m, load_cx, load_cy, load_cz,
/// load_Ixx, load_Iyy, load_Izz, load_Ixy, load_Ixz, load_Iyz.
const std::vector<std::string>& load_param_names();

/// The ten standard parameters XX XY XZ YY YZ ZZ MX MY MZ M (about the payload link's frame
/// origin; kg m^2, kg m, kg) of a load given as 10 values in LoadParameters::to_vector() order:
/// the parallel-axis theorem J_O = I_c + m (|c|^2 1 - c c^T), first moments m c.
/// A template so that Ceres' automatic differentiation can go through it (T = double or Jet).
template <class T>
void standard_from_load(const T* load, T* standard) {
  const T& m = load[0];
  const T& cx = load[1];
  const T& cy = load[2];
  const T& cz = load[3];
  standard[0] = load[4] + m * (cy * cy + cz * cz);  // XX
  standard[1] = load[7] - m * cx * cy;              // XY
  standard[2] = load[8] - m * cx * cz;              // XZ
  standard[3] = load[5] + m * (cx * cx + cz * cz);  // YY
  standard[4] = load[9] - m * cy * cz;              // YZ
  standard[5] = load[6] + m * (cx * cx + cy * cy);  // ZZ
  standard[6] = m * cx;                             // MX
  standard[7] = m * cy;                             // MY
  standard[8] = m * cz;                             // MZ
  standard[9] = m;                                  // M
}

/// standard_from_load for a LoadParameters.
std::array<double, 10> standard_from_load(const LoadParameters& load);

/// d standard / d load: 10 x 10, row k the standard parameter k (XX ... M), column l the load
/// parameter l (to_vector() order).
Eigen::MatrixXd standard_from_load_jacobian(const LoadParameters& load);

/// The inverse of standard_from_load: `standard` has 10 values XX XY XZ YY YZ ZZ MX MY MZ M.
/// Throws std::invalid_argument if a value is not finite or the mass M is not positive (no
/// centre of gravity exists then); the message gives the mass found.
LoadParameters load_from_standard(const double* standard);

/// What makes `load` physically impossible, in words, one warning per problem; empty when it is
/// consistent: a mass that is not positive, an inertia about the centre of gravity that is not
/// positive definite (principal moments given), principal moments violating the triangle
/// inequality (each at most the sum of the other two), non-finite values.
std::vector<std::string> physical_consistency_warnings(const LoadParameters& load);

/// physical_consistency_warnings() of an estimated load whose entries are all numbers; none when
/// some are NaN, the mark of a parameter the data do not identify (a consistency judgement
/// would need it, and the estimate reports it as not identifiable already).
std::vector<std::string> load_warnings(const LoadParameters& load);

}  // namespace modelgen
