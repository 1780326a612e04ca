// The validated robot description: joints as the user wrote them (MDH parameters or URDF
// transforms, limits, where in the file), the RigidBodyTree the dynamics compute on, the drive
// chain (gear ratios, motor/joint coupling; drive_chain.hpp), the friction options and
// a-priori parameter values.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/drive_chain.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen {

/// An angle as written: its value, and when it was written as a rational multiple of pi
/// ("-pi/2", "3*pi/4") that fraction, so symbolic code can use exact sines and cosines.
struct Angle {
  double value = 0;  ///< radians
  bool is_pi_fraction = false;
  long numerator = 0;    ///< value = pi * numerator / denominator when is_pi_fraction
  long denominator = 1;  ///< > 0, fraction in lowest terms
  std::string text;      ///< as written, for messages and the describe table

  static Angle from_radians(double radians);
  static Angle pi_fraction(long numerator, long denominator, std::string text);

  /// cos and sin, exact (0, +-1) for multiples of pi/2 written as fractions of pi.
  double cos() const;
  double sin() const;
};

/// Parses a number or a simple expression of pi: "0.5", "-pi/2", "3*pi/4", "pi", "2 * pi / 3".
/// Returns nullopt if the text is none of these.
std::optional<Angle> parse_angle(std::string_view text);

/// Khalil-Kleinfinger modified DH parameters of one frame (for a revolute joint theta is the
/// offset added to q; for a prismatic one r is).
struct MdhParameters {
  Angle alpha;
  double d = 0;
  Angle theta;
  double r = 0;
};

struct JointLimits {
  std::optional<double> q_lower, q_upper;  ///< rad or m
  std::optional<double> dq;                ///< max |velocity|
  std::optional<double> ddq;               ///< max |acceleration|
  std::optional<double> effort;            ///< max |torque|, N m or N
  /// A URDF `continuous` joint: unbounded in q, so no q limit is needed (q_lower and q_upper
  /// stay empty); its dq, ddq and effort limits still apply.
  bool continuous = false;
};

/// One joint/link as described; index-aligned with RigidBodyTree::bodies.
struct JointDescription {
  std::string name;
  std::string parent_link;             ///< URDF only: the parent link's name
  std::optional<MdhParameters> mdh;    ///< set for MDH descriptions
  JointLimits limits;
  SourceLocation where;
};

struct FrictionOptions {
  bool viscous = true;
  bool coulomb = true;
  bool offset = true;
  bool asymmetric = false;  ///< Bona & Curatella eq. 2: separate coefficients per direction
};

enum class DescriptionFormat { kMdhYaml, kUrdf };

/// Something the loader changed or assumed that the user should know about but that is not an
/// error (a rounded quarter turn taken as exact). Printed as "file:line: note: message", or
/// "file:line: warning: message" for a value that is likely a unit slip (degrees for radians).
struct DescriptionNote {
  SourceLocation where;
  std::string message;
  bool warning = false;

  std::string to_string() const;
};

/// Where a body's mass can be, from the description's geometry: the ellipsoid
/// sum_i ((x_i - centre_i) / semi_axes_i)^2 <= 1 in the body frame (axes along the frame's),
/// the one through the corners of the box that holds every collision shape (else visual shape)
/// of the body's links: boxes, cylinders, spheres; meshes have no size without their file.
/// A body without shapes (URDF meshes only; an MDH YAML link without `region:`) and without
/// a-priori inertial values gets a region guessed from the segments to its next joints and
/// tool frames (`guessed`); a YAML description may give one per link (`region:`).
struct BodyRegion {
  std::array<double, 3> centre{};
  std::array<double, 3> semi_axes{};
  bool guessed = false;  ///< from the joints' positions, not from a shape or the description
  bool at_joint = false;  ///< guessed without a segment (no child joint or tool frame): a sphere
};

struct RobotModel {
  std::string name;         ///< C++ identifier: namespace of generated code
  std::string source_file;  ///< as given on the command line
  DescriptionFormat format = DescriptionFormat::kMdhYaml;
  std::vector<JointDescription> joints;  ///< one per tree.bodies entry
  RigidBodyTree tree;
  DriveChain drives;
  FrictionOptions friction;
  bool rotor_inertia = true;
  int payload_body = -1;  ///< index into tree.bodies, -1 when not given
  /// A-priori values of standard parameters (YAML `known`, or URDF inertials), by
  /// tree.params index.
  std::vector<std::optional<double>> known_values;
  /// Per tree.bodies entry, its region from the geometry (URDF shapes, YAML `region:`, or
  /// guessed; nullopt for a body with a-priori inertial values and no shapes or `region:`).
  std::vector<std::optional<BodyRegion>> body_regions;
  /// What the loader snapped or assumed, in file order (see DescriptionNote).
  std::vector<DescriptionNote> notes;

  int dof() const { return tree.dof; }
  /// Index of the standard parameter with this name, or -1.
  int param_index(std::string_view param_name) const;
  std::vector<std::string> param_names() const;
};

/// Fills tree.params from the bodies and the friction/rotor options: per body j (1-based
/// suffix), XXj XYj XZj YYj YZj ZZj MXj MYj MZj Mj, then for moving joints Iaj, Fvj, Fcj (or
/// Fvpj Fvnj Fcpj Fcnj when asymmetric), OFFj as enabled, then Iamj Fvmj Fcmj when motor j
/// drives several joints (drives.motor_from_joint has off-diagonal entries in row j; fills
/// tree.coupled_motors). Resets known_values to all-unknown.
void build_standard_parameters(RobotModel& model);

/// Throws InputError at `where` unless `name` can be a C++ namespace for generated code:
/// an identifier, not a keyword, not "internal" or "gen".
void check_robot_name(const std::string& name, const SourceLocation& where);

/// The name of the generated code for a description's robot `name`: `name` itself when
/// check_robot_name accepts it, otherwise an identifier made from it (letters lowercased, every
/// run of other characters one '_', "robot_" before a leading digit, "_robot" after a reserved
/// word: "GEN3-6DOF_NO-VISION" -> "gen3_6dof_no_vision"), with a note at `where` in `notes`.
/// Vendors name robots freely; only an explicit --name must be an identifier already.
std::string robot_identifier(const std::string& name, const SourceLocation& where,
                             std::vector<DescriptionNote>& notes);

/// Standard parameters of a body from its mass, centre of mass c (in the body frame) and inertia
/// about the centre of mass expressed in a frame rotated by R_inertial (row-major) from the body
/// frame: rotation then the parallel-axis theorem, J_O = R I_c R^T + m (|c|^2 1 - c c^T).
/// Returns XX XY XZ YY YZ ZZ MX MY MZ M.
std::array<double, 10> standard_from_inertial(double mass, const std::array<double, 3>& com,
                                              const std::array<double, 9>& R_inertial,
                                              const std::array<double, 6>& I_com);

}  // namespace modelgen
