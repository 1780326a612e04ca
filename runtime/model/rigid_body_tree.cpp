// Invariant checks on RigidBodyTree: everything downstream (reference dynamics, symbolic
// derivation, code emission) may then assume a well-formed tree.

#include "modelgen/model/rigid_body_tree.hpp"

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace modelgen {

bool is_inertial(ParamKind kind) {
  return kind == ParamKind::kXX || kind == ParamKind::kXY || kind == ParamKind::kXZ ||
         kind == ParamKind::kYY || kind == ParamKind::kYZ || kind == ParamKind::kZZ ||
         kind == ParamKind::kMX || kind == ParamKind::kMY || kind == ParamKind::kMZ ||
         kind == ParamKind::kM;
}

int inertial_slot(ParamKind kind) {
  static_assert(static_cast<int>(ParamKind::kXX) == 0 && static_cast<int>(ParamKind::kM) == 9,
                "the inertial kinds come first, in slot order");
  return is_inertial(kind) ? static_cast<int>(kind) : -1;
}

const char* param_kind_stem(ParamKind kind) {
  switch (kind) {
    case ParamKind::kXX:
      return "XX";
    case ParamKind::kXY:
      return "XY";
    case ParamKind::kXZ:
      return "XZ";
    case ParamKind::kYY:
      return "YY";
    case ParamKind::kYZ:
      return "YZ";
    case ParamKind::kZZ:
      return "ZZ";
    case ParamKind::kMX:
      return "MX";
    case ParamKind::kMY:
      return "MY";
    case ParamKind::kMZ:
      return "MZ";
    case ParamKind::kM:
      return "M";
    case ParamKind::kIa:
      return "Ia";
    case ParamKind::kFv:
      return "Fv";
    case ParamKind::kFc:
      return "Fc";
    case ParamKind::kOff:
      return "OFF";
    case ParamKind::kFvPos:
      return "Fvp";
    case ParamKind::kFvNeg:
      return "Fvn";
    case ParamKind::kFcPos:
      return "Fcp";
    case ParamKind::kFcNeg:
      return "Fcn";
    case ParamKind::kIam:
      return "Iam";
    case ParamKind::kFvm:
      return "Fvm";
    case ParamKind::kFcm:
      return "Fcm";
  }
  return "?";
}

namespace {

bool is_drive_param(ParamKind kind) {
  return kind == ParamKind::kIa || kind == ParamKind::kFv || kind == ParamKind::kFc ||
         kind == ParamKind::kOff || kind == ParamKind::kFvPos || kind == ParamKind::kFvNeg ||
         kind == ParamKind::kFcPos || kind == ParamKind::kFcNeg || kind == ParamKind::kIam ||
         kind == ParamKind::kFvm || kind == ParamKind::kFcm;
}

bool is_motor_param(ParamKind kind) {
  return kind == ParamKind::kIam || kind == ParamKind::kFvm || kind == ParamKind::kFcm;
}

void check_rotation(const Body& body) {
  const auto& r = body.fixed.rotation;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += r[3 * k + i] * r[3 * k + j];
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-9) {
        throw std::invalid_argument("body '" + body.name + "': fixed rotation is not orthonormal");
      }
    }
  }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
  if (det < 0) {
    throw std::invalid_argument("body '" + body.name + "': fixed rotation is a reflection");
  }
}

}  // namespace

const CoupledMotor* coupled_motor_of(const RigidBodyTree& tree, const StandardParam& param) {
  if (param.body < 0 || param.body >= static_cast<int>(tree.bodies.size())) return nullptr;
  const int dof = tree.bodies[param.body].dof_index;
  for (const CoupledMotor& motor : tree.coupled_motors) {
    if (motor.dof_index == dof) return &motor;
  }
  return nullptr;
}

void validate(const RigidBodyTree& tree) {
  std::vector<int> dof_owner(tree.dof, -1);
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    if (body.parent < -1 || body.parent >= static_cast<int>(j)) {
      throw std::invalid_argument("body '" + body.name + "': parent index " +
                                  std::to_string(body.parent) + " must come before the body");
    }
    check_rotation(body);
    if (body.type == JointType::kFixed) {
      if (body.dof_index != -1) {
        throw std::invalid_argument("body '" + body.name + "': fixed joint with a dof index");
      }
      continue;
    }
    const double norm = std::sqrt(body.axis[0] * body.axis[0] + body.axis[1] * body.axis[1] +
                                  body.axis[2] * body.axis[2]);
    if (std::abs(norm - 1.0) > 1e-9) {
      throw std::invalid_argument("body '" + body.name + "': joint axis is not a unit vector");
    }
    if (body.dof_index < 0 || body.dof_index >= tree.dof || dof_owner[body.dof_index] != -1) {
      throw std::invalid_argument("body '" + body.name + "': dof index " +
                                  std::to_string(body.dof_index) + " is out of range or reused");
    }
    dof_owner[body.dof_index] = static_cast<int>(j);
  }
  for (int i = 0; i < tree.dof; ++i) {
    if (dof_owner[i] == -1) {
      throw std::invalid_argument("dof index " + std::to_string(i) + " has no joint");
    }
  }
  std::set<int> motors;
  for (const CoupledMotor& motor : tree.coupled_motors) {
    if (motor.dof_index < 0 || motor.dof_index >= tree.dof ||
        !motors.insert(motor.dof_index).second) {
      throw std::invalid_argument("coupled motor of dof " + std::to_string(motor.dof_index) +
                                  " is out of range or given twice");
    }
    if (static_cast<int>(motor.coupling.size()) != tree.dof ||
        motor.coupling[motor.dof_index] != 1.0) {
      throw std::invalid_argument("coupled motor of dof " + std::to_string(motor.dof_index) +
                                  ": coupling needs one entry per dof and 1 on its own joint");
    }
  }
  std::set<std::string> names;
  for (const StandardParam& param : tree.params) {
    if (param.body < 0 || param.body >= static_cast<int>(tree.bodies.size())) {
      throw std::invalid_argument("parameter '" + param.name + "' is on no body");
    }
    if (!names.insert(param.name).second) {
      throw std::invalid_argument("parameter '" + param.name + "' appears twice");
    }
    if (is_motor_param(param.kind) && coupled_motor_of(tree, param) == nullptr) {
      throw std::invalid_argument("parameter '" + param.name + "' refers to no coupled motor");
    }
    if (is_drive_param(param.kind) && tree.bodies[param.body].type == JointType::kFixed) {
      throw std::invalid_argument("parameter '" + param.name +
                                  "' is a drive parameter on fixed body '" +
                                  tree.bodies[param.body].name + "'");
    }
  }
}

}  // namespace modelgen
