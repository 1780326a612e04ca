// Parameter list construction, angle parsing and name rules shared by the description loaders.

#include "modelgen/model/robot_model.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <numeric>
#include <set>

#include "modelgen/model/number_text.hpp"

namespace modelgen {

Angle Angle::from_radians(double radians) {
  Angle a;
  a.value = radians;
  a.text = shortest_text(radians);
  return a;
}

Angle Angle::pi_fraction(long numerator, long denominator, std::string text) {
  if (denominator < 0) {
    numerator = -numerator;
    denominator = -denominator;
  }
  const long g = std::gcd(numerator, denominator);
  Angle a;
  a.is_pi_fraction = true;
  a.numerator = g ? numerator / g : 0;
  a.denominator = g ? denominator / g : 1;
  a.value =
      std::numbers::pi * static_cast<double>(a.numerator) / static_cast<double>(a.denominator);
  a.text = std::move(text);
  return a;
}

namespace {

// Exact cos/sin for k * pi/2; nullopt otherwise.
std::optional<std::pair<double, double>> quarter_turn(const Angle& a) {
  if (!a.is_pi_fraction && a.value != 0.0) return std::nullopt;
  long quarter = 0;
  if (a.is_pi_fraction) {
    if ((2 * a.numerator) % a.denominator != 0) return std::nullopt;
    quarter = 2 * a.numerator / a.denominator;
  }
  quarter = ((quarter % 4) + 4) % 4;
  static const double kCos[4] = {1, 0, -1, 0};
  static const double kSin[4] = {0, 1, 0, -1};
  return std::make_pair(kCos[quarter], kSin[quarter]);
}

}  // namespace

double Angle::cos() const {
  if (auto exact = quarter_turn(*this)) return exact->first;
  return std::cos(value);
}

double Angle::sin() const {
  if (auto exact = quarter_turn(*this)) return exact->second;
  return std::sin(value);
}

namespace {

std::string strip_spaces(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (!std::isspace(static_cast<unsigned char>(c))) out += c;
  }
  return out;
}

std::optional<double> parse_number(std::string_view s) {
  if (s.empty()) return std::nullopt;
  double value = 0;
  const char* first = s.data();
  if (*first == '+') ++first;
  auto [end, ec] = std::from_chars(first, s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long> parse_integer(std::string_view s) {
  long value = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return value;
}

}  // namespace

std::optional<Angle> parse_angle(std::string_view text) {
  const std::string s = strip_spaces(text);
  const std::size_t pi_at = s.find("pi");
  if (pi_at == std::string::npos) {
    auto value = parse_number(s);
    if (!value) return std::nullopt;
    Angle a = *value == 0.0 ? Angle::pi_fraction(0, 1, std::string(text)) : Angle{};
    a.value = *value;
    a.text = std::string(text);
    return a;
  }
  // [sign][k*]pi[/m] with k, m numbers (integers keep the angle an exact fraction of pi).
  std::string before = s.substr(0, pi_at);
  std::string after = s.substr(pi_at + 2);
  double sign = 1;
  if (!before.empty() && (before[0] == '-' || before[0] == '+')) {
    sign = before[0] == '-' ? -1 : 1;
    before.erase(0, 1);
  }
  std::string factor_text = "1";
  if (!before.empty()) {
    if (before.back() != '*') return std::nullopt;
    factor_text = before.substr(0, before.size() - 1);
  }
  std::string divisor_text = "1";
  if (!after.empty()) {
    if (after[0] != '/') return std::nullopt;
    divisor_text = after.substr(1);
  }
  auto factor = parse_number(factor_text);
  auto divisor = parse_number(divisor_text);
  if (!factor || !divisor || *divisor == 0.0) return std::nullopt;
  auto k = parse_integer(factor_text);
  auto m = parse_integer(divisor_text);
  if (k && m) return Angle::pi_fraction(static_cast<long>(sign) * *k, *m, std::string(text));
  Angle a;
  a.value = sign * *factor * std::numbers::pi / *divisor;
  a.text = std::string(text);
  return a;
}

std::string DescriptionNote::to_string() const {
  return where.to_string() + (warning ? ": warning: " : ": note: ") + message;
}

int RobotModel::param_index(std::string_view param_name) const {
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    if (tree.params[k].name == param_name) return static_cast<int>(k);
  }
  return -1;
}

std::vector<std::string> RobotModel::param_names() const {
  std::vector<std::string> names;
  for (const StandardParam& p : tree.params) names.push_back(p.name);
  return names;
}

void build_standard_parameters(RobotModel& model) {
  static const ParamKind kInertial[] = {ParamKind::kXX, ParamKind::kXY, ParamKind::kXZ,
                                        ParamKind::kYY, ParamKind::kYZ, ParamKind::kZZ,
                                        ParamKind::kMX, ParamKind::kMY, ParamKind::kMZ,
                                        ParamKind::kM};
  // Motors that drive several joints (rows of motor_from_joint with off-diagonal entries) get
  // their own rotor inertia and friction, scaled to their joint (Gautier & Briot eq. 26).
  model.tree.coupled_motors.clear();
  const Eigen::MatrixXd& K = model.drives.motor_from_joint;
  if (K.rows() == model.tree.dof && K.cols() == model.tree.dof) {
    for (int m = 0; m < model.tree.dof; ++m) {
      bool coupled = false;
      for (int l = 0; l < model.tree.dof; ++l) coupled = coupled || (l != m && K(m, l) != 0.0);
      if (!coupled || K(m, m) == 0.0) continue;
      CoupledMotor motor;
      motor.dof_index = m;
      for (int l = 0; l < model.tree.dof; ++l) motor.coupling.push_back(l == m ? 1.0 : K(m, l) / K(m, m));
      model.tree.coupled_motors.push_back(std::move(motor));
    }
  }
  std::vector<StandardParam>& params = model.tree.params;
  params.clear();
  for (std::size_t j = 0; j < model.tree.bodies.size(); ++j) {
    const int body = static_cast<int>(j);
    const std::string suffix = std::to_string(j + 1);
    auto add = [&](ParamKind kind) {
      params.push_back({std::string(param_kind_stem(kind)) + suffix, body, kind});
    };
    for (ParamKind kind : kInertial) add(kind);
    if (model.tree.bodies[j].type == JointType::kFixed) continue;
    if (model.rotor_inertia) add(ParamKind::kIa);
    if (model.friction.asymmetric) {
      if (model.friction.viscous) {
        add(ParamKind::kFvPos);
        add(ParamKind::kFvNeg);
      }
      if (model.friction.coulomb) {
        add(ParamKind::kFcPos);
        add(ParamKind::kFcNeg);
      }
    } else {
      if (model.friction.viscous) add(ParamKind::kFv);
      if (model.friction.coulomb) add(ParamKind::kFc);
    }
    if (model.friction.offset) add(ParamKind::kOff);
    for (const CoupledMotor& motor : model.tree.coupled_motors) {
      if (motor.dof_index != model.tree.bodies[j].dof_index) continue;
      if (model.rotor_inertia) add(ParamKind::kIam);
      if (model.friction.viscous) add(ParamKind::kFvm);
      if (model.friction.coulomb) add(ParamKind::kFcm);
    }
  }
  model.known_values.assign(params.size(), std::nullopt);
}

namespace {

bool is_identifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

bool is_reserved(const std::string& name) {
  static const std::set<std::string> kReserved = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break",
      "case", "catch", "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept",
      "const", "consteval", "constexpr", "constinit", "const_cast", "continue", "co_await",
      "co_return", "co_yield", "decltype", "default", "delete", "do", "double", "dynamic_cast",
      "else", "enum", "explicit", "export", "extern", "false", "float", "for", "friend", "goto",
      "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register",
      "reinterpret_cast", "requires", "return", "short", "signed", "sizeof", "static",
      "static_assert", "static_cast", "struct", "switch", "template", "this", "thread_local",
      "throw", "true", "try", "typedef", "typeid", "typename", "union", "unsigned", "using",
      "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq", "std", "modelgen",
      "internal", "gen"};
  return kReserved.count(name) > 0 || name.find("__") != std::string::npos ||
         (!name.empty() && name[0] == '_');
}

}  // namespace

void check_robot_name(const std::string& name, const SourceLocation& where) {
  if (!is_identifier(name)) {
    throw InputError(where, "robot name '" + name +
                                "' is not a C++ identifier (letters, digits and '_', not starting "
                                "with a digit); it becomes the namespace of the generated code");
  }
  if (is_reserved(name)) {
    throw InputError(where, "robot name '" + name +
                                "' is reserved (a C++ keyword, 'std', 'modelgen', 'internal', "
                                "'gen', or a reserved identifier); choose another name");
  }
}

std::string robot_identifier(const std::string& name, const SourceLocation& where,
                             std::vector<DescriptionNote>& notes) {
  if (is_identifier(name) && !is_reserved(name)) return name;
  std::string id;
  for (char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) && u < 128) {
      id += static_cast<char>(std::tolower(u));
    } else if (!id.empty() && id.back() != '_') {
      id += '_';
    }
  }
  while (!id.empty() && id.back() == '_') id.pop_back();
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "robot_" + id;
  if (id.back() == '_') id.pop_back();
  if (is_reserved(id)) id += "_robot";
  notes.push_back({where, "robot name '" + name +
                              "' is not usable as a C++ namespace; the "
                              "generated code is namespace modelgen::" +
                              id + " (--name chooses another)"});
  return id;
}

std::array<double, 10> standard_from_inertial(double mass, const std::array<double, 3>& com,
                                              const std::array<double, 9>& R_inertial,
                                              const std::array<double, 6>& I_com) {
  Eigen::Matrix3d R;
  R << R_inertial[0], R_inertial[1], R_inertial[2], R_inertial[3], R_inertial[4], R_inertial[5],
      R_inertial[6], R_inertial[7], R_inertial[8];
  Eigen::Matrix3d Ic;
  Ic << I_com[0], I_com[1], I_com[2], I_com[1], I_com[3], I_com[4], I_com[2], I_com[4], I_com[5];
  const Eigen::Vector3d c(com[0], com[1], com[2]);
  // Rotate into the body frame, then move from the centre of mass to the frame origin
  // (parallel-axis theorem in tensor form).
  const Eigen::Matrix3d J = R * Ic * R.transpose() +
                            mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return {J(0, 0), J(0, 1), J(0, 2), J(1, 1), J(1, 2), J(2, 2),
          mass * c.x(), mass * c.y(), mass * c.z(), mass};
}

}  // namespace modelgen
