// Renders a RobotModel as aligned text tables for `modelgen describe`.

#include "generator/describe.hpp"

#include <cmath>
#include <sstream>

#include "modelgen/model/number_text.hpp"

namespace modelgen::gen {

std::string format_number(double value) {
  return value == 0 ? "0" : shortest_text(value);  // also folds -0
}

namespace {

// A table whose columns are as wide as their widest cell.
class Table {
 public:
  explicit Table(std::vector<std::string> header) { rows_.push_back(std::move(header)); }
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  void print(std::ostream& out, const std::string& indent) const {
    std::vector<std::size_t> width;
    for (const auto& row : rows_) {
      if (width.size() < row.size()) width.resize(row.size(), 0);
      for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    }
    for (const auto& row : rows_) {
      std::string line = indent;
      for (std::size_t c = 0; c < row.size(); ++c) {
        line += row[c];
        if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
      }
      out << line << "\n";
    }
  }

 private:
  std::vector<std::vector<std::string>> rows_;
};

const char* type_name(JointType type) {
  switch (type) {
    case JointType::kRevolute: return "revolute";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kFixed: return "fixed";
  }
  return "?";
}

std::string optional_number(const std::optional<double>& v) {
  return v ? format_number(*v) : "-";
}

std::string limits_text(const JointLimits& limits) {
  if (!limits.q_lower) return limits.continuous ? "continuous" : "-";
  std::string out = "[";
  out += format_number(*limits.q_lower);
  out += ", ";
  out += format_number(*limits.q_upper);
  return out + "]";
}

std::string vector_text(const double* v, int n) {
  std::string out = "[";
  for (int i = 0; i < n; ++i) out += (i ? ", " : "") + format_number(v[i]);
  return out + "]";
}

// Roll-pitch-yaw (URDF convention R = Rz(yaw) Ry(pitch) Rx(roll)) of a row-major rotation.
std::array<double, 3> rpy(const std::array<double, 9>& R) {
  const double pitch = std::atan2(-R[6], std::hypot(R[0], R[3]));
  const double roll = std::atan2(R[7], R[8]);
  const double yaw = std::atan2(R[3], R[0]);
  auto clean = [](double a) { return std::abs(a) < 1e-15 ? 0.0 : a; };
  return {clean(roll), clean(pitch), clean(yaw)};
}

void print_matrix(std::ostream& out, const Eigen::MatrixXd& m, const std::string& indent) {
  Table table({});
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    std::vector<std::string> row;
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(format_number(m(r, c)));
    table.add(row);
  }
  std::ostringstream body;
  table.print(body, indent);
  out << body.str().substr(body.str().find('\n') + 1);  // drop the empty header line
}

void print_summary(std::ostream& out, const RobotModel& model) {
  const RigidBodyTree& tree = model.tree;
  const bool mdh = model.format == DescriptionFormat::kMdhYaml;
  out << "robot " << model.name << " (" << (mdh ? "modified DH" : "URDF") << ", "
      << model.source_file << ")\n";
  out << "  " << tree.dof << " moving joints, " << tree.bodies.size() << " bodies, gravity "
      << vector_text(tree.gravity.data(), 3) << " m/s^2\n\n";
}

void print_mdh_joints(std::ostream& out, const RobotModel& model) {
  const RigidBodyTree& tree = model.tree;
  out << "joints (Khalil-Kleinfinger modified DH: Rot_x(alpha) Trans_x(d) Rot_z(theta) "
         "Trans_z(r))\n";
  Table table(
      {"j", "name", "type", "ant", "alpha", "d", "theta", "r", "q limits", "dq max", "ddq max"});
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    const JointDescription& joint = model.joints[j];
    const MdhParameters& p = *joint.mdh;
    table.add({std::to_string(j + 1), body.name, type_name(body.type),
               std::to_string(body.parent + 1), p.alpha.text, format_number(p.d), p.theta.text,
               format_number(p.r), limits_text(joint.limits), optional_number(joint.limits.dq),
               optional_number(joint.limits.ddq)});
  }
  table.print(out, "  ");
}

void print_urdf_bodies(std::ostream& out, const RobotModel& model) {
  const RigidBodyTree& tree = model.tree;
  out << "bodies (frame j = parent frame * origin(xyz, rpy) * joint motion along axis)\n";
  Table table({"j", "link", "joint", "type", "parent", "xyz", "rpy", "axis", "q limits", "dq max",
               "effort max"});
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    const JointDescription& joint = model.joints[j];
    const auto angles = rpy(body.fixed.rotation);
    table.add({std::to_string(j + 1), body.name, joint.name, type_name(body.type),
               body.parent < 0 ? joint.parent_link : tree.bodies[body.parent].name,
               vector_text(body.fixed.translation.data(), 3), vector_text(angles.data(), 3),
               vector_text(body.axis.data(), 3), limits_text(joint.limits),
               optional_number(joint.limits.dq), optional_number(joint.limits.effort)});
  }
  table.print(out, "  ");
}

void print_notes(std::ostream& out, const RobotModel& model) {
  // Warnings (likely unit slips, mimic joints) first, then what the loader changed.
  for (const bool warnings : {true, false}) {
    bool first = true;
    for (const DescriptionNote& note : model.notes) {
      if (note.warning != warnings) continue;
      if (first) {
        out << (warnings ? "\nwarnings (values to check; the tables above show them as read)\n"
                         : "\nangles taken as exact quarter turns (the table above shows the "
                           "values used)\n");
        first = false;
      }
      out << "  line " << note.where.line << ": " << note.message << "\n";
    }
  }
}

void print_drive_chain(std::ostream& out, const RobotModel& model) {
  out << "\ndrive chain\n";
  const DriveChain& drives = model.drives;
  out << "  gear ratio: "
      << (drives.ratio.empty() ? std::string("not given (1)")
                               : vector_text(drives.ratio.data(), static_cast<int>(drives.ratio.size())))
      << "\n";
  if (drives.has_coupling()) {
    out << "  coupling as written (" << drives.coupling_form
        << (drives.coupling_form == "joint_from_motor" ? ", Swevers eq. 9: q_joint = V q_motor/ratio"
                                                       : ", Gautier eq. 25: dq_motor = N dq_joint")
        << ") on joints";
    for (int i : drives.coupled_joints) out << " " << i + 1;
    out << ":\n";
    print_matrix(out, drives.coupling_as_written, "    ");
  } else {
    out << "  coupling: none\n";
  }
  if (drives.motor_from_joint.size() > 0) {
    out << "  motor_from_joint K (dq_motor = K dq_joint, tau_joint = K^T tau_motor):\n";
    print_matrix(out, drives.motor_from_joint, "    ");
  }
  auto any_nonzero = [](const Eigen::VectorXd& v) { return (v.array() != 0).any(); };
  if (any_nonzero(drives.torque_constant)) {
    out << "  torque constant (N m/A, motor side): "
        << vector_text(drives.torque_constant.data(), static_cast<int>(drives.torque_constant.size()))
        << "\n";
  }
  if (any_nonzero(drives.joint_offset)) {
    out << "  joint offset (q = K^-1 q_motor + offset): "
        << vector_text(drives.joint_offset.data(), static_cast<int>(drives.joint_offset.size()))
        << "\n";
  }
}

void print_friction_and_payload(std::ostream& out, const RobotModel& model) {
  out << "  friction: " << (model.friction.viscous ? "viscous " : "")
      << (model.friction.coulomb ? "Coulomb " : "") << (model.friction.offset ? "offset " : "")
      << (model.friction.asymmetric ? "(asymmetric, Bona & Curatella eq. 2)" : "(symmetric)")
      << "; drive inertia: " << (model.rotor_inertia ? "yes" : "no") << "\n";
  if (model.payload_body >= 0) {
    out << "  payload carried by link " << model.payload_body + 1 << " ("
        << model.tree.bodies[model.payload_body].name << ")\n";
  }
}

void print_parameters(std::ostream& out, const RobotModel& model) {
  const RigidBodyTree& tree = model.tree;
  out << "\nstandard parameters (" << tree.params.size() << ", Gautier & Briot eq. 3)\n";
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    std::string line;
    for (const StandardParam& p : tree.params) {
      if (p.body == static_cast<int>(j)) line += " " + p.name;
    }
    out << "  " << tree.bodies[j].name << ":" << line << "\n";
  }
  bool any_known = false;
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    if (!model.known_values[k]) continue;
    if (!any_known) out << "\na-priori values\n";
    any_known = true;
    out << "  " << tree.params[k].name << " = " << format_number(*model.known_values[k]) << "\n";
  }
}

}  // namespace

std::string describe(const RobotModel& model) {
  std::ostringstream out;
  print_summary(out, model);
  if (model.format == DescriptionFormat::kMdhYaml) {
    print_mdh_joints(out, model);
  } else {
    print_urdf_bodies(out, model);
  }
  print_notes(out, model);
  print_drive_chain(out, model);
  print_friction_and_payload(out, model);
  print_parameters(out, model);
  return out.str();
}

}  // namespace modelgen::gen
