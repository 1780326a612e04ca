// The pseudo-inertia matrix of a rigid body and its log-Cholesky parametrisation.
//
// A body's ten inertial parameters p = (XX, XY, XZ, YY, YZ, ZZ, MX, MY, MZ, M) — the inertia
// tensor about the body frame's origin, the first moments and the mass, in the order of
// ParamKind — are those of some physical mass distribution exactly when the 4x4 pseudo-inertia
//     P = [ S  h ]    S = 1/2 tr(I) 1 - I  (the second moment of the mass distribution),
//         [ h' m ]    h = (MX, MY, MZ),
// is positive definite (Wensing, Kim & Slotine 2017): P > 0 is m > 0 together with the
// triangle inequalities of the inertia about the centre of mass, strictly.
//
// The log-Cholesky parametrisation (Rucker & Wensing 2022) writes P = U U' with
//     U = e^a [ e^d1  s12   s13   t1 ]
//             [ 0     e^d2  s23   t2 ]
//             [ 0     0     e^d3  t3 ]
//             [ 0     0     0     1  ]
// theta = (a, d1, d2, d3, s12, s23, s13, t1, t2, t3): ten unconstrained numbers, every value
// a physically consistent body and every consistent body one value. Templates, so Ceres can
// differentiate them.
#pragma once

#include <cmath>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace modelgen {

/// Number of inertial parameters of a body and of log-Cholesky parameters.
inline constexpr int kInertialParams = 10;

/// The pseudo-inertia of the inertial parameters p[0..9].
template <class T>
Eigen::Matrix<T, 4, 4> pseudo_inertia(const T* p) {
  Eigen::Matrix<T, 3, 3> I;
  I << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
  const T half_trace = T(0.5) * (p[0] + p[3] + p[5]);
  Eigen::Matrix<T, 4, 4> P;
  P.template topLeftCorner<3, 3>() = Eigen::Matrix<T, 3, 3>::Identity() * half_trace - I;
  P(0, 3) = P(3, 0) = p[6];
  P(1, 3) = P(3, 1) = p[7];
  P(2, 3) = P(3, 2) = p[8];
  P(3, 3) = p[9];
  return P;
}

/// The inertial parameters p[0..9] of a pseudo-inertia: I = tr(S) 1 - S.
template <class T>
void inertial_from_pseudo_inertia(const Eigen::Matrix<T, 4, 4>& P, T* p) {
  const T trace_S = P(0, 0) + P(1, 1) + P(2, 2);
  p[0] = trace_S - P(0, 0);
  p[1] = -P(0, 1);
  p[2] = -P(0, 2);
  p[3] = trace_S - P(1, 1);
  p[4] = -P(1, 2);
  p[5] = trace_S - P(2, 2);
  p[6] = P(0, 3);
  p[7] = P(1, 3);
  p[8] = P(2, 3);
  p[9] = P(3, 3);
}

/// The inertial parameters p[0..9] of the log-Cholesky parameters theta[0..9] (header comment).
template <class T>
void inertial_from_log_cholesky(const T* theta, T* p) {
  using std::exp;
  const T scale = exp(theta[0]);
  Eigen::Matrix<T, 4, 4> U = Eigen::Matrix<T, 4, 4>::Zero();
  U(0, 0) = exp(theta[1]);
  U(1, 1) = exp(theta[2]);
  U(2, 2) = exp(theta[3]);
  U(0, 1) = theta[4];
  U(1, 2) = theta[5];
  U(0, 2) = theta[6];
  U(0, 3) = theta[7];
  U(1, 3) = theta[8];
  U(2, 3) = theta[9];
  U(3, 3) = T(1);
  U *= scale;
  const Eigen::Matrix<T, 4, 4> P = U * U.transpose();
  inertial_from_pseudo_inertia(P, p);
}

/// The log-Cholesky parameters of the inertial parameters p[0..9], or nullopt when their
/// pseudo-inertia is not positive definite (the body is not physically consistent).
inline std::optional<Eigen::Matrix<double, 10, 1>> log_cholesky_from_inertial(const double* p) {
  // P = U U' with U upper triangular is the ordinary (lower) Cholesky factor of P with rows and
  // columns in reverse order: E P E = L L' gives U = E L E.
  const Eigen::Matrix4d P = pseudo_inertia(p);
  const Eigen::Matrix4d reversed = P.reverse();
  const Eigen::LLT<Eigen::Matrix4d> llt(reversed);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix4d L = llt.matrixL();
  const Eigen::Matrix4d U = L.reverse();
  if (!(U(0, 0) > 0 && U(1, 1) > 0 && U(2, 2) > 0 && U(3, 3) > 0)) return std::nullopt;
  const double scale = U(3, 3);
  Eigen::Matrix<double, 10, 1> theta;
  theta << std::log(scale), std::log(U(0, 0) / scale), std::log(U(1, 1) / scale),
      std::log(U(2, 2) / scale), U(0, 1) / scale, U(1, 2) / scale, U(0, 2) / scale,
      U(0, 3) / scale, U(1, 3) / scale, U(2, 3) / scale;
  if (!theta.allFinite()) return std::nullopt;
  return theta;
}

}  // namespace modelgen
