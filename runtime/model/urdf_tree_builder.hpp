// Builds the bodies of a RobotModel from a URDF read by urdfdom and checked by the TinyXML2
// pass (urdf_structure.hpp), walking the kinematic tree depth first from the base link.
// Private to the URDF loader.
#pragma once

#include <array>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <urdf_model/model.h>
#include <Eigen/Geometry>

#include "modelgen/model/robot_model.hpp"
#include "runtime/model/urdf_structure.hpp"

namespace modelgen {

// Walks the kinematic tree depth first from the base, making a body per moving joint.
class TreeBuilder {
 public:
  TreeBuilder(const std::string& path, const UrdfStructure& structure,
              const urdf::ModelInterface& urdf, const std::set<int>* kept_joints, RobotModel& model)
      : path_(path), structure_(structure), urdf_(urdf), kept_joints_(kept_joints), model_(model) {}

  // `tolerance`: LoadOptions::angle_tolerance, for snapping rounded quarter turns;
  // `mimic_as_joint`: LoadOptions::mimic_as_joint.
  void build(int base_link, double tolerance, bool mimic_as_joint);

  // The summed inertial parameters per body; nullopt for bodies none of whose links has an
  // <inertial>, so an absent inertial stays unknown rather than becoming zero.
  const std::vector<std::optional<std::array<double, 10>>>& inertials() const { return inertials_; }

  // Per body, the box (lowest and highest corner, body frame) holding its links' shapes.
  using Box = std::pair<Eigen::Vector3d, Eigen::Vector3d>;
  const std::vector<std::optional<Box>>& shape_boxes() const { return boxes_; }

  // Per body, the origins (body frame) of its child joints and of the links fixed to it: the
  // ends of the segments a body without shapes is guessed to span (body_regions.hpp).
  const std::vector<std::vector<Eigen::Vector3d>>& segment_ends() const { return ends_; }

 private:
  const urdf::Joint& joint(const JointEntry& entry) const;
  Eigen::Isometry3d origin_transform(const urdf::Pose& pose, const OriginEntry& origin,
                                     const std::string& owner);
  std::array<double, 3> joint_axis(const urdf::Joint& joint, const JointEntry& entry);
  void add_inertial(const std::string& link_name, int body,
                    const Eigen::Isometry3d& body_from_link);
  void add_shapes(const std::string& link_name, int body, const Eigen::Isometry3d& body_from_link);
  void push_children(int link, int body, const Eigen::Isometry3d& body_from_link);
  JointDescription joint_description(const urdf::Joint& urdf_joint, const JointEntry& entry) const;
  void visit(int j, int body, const Eigen::Isometry3d& body_from_link);
  void note_mimic(const JointEntry& entry);

  // A joint still to visit: below `body`, its parent link at `body_from_link` in that body.
  struct Pending {
    int joint;
    int body;
    Eigen::Isometry3d body_from_link;
  };

  const std::string& path_;
  const UrdfStructure& structure_;
  const urdf::ModelInterface& urdf_;
  const std::set<int>* kept_joints_;
  RobotModel& model_;
  std::vector<std::optional<std::array<double, 10>>> inertials_;
  std::vector<std::optional<Box>> boxes_;
  std::vector<std::vector<Eigen::Vector3d>> ends_;
  std::vector<Pending> pending_;
  double tolerance_ = 0;
  bool mimic_as_joint_ = false;
};

}  // namespace modelgen
