// What the modelid export tests share (modelid_export_test, modelid_export_refusal_test):
// estimate files made here from a standard set, the round trip of a written description back to
// its base parameters, a two-axis URDF arm with a tool on a fixed joint, and readers of a written
// URDF's masses. Header only: each test links urdfdom and TinyXML2 itself (tests/CMakeLists.txt).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tinyxml2.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"

namespace modelgen::test {

inline ReferenceModel reference_of(const RobotModel& robot, const std::string& path) {
  return ReferenceModel(robot.name, robot.tree, sha256_hex(read_source_file(path)), robot.drives);
}

// The base parameters of an estimate file ("parameters", in the model's order).
inline Eigen::VectorXd estimate_base(const nlohmann::json& est, const IdentificationModel& model) {
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(model.num_base_params());
  const auto& names = model.base_param_names();
  for (const nlohmann::json& p : est["parameters"]) {
    const auto it = std::find(names.begin(), names.end(), p["name"].get<std::string>());
    EXPECT_NE(it, names.end()) << p["name"];
    if (it != names.end()) beta[it - names.begin()] = p["value"].get<double>();
  }
  return beta;
}

// The round trip of the issue: the written description, loaded by modelgen, has a-priori values
// whose base parameters (through that model's regrouping) are the estimate's. Parameters the
// description has no place for (drive parameters in a URDF) come from the estimate's standard
// set. Returns the largest relative difference.
inline double round_trip_error(const std::filesystem::path& written, const nlohmann::json& est) {
  const RobotModel robot = load_robot(written.string());
  const ReferenceModel model = reference_of(robot, written.string());
  Eigen::VectorXd standard = Eigen::VectorXd::Zero(model.num_standard_params());
  for (int k = 0; k < model.num_standard_params(); ++k) {
    const std::string& name = model.standard_param_names()[static_cast<std::size_t>(k)];
    const bool inertial = robot.tree.params[static_cast<std::size_t>(k)].kind <= ParamKind::kM;
    if (robot.format == DescriptionFormat::kUrdf && !inertial) {
      standard[k] = est["standard"][name].get<double>();
    } else if (robot.known_values[static_cast<std::size_t>(k)]) {
      standard[k] = *robot.known_values[static_cast<std::size_t>(k)];
    } else {
      ADD_FAILURE() << name << " has no value in " << written;
    }
  }
  Eigen::VectorXd beta(model.num_base_params());
  model.base_from_standard(standard.data(), beta.data());
  const Eigen::VectorXd expected = estimate_base(est, model);
  double worst = 0;
  for (Eigen::Index b = 0; b < beta.size(); ++b) {
    worst = std::max(worst, std::abs(beta[b] - expected[b]) / (1 + std::abs(expected[b])));
  }
  return worst;
}

// A physically consistent standard set for any description, made here: per body a mass, a
// centre of mass and an inertia about it (positive definite, triangle inequalities), moved to
// the body frame's origin by the parallel-axis theorem; positive drive parameters.
inline Eigen::VectorXd consistent_standard(const RobotModel& robot) {
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.tree.params.size()));
  for (std::size_t k = 0; k < robot.tree.params.size(); ++k) p[k] = 0.1 + 0.01 * k;
  for (std::size_t b = 0; b < robot.tree.bodies.size(); ++b) {
    const std::string j = std::to_string(b + 1);
    if (robot.param_index("M" + j) < 0) continue;
    const double m = 1 + 0.3 * b;
    const Eigen::Vector3d c(0.02 * (b + 1), -0.01, 0.05);
    Eigen::Matrix3d Ic;
    Ic << 0.05, 0.001, 0, 0.001, 0.045, 0.002, 0, 0.002, 0.04;
    Ic *= 1 + 0.2 * b;
    const Eigen::Matrix3d J =
        Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const std::pair<const char*, double> values[] = {
        {"XX", J(0, 0)}, {"XY", J(0, 1)},   {"XZ", J(0, 2)},   {"YY", J(1, 1)},   {"YZ", J(1, 2)},
        {"ZZ", J(2, 2)}, {"MX", m * c.x()}, {"MY", m * c.y()}, {"MZ", m * c.z()}, {"M", m}};
    for (const auto& [stem, value] : values) p[robot.param_index(stem + j)] = value;
  }
  return p;
}

// An estimate file as fit --physical writes it, for `standard` of the description at `path`.
inline nlohmann::json estimate_of(const std::string& path, const Eigen::VectorXd& standard) {
  const RobotModel robot = load_robot(path);
  const ReferenceModel model = reference_of(robot, path);
  Eigen::VectorXd beta(model.num_base_params());
  model.base_from_standard(standard.data(), beta.data());
  nlohmann::json est;
  est["model"] = model.name();
  est["description_sha256"] = model.description_sha256();
  est["method"] = "IDIM-WLS (physically consistent)";
  est["parameters"] = nlohmann::json::array();
  for (int b = 0; b < model.num_base_params(); ++b) {
    est["parameters"].push_back({{"name", model.base_param_names()[b]}, {"value", beta[b]}});
  }
  for (int k = 0; k < model.num_standard_params(); ++k) {
    est["standard"][model.standard_param_names()[k]] = standard[k];
  }
  est["physical"] = {{"prior_weight", 0.001}};
  return est;
}

inline const tinyxml2::XMLElement* link_element(const tinyxml2::XMLDocument& doc,
                                                const std::string& name) {
  for (const tinyxml2::XMLElement* link = doc.RootElement()->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    if (link->Attribute("name", name.c_str())) return link;
  }
  return nullptr;
}

inline double mass_of(const tinyxml2::XMLDocument& doc, const std::string& link) {
  const tinyxml2::XMLElement* element = link_element(doc, link);
  if (!element || !element->FirstChildElement("inertial")) return -1;
  return element->FirstChildElement("inertial")
      ->FirstChildElement("mass")
      ->DoubleAttribute("value");
}

// A two-axis arm with a 0.8 kg tool on a fixed joint, turned and offset: modelgen merges the
// tool into link l2's body.
inline constexpr const char* kToolArm = R"(<?xml version="1.0"?>
<robot name="tool_arm">
  <link name="base"/>
  <joint name="j1" type="revolute">
    <parent link="base"/>
    <child link="l1"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <link name="l1">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/>
    </inertial>
  </link>
  <joint name="j2" type="revolute">
    <parent link="l1"/>
    <child link="l2"/>
    <origin xyz="0.4 0 0" rpy="1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <link name="l2">
    <inertial>
      <origin xyz="0.15 0.01 0" rpy="0 0 0.3"/>
      <mass value="1.5"/>
      <inertia ixx="0.004" ixy="0.0002" ixz="0" iyy="0.01" iyz="0" izz="0.011"/>
    </inertial>
  </link>
  <joint name="tool_joint" type="fixed">
    <parent link="l2"/>
    <child link="tool"/>
    <origin xyz="0.3 0 0" rpy="0 1.5707963267948966 0"/>
  </joint>
  <!-- a gripper -->
  <link name="tool">
    <inertial>
      <origin xyz="0 0 0.05" rpy="0.2 0 0"/>
      <mass value="0.8"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.001"/>
    </inertial>
  </link>
</robot>
)";

// The description's own values with link 2's body (l2 and the tool) scaled by `scale`: still
// a physical body, of mass scale * 2.3 kg.
inline nlohmann::json tool_arm_estimate(const std::filesystem::path& urdf, double scale) {
  const RobotModel robot = load_robot(urdf.string());
  Eigen::VectorXd standard = consistent_standard(robot);
  for (std::size_t k = 0; k < robot.tree.params.size(); ++k) {
    if (robot.known_values[k]) standard[k] = *robot.known_values[k];
    if (robot.tree.params[k].body == 1 && robot.known_values[k]) standard[k] *= scale;
  }
  return estimate_of(urdf.string(), standard);
}

}  // namespace modelgen::test
