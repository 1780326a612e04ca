// Loads a URDF into a RobotModel. A TinyXML2 pass (urdf_structure.cpp) checks structure and
// numbers first, because urdfdom forgets line numbers and reports problems only on the console;
// urdfdom then supplies the values. Each moving joint becomes a body; fixed joints fold into the transforms of the
// moving joints below them and merge their link's inertia into the nearest moving ancestor.

#include "runtime/model/urdf_loader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <exception>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/robot_model.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "runtime/model/angle_snapping.hpp"
#include "runtime/model/urdf_structure.hpp"

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

// Position of an inertial parameter in standard_from_inertial's result, -1 for drive ones.
int inertial_slot(ParamKind kind) {
  switch (kind) {
    case ParamKind::kXX:
      return 0;
    case ParamKind::kXY:
      return 1;
    case ParamKind::kXZ:
      return 2;
    case ParamKind::kYY:
      return 3;
    case ParamKind::kYZ:
      return 4;
    case ParamKind::kZZ:
      return 5;
    case ParamKind::kMX:
      return 6;
    case ParamKind::kMY:
      return 7;
    case ParamKind::kMZ:
      return 8;
    case ParamKind::kM:
      return 9;
    default:
      return -1;
  }
}

// Walks the kinematic tree depth first from the base, making a body per moving joint.
class TreeBuilder {
 public:
  TreeBuilder(const std::string& path, const UrdfStructure& structure,
              const urdf::ModelInterface& urdf, const std::set<int>* kept_joints, RobotModel& model)
      : path_(path), structure_(structure), urdf_(urdf), kept_joints_(kept_joints), model_(model) {}

  // `tolerance`: LoadOptions::angle_tolerance, for snapping rounded quarter turns.
  void build(int base_link, double tolerance) {
    tolerance_ = tolerance;
    // Depth first in file order, with a stack of its own: a chain of thousands of fixed links
    // would overflow the call stack if this recursed.
    push_children(base_link, -1, Eigen::Isometry3d::Identity());
    while (!pending_.empty()) {
      const Pending next = pending_.back();
      pending_.pop_back();
      visit(next.joint, next.body, next.body_from_link);
    }
  }

  // The summed inertial parameters per body; nullopt for bodies none of whose links has an
  // <inertial>, so an absent inertial stays unknown rather than becoming zero.
  const std::vector<std::optional<std::array<double, 10>>>& inertials() const { return inertials_; }

 private:
  const urdf::Joint& joint(const JointEntry& entry) const {
    const urdf::JointConstSharedPtr joint = urdf_.getJoint(entry.name);
    if (!joint) throw std::logic_error("urdfdom lost joint '" + entry.name + "'");
    return *joint;
  }

  // The transform of an <origin>: urdfdom's, or when its rpy holds rounded quarter turns (more
  // than kSilentSnap off, so files that write pi with 15 digits keep their exact old values)
  // the one of the snapped angles, with a note per snapped angle.
  Eigen::Isometry3d origin_transform(const urdf::Pose& pose, const OriginEntry& origin,
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
  std::array<double, 3> joint_axis(const urdf::Joint& joint, const JointEntry& entry) {
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
    model_.notes.push_back(
        {{path_, entry.axis_line, 0},
         "joint '" + entry.name + "': axis xyz " + shortest_text(a[0]) + " " + shortest_text(a[1]) +
             " " + shortest_text(a[2]) + " taken as " + shortest_text(axis.x() + 0.0) + " " +
             shortest_text(axis.y() + 0.0) + " " + shortest_text(axis.z() + 0.0) + " (" + text +
             " rad off, within --angle-tolerance " + shortest_text(tolerance_) +
             "; give --angle-tolerance 0 to take it as written)"});
    return {axis.x(), axis.y(), axis.z()};
  }

  // Adds the link's inertial, the link frame being at `body_from_link` in the body frame.
  void add_inertial(const std::string& link_name, int body,
                    const Eigen::Isometry3d& body_from_link) {
    const urdf::LinkConstSharedPtr link = urdf_.getLink(link_name);
    if (!link) throw std::logic_error("urdfdom lost link '" + link_name + "'");
    if (!link->inertial) return;
    const urdf::Inertial& in = *link->inertial;
    const LinkEntry& entry = structure_.links[structure_.link_index.at(link_name)];
    const Eigen::Isometry3d body_from_inertial =
        body_from_link *
        origin_transform(in.origin, entry.inertial_origin, "link '" + link_name + "': inertial origin");
    const Frame frame = to_frame(body_from_inertial);
    const std::array<double, 10> values =
        standard_from_inertial(in.mass, frame.translation, frame.rotation,
                               {in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz});
    auto& sum = inertials_[body];
    if (!sum) sum.emplace();
    // All ten are linear in the mass distribution, so merged links simply add up.
    for (std::size_t k = 0; k < values.size(); ++k) (*sum)[k] += values[k];
  }

  // A joint still to visit: below `body`, its parent link at `body_from_link` in that body.
  struct Pending {
    int joint;
    int body;
    Eigen::Isometry3d body_from_link;
  };

  // Queues the joints below `link`, so that they are visited in file order.
  void push_children(int link, int body, const Eigen::Isometry3d& body_from_link) {
    const std::vector<int>& children = structure_.child_joints[link];
    for (auto j = children.rbegin(); j != children.rend(); ++j) {
      if (kept_joints_ != nullptr && !kept_joints_->count(*j)) continue;
      pending_.push_back({*j, body, body_from_link});
    }
  }

  void visit(int j, int body, const Eigen::Isometry3d& body_from_link) {
    {
      const JointEntry& entry = structure_.joints[j];
      const urdf::Joint& urdf_joint = joint(entry);
      const int child = structure_.link_index.at(entry.child);
      // A URDF joint frame is its child link's frame; at q = 0 it sits at <origin>.
      const Eigen::Isometry3d body_from_child =
          body_from_link * origin_transform(urdf_joint.parent_to_joint_origin_transform,
                                            entry.origin, "joint '" + entry.name + "': origin");
      if (!is_moving(entry.type)) {
        // Mass fixed to the base never moves, so it has no effect on the dynamics.
        if (body >= 0) add_inertial(entry.child, body, body_from_child);
        push_children(child, body, body_from_child);
        return;
      }
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

      JointDescription description;
      description.name = entry.name;
      description.parent_link = entry.parent;
      description.where = {path_, entry.line, 0};
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

      const int index = static_cast<int>(model_.tree.bodies.size());
      model_.tree.bodies.push_back(std::move(made));
      model_.joints.push_back(std::move(description));
      inertials_.emplace_back();
      add_inertial(entry.child, index, Eigen::Isometry3d::Identity());
      push_children(child, index, Eigen::Isometry3d::Identity());
    }
  }

  const std::string& path_;
  const UrdfStructure& structure_;
  const urdf::ModelInterface& urdf_;
  const std::set<int>* kept_joints_;
  RobotModel& model_;
  std::vector<std::optional<std::array<double, 10>>> inertials_;
  std::vector<Pending> pending_;
  double tolerance_ = 0;
};

// urdfdom reports why it rejects a file through console_bridge, on the console and without a
// line ("Could not parse collision element for Link [arm]"). Caught here, so the message
// becomes part of the error, placed at the line of the link or joint it names.
class UrdfdomMessages : public console_bridge::OutputHandler {
 public:
  UrdfdomMessages() {
    previous_ = console_bridge::getOutputHandler();
    console_bridge::useOutputHandler(this);
  }
  ~UrdfdomMessages() override { console_bridge::useOutputHandler(previous_); }
  UrdfdomMessages(const UrdfdomMessages&) = delete;
  UrdfdomMessages& operator=(const UrdfdomMessages&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors_.push_back(text);
  }
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  console_bridge::OutputHandler* previous_ = nullptr;
  std::vector<std::string> errors_;
};

// The line of the first link or joint a urdfdom message names in brackets ("[arm]"), 0 if none.
int line_named_in(const std::string& message, const UrdfStructure& structure) {
  for (std::size_t open = message.find('['); open != std::string::npos;
       open = message.find('[', open + 1)) {
    const std::size_t close = message.find(']', open);
    if (close == std::string::npos) break;
    const std::string name = message.substr(open + 1, close - open - 1);
    if (const auto link = structure.link_index.find(name); link != structure.link_index.end()) {
      return structure.links[link->second].line;
    }
    for (const JointEntry& joint : structure.joints) {
      if (joint.name == name) return joint.line;
    }
  }
  return 0;
}

int link_option(const std::string& path, const UrdfStructure& structure, const std::string& name,
                const char* role, const char* option) {
  const auto it = structure.link_index.find(name);
  if (it == structure.link_index.end()) {
    std::vector<std::string> names;
    for (const LinkEntry& link : structure.links) names.push_back(link.name);
    throw InputError({path}, std::string(role) + " link '" + name + "' (" + option +
                                 ") is not a link of this URDF" + did_you_mean(name, names));
  }
  return it->second;
}

}  // namespace

RobotModel load_urdf(const std::string& path, const std::string& text, const LoadOptions& options) {
  const UrdfStructure structure = check_urdf_structure(path, text);

  urdf::ModelInterfaceSharedPtr urdf;
  std::vector<std::string> urdfdom_errors;
  try {
    const UrdfdomMessages messages;
    urdf = urdf::parseURDF(text);
    urdfdom_errors = messages.errors();
  } catch (const std::exception& e) {
    throw InputError({path}, std::string("urdfdom rejected the file: ") + e.what());
  }
  if (!urdf) {
    if (urdfdom_errors.empty()) {
      throw InputError({path}, "urdfdom rejected the file without saying why");
    }
    // Its first message is the cause; the rest name the enclosing elements ("Could not parse
    // joint element for joint [j1]"), which give the line.
    int line = 0;
    for (const std::string& message : urdfdom_errors) {
      if (line == 0) line = line_named_in(message, structure);
    }
    throw InputError({path, line, 0}, "urdfdom rejected the file: " + urdfdom_errors.front());
  }

  RobotModel model;
  model.format = DescriptionFormat::kUrdf;
  model.source_file = path;
  if (!options.name.empty()) {
    check_robot_name(options.name, {path});
    model.name = options.name;
  } else {
    try {
      check_robot_name(structure.robot_name, {path, structure.robot_line, 0});
    } catch (const InputError& e) {
      throw InputError(e.where(), e.message() + "; choose another name with --name");
    }
    model.name = structure.robot_name;
  }

  int base = -1;
  if (!options.base_link.empty()) {
    base = link_option(path, structure, options.base_link, "base", "--base");
  } else {
    for (std::size_t l = 0; l < structure.links.size() && base == -1; ++l) {
      if (structure.parent_joint[l] == -1) base = static_cast<int>(l);
    }
  }
  const std::string& base_name = structure.links[base].name;

  std::optional<std::set<int>> path_joints;
  if (!options.tip_link.empty()) {
    const int tip = link_option(path, structure, options.tip_link, "tip", "--tip");
    path_joints.emplace();
    int link = tip;
    while (link != base) {
      const int joint = structure.parent_joint[link];
      if (joint == -1) {
        throw InputError({path}, "no path from base link '" + base_name + "' to tip link '" +
                                     options.tip_link + "': the tip is not below the base");
      }
      path_joints->insert(joint);
      link = structure.link_index.at(structure.joints[joint].parent);
    }
  }

  TreeBuilder builder(path, structure, *urdf, path_joints ? &*path_joints : nullptr, model);
  model.tree.angle_precision = options.angle_tolerance;
  builder.build(base, options.angle_tolerance);
  std::stable_sort(model.notes.begin(), model.notes.end(),
                   [](const DescriptionNote& a, const DescriptionNote& b) {
                     return a.where.line < b.where.line;
                   });
  if (model.tree.dof == 0) {
    throw InputError({path}, "no moving joint below base link '" + base_name +
                                 (options.tip_link.empty()
                                      ? "'"
                                      : "' on the way to tip link '" + options.tip_link + "'") +
                                 "; nothing to identify");
  }

  // No drive ratios in URDF: motor and joint sides coincide.
  model.drives.motor_from_joint = Eigen::MatrixXd::Identity(model.tree.dof, model.tree.dof);
  model.drives.torque_constant = Eigen::VectorXd::Zero(model.tree.dof);
  model.drives.joint_offset = Eigen::VectorXd::Zero(model.tree.dof);
  build_standard_parameters(model);
  for (std::size_t k = 0; k < model.tree.params.size(); ++k) {
    const StandardParam& param = model.tree.params[k];
    const int slot = inertial_slot(param.kind);
    const auto& inertial = builder.inertials()[param.body];
    if (slot >= 0 && inertial) model.known_values[k] = (*inertial)[slot];
  }

  validate(model.tree);
  return model;
}

}  // namespace modelgen
