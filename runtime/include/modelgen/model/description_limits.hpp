// What modelgen accepts in a robot description, and why each bound is where it is. Inputs
// beyond these are refused with an InputError naming the file, the line and the limit, instead
// of an allocation that cannot succeed, a generation that runs for minutes, or products that
// overflow to infinity somewhere inside the dynamics (README, "Limits").
#pragma once

#include <cstdint>

namespace modelgen {

/// Description files are read whole; real URDFs and MDH tables are well below 1 MiB.
inline constexpr std::uintmax_t kMaxDescriptionBytes = 32u << 20;  // 32 MiB
/// Links of a URDF (fixed ones included; they are folded into the moving bodies).
inline constexpr int kMaxUrdfLinks = 10000;
/// Moving joints of the model. Generation grows with about the cube of the joints (30
/// joints: 9 s and 24 MB of code; 15: 1.8 s and 6 MB), the numeric base-parameter derivation
/// with about the square; 32 covers every fixed-base manipulator, dual-arm ones included.
inline constexpr int kMaxMovingJoints = 32;
/// Rows of an MDH table (fixed frames are bodies with parameters of their own).
inline constexpr int kMaxBodies = 64;
/// Lengths (URDF xyz, MDH d and r) in metres, and gravity in m/s^2: a kilometre is beyond
/// any robot, and squared lengths times masses must stay far from overflow.
inline constexpr double kMaxLength = 1e3;
/// Masses in kg.
inline constexpr double kMaxMass = 1e6;
/// Angles in rad (rpy, alpha, theta, offsets).
inline constexpr double kMaxAngle = 1e3;
/// Any other number of a description (inertias, a-priori values, gear ratios, coupling
/// entries, torque constants, axis components).
inline constexpr double kMaxMagnitude = 1e9;
/// A joint axis shorter than this gives no reliable direction (its squared norm underflows
/// long before 1e-200).
inline constexpr double kMinAxisNorm = 1e-6;

}  // namespace modelgen
