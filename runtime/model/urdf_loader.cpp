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
#include <map>
#include <optional>
#include <set>
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
#include "modelgen/model/rigid_body_tree.hpp"
#include "modelgen/model/robot_model.hpp"
#include "runtime/model/body_regions.hpp"
#include "runtime/model/urdf_structure.hpp"
#include "runtime/model/urdf_tree_builder.hpp"

namespace modelgen {

namespace {

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

// urdfdom's model of `text`; a file it rejects is reported with its first message, at the
// line of the first link or joint its messages name.
urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& path, const std::string& text,
                                                 const UrdfStructure& structure) {
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
  return urdf;
}

// --name (which must be an identifier), else the <robot> name made one (with a note).
std::string robot_name(const std::string& path, const UrdfStructure& structure,
                       const LoadOptions& options, std::vector<DescriptionNote>& notes) {
  if (!options.name.empty()) {
    check_robot_name(options.name, {path});
    return options.name;
  }
  return robot_identifier(structure.robot_name, {path, structure.robot_line, 0}, notes);
}

// --base, else the first link without a parent joint.
int base_link(const std::string& path, const UrdfStructure& structure, const LoadOptions& options) {
  int base = -1;
  if (!options.base_link.empty()) {
    base = link_option(path, structure, options.base_link, "base", "--base");
  } else {
    for (std::size_t l = 0; l < structure.links.size() && base == -1; ++l) {
      if (structure.parent_joint[l] == -1) base = static_cast<int>(l);
    }
  }
  return base;
}

// With --tip, the joints on the way from `base` to the tip (the only ones kept); else nullopt.
std::optional<std::set<int>> joints_to_tip(const std::string& path, const UrdfStructure& structure,
                                           const LoadOptions& options, int base) {
  std::optional<std::set<int>> path_joints;
  if (options.tip_link.empty()) return path_joints;
  const int tip = link_option(path, structure, options.tip_link, "tip", "--tip");
  path_joints.emplace();
  int link = tip;
  while (link != base) {
    const int joint = structure.parent_joint[link];
    if (joint == -1) {
      throw InputError({path}, "no path from base link '" + structure.links[base].name +
                                   "' to tip link '" + options.tip_link +
                                   "': the tip is not below the base");
    }
    path_joints->insert(joint);
    link = structure.link_index.at(structure.joints[joint].parent);
  }
  return path_joints;
}

// The drive chain (none in URDF) and the standard parameters, with the inertials the URDF
// gives as known values.
void set_parameters(const std::vector<std::optional<std::array<double, 10>>>& inertials,
                    RobotModel& model) {
  // No drive ratios in URDF: motor and joint sides coincide.
  model.drives.motor_from_joint = Eigen::MatrixXd::Identity(model.tree.dof, model.tree.dof);
  model.drives.torque_constant = Eigen::VectorXd::Zero(model.tree.dof);
  model.drives.joint_offset = Eigen::VectorXd::Zero(model.tree.dof);
  build_standard_parameters(model);
  for (std::size_t k = 0; k < model.tree.params.size(); ++k) {
    const StandardParam& param = model.tree.params[k];
    const int slot = inertial_slot(param.kind);
    const auto& inertial = inertials[param.body];
    if (slot >= 0 && inertial) model.known_values[k] = (*inertial)[slot];
  }
}

}  // namespace

RobotModel load_urdf(const std::string& path, const std::string& text, const LoadOptions& options) {
  const UrdfStructure structure = check_urdf_structure(path, text);
  const urdf::ModelInterfaceSharedPtr urdf = parse_with_urdfdom(path, text, structure);

  RobotModel model;
  model.format = DescriptionFormat::kUrdf;
  model.source_file = path;
  model.name = robot_name(path, structure, options, model.notes);

  const int base = base_link(path, structure, options);
  const std::string& base_name = structure.links[base].name;
  const std::optional<std::set<int>> path_joints = joints_to_tip(path, structure, options, base);

  TreeBuilder builder(path, structure, *urdf, path_joints ? &*path_joints : nullptr, model);
  model.tree.angle_precision = options.angle_tolerance;
  builder.build(base, options.angle_tolerance, options.mimic_as_joint);
  model.notes.insert(model.notes.end(), structure.notes.begin(), structure.notes.end());
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
  set_parameters(builder.inertials(), model);
  // Each body's region: the ellipsoid around its shapes' box; without shapes (meshes only,
  // or none) and without an <inertial> the guess from the segments to its child joints
  // (body_regions.hpp). A body with an <inertial> keeps that as its a-priori model: a guess
  // would only contradict the vendor (the UR5's wrist inertias reach 0.3 m from the joint).
  for (const auto& box : builder.shape_boxes()) {
    model.body_regions.push_back(box ? std::optional(region_around_box(box->first, box->second))
                                     : std::nullopt);
  }
  guess_missing_regions(model, builder.segment_ends());
  validate(model.tree);
  return model;
}

}  // namespace modelgen
