// Reads the YAML description (modified DH table, drive chain, friction options, a-priori
// values) with yaml-cpp, checking every key and value and reporting positions from yaml-cpp's
// marks (yaml_reader.hpp). Frame j from frame a(j): Rot_x(alpha) Trans_x(d) Rot_z(theta)
// Trans_z(r) (DESIGN.md). The drive chain and the a-priori values have files of their own
// (mdh_drive_chain.cpp, mdh_known_values.cpp).

#include "runtime/model/mdh_yaml_loader.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/number_text.hpp"
#include "runtime/model/angle_snapping.hpp"
#include "runtime/model/body_regions.hpp"
#include "runtime/model/magnitude_checks.hpp"
#include "runtime/model/mdh_drive_chain.hpp"
#include "runtime/model/mdh_known_values.hpp"
#include "runtime/model/mdh_region.hpp"
#include "runtime/model/yaml_reader.hpp"

namespace modelgen {

namespace {

Eigen::Matrix3d rot_x(const Angle& a) {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, a.cos(), -a.sin(), 0, a.sin(), a.cos();
  return R;
}

Eigen::Matrix3d rot_z(const Angle& a) {
  Eigen::Matrix3d R;
  R << a.cos(), -a.sin(), 0, a.sin(), a.cos(), 0, 0, 0, 1;
  return R;
}

// Rot_x(alpha) Trans_x(d) Rot_z(theta) Trans_z(r) as a Frame (Khalil & Kleinfinger).
Frame mdh_frame(const MdhParameters& mdh) {
  const Eigen::Matrix3d Rx = rot_x(mdh.alpha);
  const Eigen::Matrix3d R = Rx * rot_z(mdh.theta);
  const Eigen::Vector3d t = Eigen::Vector3d(mdh.d, 0, 0) + R * Eigen::Vector3d(0, 0, mdh.r);
  Frame f;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) f.rotation[3 * r + c] = R(r, c);
    f.translation[r] = t[r];
  }
  return f;
}

struct RawJoint {
  JointDescription description;
  JointType type = JointType::kRevolute;
  int antecedent = 0;  // 0 = base, 1-based link number otherwise
  bool has_ant = false;
  YAML::Node ant_node;
};

class MdhYamlLoader {
 public:
  MdhYamlLoader(const std::string& path, double angle_tolerance)
      : in_(path), angle_tolerance_(angle_tolerance) {}

  RobotModel load(const std::string& text) {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      throw InputError({in_.path(), e.mark.line + 1, e.mark.column + 1},
                       "YAML syntax error: " + e.msg);
    }
    if (!root || root.IsNull()) throw InputError({in_.path()}, "the file is empty");
    in_.check_keys(root,
                   {"name", "gravity", "joints", "drives", "friction", "rotor_inertia", "payload",
                    "known"},
                   "the robot description");
    model_.source_file = in_.path();
    model_.format = DescriptionFormat::kMdhYaml;
    model_.tree.angle_precision = angle_tolerance_;
    const YAML::Node name = in_.require(root, "name", "the robot description");
    model_.name = robot_identifier(in_.text(name, "name"), in_.at(name), model_.notes);
    if (root["gravity"]) {
      const auto g = in_.numbers(root["gravity"], "gravity", 3);
      for (int i = 0; i < 3; ++i) in_.within(root["gravity"][i], "gravity", g[i], kMaxLength, " m/s^2");
      model_.tree.gravity = {g[0], g[1], g[2]};
    }
    read_joints(in_.require(root, "joints", "the robot description"));
    if (root["friction"]) read_friction(root["friction"]);
    if (root["rotor_inertia"]) model_.rotor_inertia = in_.boolean(root["rotor_inertia"], "rotor_inertia");
    read_drive_chain(in_, root["drives"], model_);
    build_standard_parameters(model_);
    if (root["payload"]) read_payload(root["payload"]);
    if (root["known"]) read_known_values(in_, root["known"], model_);
    // A link without `region:` and without a-priori inertials: guessed around the segments its
    // DH rows give to the next joints and tool frames and back along its axis by its r
    // (body_regions.hpp), as for a URDF body.
    guess_missing_regions(model_, child_origins(model_.tree));
    validate(model_.tree);
    return std::move(model_);
  }

 private:
  void read_joints(const YAML::Node& list) {
    if (!list.IsSequence() || list.size() == 0) {
      in_.fail(list, "'joints' must be a non-empty list of modified DH rows");
    }
    if (list.size() > static_cast<std::size_t>(kMaxBodies)) {
      in_.fail(list[kMaxBodies], "joint " + std::to_string(kMaxBodies + 1) + ": a description may hold at most " +
                                     std::to_string(kMaxBodies) + " rows (README, Limits)");
    }
    std::vector<RawJoint> raw;
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const YAML::Node row = list[i];
      const int j = static_cast<int>(i) + 1;
      const std::string context = "joint " + std::to_string(j);
      in_.check_keys(row, {"name", "type", "ant", "alpha", "d", "theta", "r", "limits", "region"},
                     context);
      RawJoint joint;
      joint.description.where = in_.at(row);
      joint.description.name = row["name"] ? in_.text(row["name"], "name") : "L" + std::to_string(j);
      if (!names.insert(joint.description.name).second) {
        in_.fail(row["name"], "joint name '" + joint.description.name + "' is used twice");
      }
      const YAML::Node type = in_.require(row, "type", context);
      const std::string type_text = in_.text(type, "type");
      if (type_text == "revolute") {
        joint.type = JointType::kRevolute;
      } else if (type_text == "prismatic") {
        joint.type = JointType::kPrismatic;
      } else if (type_text == "fixed") {
        joint.type = JointType::kFixed;
      } else {
        in_.fail(type, "unknown joint type '" + type_text + "'" +
                           did_you_mean(type_text, {"revolute", "prismatic", "fixed"}) +
                           "; valid types: revolute, prismatic, fixed");
      }
      MdhParameters mdh;
      mdh.alpha = snapped_angle(in_.require(row, "alpha", context), "alpha", context);
      mdh.d = in_.length(in_.require(row, "d", context), "d");
      mdh.theta = snapped_angle(in_.require(row, "theta", context), "theta", context);
      mdh.r = in_.length(in_.require(row, "r", context), "r");
      joint.description.mdh = mdh;
      joint.antecedent = j - 1;
      if (row["ant"]) {
        joint.has_ant = true;
        joint.ant_node = row["ant"];
      }
      if (row["limits"]) joint.description.limits = read_limits(row["limits"], joint.type, context);
      model_.body_regions.emplace_back();
      if (row["region"]) model_.body_regions.back() = read_region(in_, row["region"], context);
      raw.push_back(std::move(joint));
    }
    resolve_antecedents(raw);
    int dof = 0;
    for (RawJoint& joint : raw) {
      Body body;
      body.name = joint.description.name;
      body.parent = joint.antecedent - 1;
      body.type = joint.type;
      body.dof_index = joint.type == JointType::kFixed ? -1 : dof++;
      body.fixed = mdh_frame(*joint.description.mdh);
      body.axis = {0, 0, 1};
      model_.tree.bodies.push_back(body);
      model_.joints.push_back(std::move(joint.description));
    }
    model_.tree.dof = dof;
    if (dof > kMaxMovingJoints) {
      int moving = 0;
      for (std::size_t j = 0; j < model_.tree.bodies.size(); ++j) {
        if (model_.tree.bodies[j].dof_index >= 0 && ++moving > kMaxMovingJoints) {
          throw InputError(model_.joints[j].where,
                           "joint " + std::to_string(j + 1) + " is moving joint " +
                               std::to_string(moving) + "; modelgen models at most " +
                               std::to_string(kMaxMovingJoints) +
                               " moving joints (generation time grows with their cube; README, Limits)");
        }
      }
    }
    if (dof == 0) in_.fail(list, "the robot has no moving joint (all joints are 'fixed')");
  }

  // An MDH angle; a number written for a quarter turn ("1.5708") becomes the exact fraction of
  // pi, so the generated code gets exact sines and cosines and the base parameters the
  // robot's symmetries. A note says so unless the number was pi to double precision.
  Angle snapped_angle(const YAML::Node& node, const std::string& field, const std::string& joint) {
    const Angle written = in_.angle(node, field);
    if (written.is_pi_fraction) return written;
    const auto quarters = nearest_quarter_turn(written.value, angle_tolerance_);
    if (!quarters) return written;
    Angle exact = Angle::pi_fraction(*quarters, 2, quarter_turn_text(*quarters));
    if (std::abs(written.value - exact.value) > kSilentSnap) {
      model_.notes.push_back(
          {in_.at(node), snap_note(joint + ": " + field, written.value, *quarters, angle_tolerance_)});
    }
    return exact;
  }

  // `ant` is a link number (0 = base) or a link name; Khalil's numbering needs a(j) < j.
  void resolve_antecedents(std::vector<RawJoint>& raw) {
    const int n = static_cast<int>(raw.size());
    std::vector<std::string> names;
    for (const RawJoint& joint : raw) names.push_back(joint.description.name);
    for (int j = 1; j <= n; ++j) {
      RawJoint& joint = raw[j - 1];
      if (!joint.has_ant) continue;
      const YAML::Node& node = joint.ant_node;
      int ant = -1;
      if (node.IsScalar() && !node.Scalar().empty() &&
          node.Scalar().find_first_not_of("+-0123456789") == std::string::npos) {
        ant = static_cast<int>(in_.integer(node, "ant"));
      } else if (node.IsScalar()) {
        auto found = std::find(names.begin(), names.end(), node.Scalar());
        if (found == names.end()) {
          in_.fail(node, "antecedent '" + node.Scalar() + "' of joint " + std::to_string(j) +
                             " is not a link name" + did_you_mean(node.Scalar(), names));
        }
        ant = static_cast<int>(found - names.begin()) + 1;
      } else {
        in_.fail(node, "'ant' must be a link number (0 for the base) or a link name");
      }
      if (ant < 0 || ant > n) {
        in_.fail(node, "antecedent " + std::to_string(ant) + " of joint " + std::to_string(j) +
                           " does not exist (links are numbered 1.." + std::to_string(n) +
                           ", 0 is the base)");
      }
      joint.antecedent = ant;
    }
    for (int j = 1; j <= n; ++j) {
      const RawJoint& joint = raw[j - 1];
      if (joint.antecedent < j) continue;
      // Follow the antecedents from j: either they come back to j (a cycle) or the numbering is
      // simply not Khalil's (a(j) < j); say which.
      std::string chain = std::to_string(j);
      int k = joint.antecedent;
      for (int steps = 0; steps <= n && k != 0; ++steps) {
        chain += " -> " + std::to_string(k);
        if (k == j) {
          in_.fail(joint.ant_node, "antecedents form a cycle: " + chain +
                                       "; a robot description must be a tree rooted at the base");
        }
        k = raw[k - 1].antecedent;
      }
      in_.fail(joint.ant_node,
               "antecedent " + std::to_string(joint.antecedent) + " of joint " +
                   std::to_string(j) +
                   " comes after it; number the links so that a(j) < j (Khalil-Kleinfinger)");
    }
  }

  JointLimits read_limits(const YAML::Node& node, JointType type, const std::string& context) {
    in_.check_keys(node, {"q", "dq", "ddq", "effort"}, "limits of " + context);
    JointLimits limits;
    if (node["q"]) {
      if (type == JointType::kFixed) in_.fail(node["q"], "a fixed joint has no position limits");
      const auto q = in_.numbers(node["q"], "q", 2);
      if (!(q[0] < q[1])) in_.fail(node["q"], "position limits must be [lower, upper] with lower < upper");
      limits.q_lower = q[0];
      limits.q_upper = q[1];
      if (type == JointType::kRevolute) {
        check_angle_limit(in_.at(node["q"]), context + ": limits.q lower", q[0], model_.notes);
        check_angle_limit(in_.at(node["q"]), context + ": limits.q upper", q[1], model_.notes);
      }
    }
    if (node["dq"]) limits.dq = in_.positive(node["dq"], "dq");
    if (limits.dq && type == JointType::kRevolute) {
      check_velocity_limit(in_.at(node["dq"]), context + ": limits.dq", *limits.dq, model_.notes);
    }
    if (node["ddq"]) limits.ddq = in_.positive(node["ddq"], "ddq");
    if (node["effort"]) limits.effort = in_.positive(node["effort"], "effort");
    return limits;
  }

  void read_friction(const YAML::Node& node) {
    in_.check_keys(node, {"viscous", "coulomb", "offset", "asymmetric"}, "friction");
    if (node["viscous"]) model_.friction.viscous = in_.boolean(node["viscous"], "viscous");
    if (node["coulomb"]) model_.friction.coulomb = in_.boolean(node["coulomb"], "coulomb");
    if (node["offset"]) model_.friction.offset = in_.boolean(node["offset"], "offset");
    if (node["asymmetric"]) model_.friction.asymmetric = in_.boolean(node["asymmetric"], "asymmetric");
  }

  void read_payload(const YAML::Node& node) {
    in_.check_keys(node, {"link"}, "payload");
    const YAML::Node link = in_.require(node, "link", "payload");
    const long j = in_.integer(link, "link");
    if (j < 1 || j > static_cast<long>(model_.tree.bodies.size())) {
      in_.fail(link, "payload link " + std::to_string(j) + " does not exist (links are 1.." +
                         std::to_string(model_.tree.bodies.size()) + ")");
    }
    model_.payload_body = static_cast<int>(j) - 1;
  }

  YamlReader in_;
  double angle_tolerance_;
  RobotModel model_;
};

}  // namespace

RobotModel load_mdh_yaml(const std::string& path, const std::string& text,
                          double angle_tolerance) {
  try {
    return MdhYamlLoader(path, angle_tolerance).load(text);
  } catch (const YAML::Exception& e) {
    // A yaml-cpp error the checks above did not anticipate: still report it with a position.
    throw InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
}

}  // namespace modelgen
