// The walk of the URDF loader over the kinematic tree: a body per moving joint, fixed joints
// folded into the transforms of the moving joints below them and their links' inertia merged
// into the nearest moving ancestor; rounded quarter turns and near-axis axes snapped, with notes.

#include "runtime/model/urdf_tree_builder.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "runtime/model/angle_snapping.hpp"

namespace modelgen {

namespace {

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  q.normalize();
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = q.toRotationMatrix();
  transform.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return transform;
}

// URDFs write quarter turns with a rounded pi ("1.5707963267949"), which leaves entries such as
// 4.9e-12 where the robot has an exact zero. A rotation whose entries are all within 1e-9 of
// 0 or +-1 is such a signed permutation and is snapped to it exactly (still orthonormal), so the
// symbolic models fold those zeros and ones away; likewise translations below 1e-12 m.
Frame to_frame(const Eigen::Isometry3d& transform) {
  Frame frame;
  bool quarter_turn = true;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double entry = transform.linear()(i, j);
      frame.rotation[3 * i + j] = entry;
      const double nearest = std::round(entry);
      if (std::abs(entry - nearest) > 1e-9) quarter_turn = false;
    }
    const double t = transform.translation()(i);
    frame.translation[i] = std::abs(t) < 1e-12 ? 0.0 : t;
  }
  if (quarter_turn) {
    for (double& entry : frame.rotation) entry = std::round(entry) + 0.0;  // + 0.0: no -0
  }
  return frame;
}

}  // namespace

// `tolerance`: LoadOptions::angle_tolerance, for snapping rounded quarter turns.
void TreeBuilder::build(int base_link, double tolerance, bool mimic_as_joint) {
  tolerance_ = tolerance;
  mimic_as_joint_ = mimic_as_joint;
  // Depth first in file order, with a stack of its own: a chain of thousands of fixed links
  // would overflow the call stack if this recursed.
  push_children(base_link, -1, Eigen::Isometry3d::Identity());
  while (!pending_.empty()) {
    const Pending next = pending_.back();
    pending_.pop_back();
    visit(next.joint, next.body, next.body_from_link);
  }
}

const urdf::Joint& TreeBuilder::joint(const JointEntry& entry) const {
  const urdf::JointConstSharedPtr joint = urdf_.getJoint(entry.name);
  if (!joint) throw std::logic_error("urdfdom lost joint '" + entry.name + "'");
  return *joint;
}

// The transform of an <origin>: urdfdom's, or when its rpy holds rounded quarter turns (more
// than kSilentSnap off, so files that write pi with 15 digits keep their exact old values)
// the one of the snapped angles, with a note per snapped angle.
Eigen::Isometry3d TreeBuilder::origin_transform(const urdf::Pose& pose, const OriginEntry& origin,
                                                const std::string& owner) {
  std::array<double, 3> rpy = origin.rpy;
  bool noteworthy = false;
  std::vector<DescriptionNote> notes;
  static const char* const kNames[] = {"roll", "pitch", "yaw"};
  for (int i = 0; i < 3; ++i) {
    const auto quarters = nearest_quarter_turn(rpy[i], tolerance_);
    if (!quarters) continue;
    const double exact = static_cast<double>(*quarters) * (std::numbers::pi / 2);
    if (std::abs(rpy[i] - exact) > kSilentSnap) {
      noteworthy = true;
      notes.push_back({{path_, origin.line, 0},
                       snap_note(owner + " rpy " + kNames[i], rpy[i], *quarters, tolerance_)});
    }
    rpy[i] = exact;
  }
  if (!noteworthy) return to_isometry(pose);
  for (DescriptionNote& note : notes) model_.notes.push_back(std::move(note));
  urdf::Pose snapped = pose;
  snapped.rotation.setFromRPY(rpy[0], rpy[1], rpy[2]);
  return to_isometry(snapped);
}

// The unit joint axis; components within the tolerance of 0 become 0 (an axis 2e-5 rad off
// z is z), with a note when that moves it by more than kSilentSnap.
std::array<double, 3> TreeBuilder::joint_axis(const urdf::Joint& joint, const JointEntry& entry) {
  const Eigen::Vector3d written =
      Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
  Eigen::Vector3d axis = written;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(axis[i]) <= tolerance_) axis[i] = 0;
  }
  axis.normalize();
  const double off = std::atan2(written.cross(axis).norm(), written.dot(axis));
  if (!(off > kSilentSnap)) return {written.x(), written.y(), written.z()};
  char text[64];
  std::snprintf(text, sizeof text, "%.2g", off);
  const auto& a = *entry.axis;
  model_.notes.push_back({{path_, entry.axis_line, 0},
                          "joint '" + entry.name + "': axis xyz " + shortest_text(a[0]) + " " +
                              shortest_text(a[1]) + " " + shortest_text(a[2]) + " taken as " +
                              shortest_text(axis.x() + 0.0) + " " + shortest_text(axis.y() + 0.0) +
                              " " + shortest_text(axis.z() + 0.0) + " (" + text +
                              " rad off, within --angle-tolerance " + shortest_text(tolerance_) +
                              "; give --angle-tolerance 0 to take it as written)"});
  return {axis.x(), axis.y(), axis.z()};
}

// Adds the link's inertial, the link frame being at `body_from_link` in the body frame.
void TreeBuilder::add_inertial(const std::string& link_name, int body,
                               const Eigen::Isometry3d& body_from_link) {
  const urdf::LinkConstSharedPtr link = urdf_.getLink(link_name);
  if (!link) throw std::logic_error("urdfdom lost link '" + link_name + "'");
  if (!link->inertial) return;
  const urdf::Inertial& in = *link->inertial;
  const LinkEntry& entry = structure_.links[structure_.link_index.at(link_name)];
  const Eigen::Isometry3d body_from_inertial =
      body_from_link * origin_transform(in.origin, entry.inertial_origin,
                                        "link '" + link_name + "': inertial origin");
  const Frame frame = to_frame(body_from_inertial);
  const std::array<double, 10> values = standard_from_inertial(
      in.mass, frame.translation, frame.rotation, {in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz});
  auto& sum = inertials_[body];
  if (!sum) sum.emplace();
  // All ten are linear in the mass distribution, so merged links simply add up.
  for (std::size_t k = 0; k < values.size(); ++k) (*sum)[k] += values[k];
}

// Widens the body's box by the link's collision shapes (its visual ones when it has none):
// each shape's own bounding box, its eight corners taken to the body frame.
void TreeBuilder::add_shapes(const std::string& link_name, int body,
                             const Eigen::Isometry3d& body_from_link) {
  const urdf::LinkConstSharedPtr link = urdf_.getLink(link_name);
  if (!link) throw std::logic_error("urdfdom lost link '" + link_name + "'");
  std::vector<std::pair<urdf::GeometrySharedPtr, urdf::Pose>> shapes;
  for (const auto& c : link->collision_array)
    if (c && c->geometry) shapes.emplace_back(c->geometry, c->origin);
  if (shapes.empty()) {
    for (const auto& v : link->visual_array)
      if (v && v->geometry) shapes.emplace_back(v->geometry, v->origin);
  }
  for (const auto& [geometry, pose] : shapes) {
    Eigen::Vector3d half;
    if (const auto box = std::dynamic_pointer_cast<urdf::Box>(geometry)) {
      half = 0.5 * Eigen::Vector3d(box->dim.x, box->dim.y, box->dim.z);
    } else if (const auto cylinder = std::dynamic_pointer_cast<urdf::Cylinder>(geometry)) {
      half = Eigen::Vector3d(cylinder->radius, cylinder->radius, 0.5 * cylinder->length);
    } else if (const auto sphere = std::dynamic_pointer_cast<urdf::Sphere>(geometry)) {
      half = Eigen::Vector3d::Constant(sphere->radius);
    } else {
      continue;  // a mesh: no size without its file
    }
    Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
    Eigen::Isometry3d link_from_shape = Eigen::Isometry3d::Identity();
    link_from_shape.linear() = q.normalized().toRotationMatrix();
    link_from_shape.translation() =
        Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
    auto& box = boxes_[static_cast<std::size_t>(body)];
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d local((corner & 1 ? 1 : -1) * half.x(),
                                  (corner & 2 ? 1 : -1) * half.y(),
                                  (corner & 4 ? 1 : -1) * half.z());
      const Eigen::Vector3d x = body_from_link * (link_from_shape * local);
      if (!box) box.emplace(x, x);
      box->first = box->first.cwiseMin(x);
      box->second = box->second.cwiseMax(x);
    }
  }
}

// Queues the joints below `link`, so that they are visited in file order.
void TreeBuilder::push_children(int link, int body, const Eigen::Isometry3d& body_from_link) {
  const std::vector<int>& children = structure_.child_joints[link];
  for (auto j = children.rbegin(); j != children.rend(); ++j) {
    if (kept_joints_ != nullptr && !kept_joints_->count(*j)) continue;
    pending_.push_back({*j, body, body_from_link});
  }
}

// The joint as the model describes it: name, parent link, line and the limits URDF gives.
JointDescription TreeBuilder::joint_description(const urdf::Joint& urdf_joint,
                                                const JointEntry& entry) const {
  JointDescription description;
  description.name = entry.name;
  description.parent_link = entry.parent;
  description.where = {path_, entry.line, 0};
  description.limits.continuous = entry.type == "continuous";
  if (urdf_joint.limits) {
    const urdf::JointLimits& limits = *urdf_joint.limits;
    if (entry.type != "continuous") {
      if (entry.has_lower) description.limits.q_lower = limits.lower;
      if (entry.has_upper) description.limits.q_upper = limits.upper;
    }
    // URDF makes velocity and effort mandatory, so files write 0 where the value is
    // unknown (the KR150 URDF does); only a positive value limits anything.
    if (limits.velocity > 0) description.limits.dq = limits.velocity;
    if (limits.effort > 0) description.limits.effort = limits.effort;
  }
  return description;
}

// A follower moves with its leader (q = multiplier * q_leader + offset): as a joint of its own
// it is a degree of freedom the robot does not have, and its regressor columns are excited by
// motions the robot cannot make. modelgen has no such constraint (issue 29), so a follower in
// the modelled part is refused unless the user asked for it as a joint (--mimic-as-joint).
void TreeBuilder::note_mimic(const JointEntry& entry) {
  const std::string follows =
      "joint '" + entry.name + "' mimics joint '" + entry.mimic_leader + "'";
  if (!mimic_as_joint_) {
    throw InputError({path_, entry.mimic_line, 0},
                     follows +
                         " (moves with it), but modelgen has no mimic constraint and would "
                         "model it as a degree of freedom the robot does not have; leave the "
                         "part it moves out with --tip LINK, make '" +
                         entry.name +
                         "' fixed in a copy of the file, or keep it as an independent joint "
                         "with --mimic-as-joint (docs/commands/modelgen.md, Mimic joints)");
  }
  model_.notes.push_back({{path_, entry.mimic_line, 0},
                          follows + " but is modelled as an independent degree of freedom, as "
                                    "--mimic-as-joint asks",
                          true});
}

void TreeBuilder::visit(int j, int body, const Eigen::Isometry3d& body_from_link) {
  const JointEntry& entry = structure_.joints[j];
  const urdf::Joint& urdf_joint = joint(entry);
  const int child = structure_.link_index.at(entry.child);
  // A URDF joint frame is its child link's frame; at q = 0 it sits at <origin>.
  const Eigen::Isometry3d body_from_child =
      body_from_link * origin_transform(urdf_joint.parent_to_joint_origin_transform, entry.origin,
                                        "joint '" + entry.name + "': origin");
  if (body >= 0) ends_[static_cast<std::size_t>(body)].push_back(body_from_child.translation());
  if (!is_moving(entry.type)) {
    // Mass fixed to the base never moves, so it has no effect on the dynamics.
    if (body >= 0) {
      add_inertial(entry.child, body, body_from_child);
      add_shapes(entry.child, body, body_from_child);
    }
    push_children(child, body, body_from_child);
    return;
  }
  if (!entry.mimic_leader.empty()) note_mimic(entry);
  if (model_.tree.dof == kMaxMovingJoints) {
    throw InputError({path_, entry.line, 0},
                     "joint '" + entry.name + "' is moving joint " +
                         std::to_string(kMaxMovingJoints + 1) + "; modelgen models at most " +
                         std::to_string(kMaxMovingJoints) +
                         " moving joints (generation time grows with their cube; README, "
                         "Limits); choose a part of the tree with --base and --tip");
  }
  Body made;
  made.name = entry.child;
  made.parent = body;
  made.type = entry.type == "prismatic" ? JointType::kPrismatic : JointType::kRevolute;
  made.dof_index = model_.tree.dof++;
  made.fixed = to_frame(body_from_child);
  made.axis = joint_axis(urdf_joint, entry);

  const int index = static_cast<int>(model_.tree.bodies.size());
  model_.tree.bodies.push_back(std::move(made));
  model_.joints.push_back(joint_description(urdf_joint, entry));
  inertials_.emplace_back();
  boxes_.emplace_back();
  ends_.emplace_back();
  add_inertial(entry.child, index, Eigen::Isometry3d::Identity());
  add_shapes(entry.child, index, Eigen::Isometry3d::Identity());
  push_children(child, index, Eigen::Isometry3d::Identity());
}

}  // namespace modelgen
