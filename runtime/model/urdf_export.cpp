// The identified URDF: the loader's merge of fixed links undone (urdf_loader.cpp adds each fixed
// link's inertial, moved to the body frame, to the body of its moving ancestor), each moving
// link's <inertial> rewritten from its body's ten standard parameters.

#include "modelgen/model/urdf_export.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <tinyxml2.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "runtime/model/angle_snapping.hpp"
#include "runtime/model/urdf_loader.hpp"
#include "runtime/model/urdf_structure.hpp"

namespace modelgen {

namespace {

using Inertial = Eigen::Matrix<double, 10, 1>;  // XX XY XZ YY YZ ZZ MX MY MZ M, body frame
constexpr const char* kCommentStart = " modelid export:";

std::string text_of(double value) { return shortest_text(value + 0.0); }  // + 0.0: no "-0"

std::string printed(const tinyxml2::XMLDocument& document) {
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);
  return printer.CStr();
}

void parse(tinyxml2::XMLDocument& document, const std::string& text) {
  // The loader read this text already, so a failure here is a bug, not bad input.
  if (document.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS ||
      document.RootElement() == nullptr) {
    throw std::logic_error(std::string("export: TinyXML2 cannot parse the URDF the loader read: ") +
                           document.ErrorStr());
  }
}

std::map<std::string, tinyxml2::XMLElement*> links_by_name(tinyxml2::XMLDocument& document) {
  std::map<std::string, tinyxml2::XMLElement*> links;
  for (tinyxml2::XMLElement* link = document.RootElement()->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    if (const char* name = link->Attribute("name")) links[name] = link;
  }
  return links;
}

// The links the loader merged into the body of `link`: those below it through fixed joints
// only, depth first.
std::vector<std::string> fixed_links_below(const tinyxml2::XMLDocument& document,
                                           const std::string& link) {
  std::multimap<std::string, std::string> fixed_children;
  for (const tinyxml2::XMLElement* joint = document.RootElement()->FirstChildElement("joint");
       joint; joint = joint->NextSiblingElement("joint")) {
    const char* type = joint->Attribute("type");
    const tinyxml2::XMLElement* parent = joint->FirstChildElement("parent");
    const tinyxml2::XMLElement* child = joint->FirstChildElement("child");
    if (!type || is_moving(type) || !parent || !child || !parent->Attribute("link") ||
        !child->Attribute("link")) {
      continue;
    }
    fixed_children.emplace(parent->Attribute("link"), child->Attribute("link"));
  }
  std::vector<std::string> out;
  std::vector<std::string> pending{link};
  while (!pending.empty()) {
    const std::string next = pending.back();
    pending.pop_back();
    const auto [first, last] = fixed_children.equal_range(next);
    for (auto it = first; it != last; ++it) {
      out.push_back(it->second);
      pending.push_back(it->second);
    }
  }
  return out;
}

// The rotation of an inertial origin's rpy as the loader takes it: angles within the tolerance
// of a quarter turn snapped, then urdfdom's convention R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d rotation_of(const std::string& rpy_text, double tolerance) {
  std::istringstream in(rpy_text);
  std::array<double, 3> rpy{};
  for (double& angle : rpy) {
    if (!(in >> angle)) angle = 0;  // the structure check refused malformed rpy already
    if (const auto quarters = nearest_quarter_turn(angle, tolerance)) {
      angle = static_cast<double>(*quarters) * (std::numbers::pi / 2);
    }
  }
  return (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

tinyxml2::XMLElement* child_element(tinyxml2::XMLElement* parent, const char* name) {
  tinyxml2::XMLElement* child = parent->FirstChildElement(name);
  if (child == nullptr)
    child = parent->InsertEndChild(parent->GetDocument()->NewElement(name))->ToElement();
  return child;
}

// Writes the body parameters p (link frame) as the link's <inertial>: centre of mass c = h / m,
// inertia about it by the parallel-axis theorem J_c = J_O - m (|c|^2 1 - c c'), expressed in the
// inertial frame R: I = R' J_c R (the loader computes R I R' + m (|c|^2 1 - c c') back).
void write_inertial(tinyxml2::XMLElement* link, const Inertial& p, double tolerance) {
  tinyxml2::XMLElement* inertial = link->FirstChildElement("inertial");
  if (inertial == nullptr) {
    inertial = link->InsertFirstChild(link->GetDocument()->NewElement("inertial"))->ToElement();
  }
  tinyxml2::XMLElement* origin = child_element(inertial, "origin");
  const std::string rpy = origin->Attribute("rpy") ? origin->Attribute("rpy") : "0 0 0";
  const Eigen::Matrix3d R = rotation_of(rpy, tolerance);
  const double m = p[9];
  Eigen::Vector3d c = m > 0 ? Eigen::Vector3d(p.segment<3>(6) / m) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d J;
  J << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
  const Eigen::Matrix3d Jc =
      J - m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  Eigen::Matrix3d I = R.transpose() * Jc * R;
  // What is left of an exact zero after the subtractions above (1e-20 beside 0.01) is rounding:
  // written as 0, it changes the base parameters by far less than the fit's precision.
  const double inertia_scale = I.diagonal().cwiseAbs().maxCoeff();
  I = I.unaryExpr([&](double v) { return std::abs(v) < 1e-14 * inertia_scale ? 0.0 : v; });
  const double length_scale = c.cwiseAbs().maxCoeff();
  c = c.unaryExpr([&](double v) { return std::abs(v) < 1e-14 * length_scale ? 0.0 : v; });
  origin->SetAttribute("xyz",
                       (text_of(c.x()) + " " + text_of(c.y()) + " " + text_of(c.z())).c_str());
  origin->SetAttribute("rpy", rpy.c_str());
  child_element(inertial, "mass")->SetAttribute("value", text_of(m).c_str());
  tinyxml2::XMLElement* inertia = child_element(inertial, "inertia");
  const std::pair<const char*, double> entries[] = {{"ixx", I(0, 0)}, {"ixy", I(0, 1)},
                                                    {"ixz", I(0, 2)}, {"iyy", I(1, 1)},
                                                    {"iyz", I(1, 2)}, {"izz", I(2, 2)}};
  for (const auto& [name, value] : entries) inertia->SetAttribute(name, text_of(value).c_str());
}

// A physical body: all zero (massless), or a positive definite pseudo-inertia.
bool is_physical(const Inertial& p) {
  return p.cwiseAbs().maxCoeff() == 0 || log_cholesky_from_inertial(p.data()).has_value();
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "'" : ", '") + name + "'";
  return out;
}

// `text` in lines of at most `width` characters, broken at spaces.
std::vector<std::string> wrapped(const std::string& text, std::size_t width) {
  std::vector<std::string> lines{""};
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width)
      lines.emplace_back();
    lines.back() += (lines.back().empty() ? "" : " ") + word;
  }
  return lines;
}

// The comment at the top of <robot>: what export did and the drive parameters, which have no
// URDF element. "--" may not appear in an XML comment.
std::string comment_text(const RobotModel& description, const Eigen::VectorXd& standard,
                         const std::string& note) {
  std::string text = kCommentStart;
  std::istringstream paragraphs(note);  // each line of the note wrapped on its own
  for (std::string paragraph; std::getline(paragraphs, paragraph);) {
    for (const std::string& line : wrapped(paragraph, 84))
      text += (text == kCommentStart ? " " : "     ") + line + "\n";
  }
  std::string drives;
  for (std::size_t b = 0; b < description.tree.bodies.size(); ++b) {
    std::string line;
    for (std::size_t k = 0; k < description.tree.params.size(); ++k) {
      const StandardParam& param = description.tree.params[k];
      if (param.body != static_cast<int>(b) || inertial_slot(param.kind) >= 0) continue;
      line += (line.empty() ? "" : ", ") + param.name + " = " +
              text_of(standard[static_cast<Eigen::Index>(k)]);
    }
    if (!line.empty())
      drives += "       joint '" + description.joints[b].name + "': " + line + "\n";
  }
  if (!drives.empty()) {
    text +=
        "     Drive parameters have no URDF element; their identified values, for reference:\n" +
        drives;
  }
  for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) {
    text.replace(at, 2, "- -");
  }
  return text + "  ";
}

void replace_comment(tinyxml2::XMLDocument& document, const std::string& text) {
  tinyxml2::XMLElement* robot = document.RootElement();
  for (tinyxml2::XMLNode* node = robot->FirstChild(); node;) {
    tinyxml2::XMLNode* next = node->NextSibling();
    if (node->ToComment() && std::string(node->Value()).rfind(kCommentStart, 0) == 0) {
      robot->DeleteChild(node);
    }
    node = next;
  }
  robot->InsertFirstChild(document.NewComment(text.c_str()));
}

}  // namespace

UrdfExport identified_urdf(const std::string& path, const std::string& text,
                           const RobotModel& description, const Eigen::VectorXd& standard,
                           const LoadOptions& options, const std::string& note) {
  const RigidBodyTree& tree = description.tree;
  const auto indices = inertial_param_indices(tree);

  // The fixed links' share of each body, as the loader computes it: the same URDF loaded with
  // the moving links' inertials taken out.
  tinyxml2::XMLDocument stripped;
  parse(stripped, text);
  {
    const auto links = links_by_name(stripped);
    for (const Body& body : tree.bodies) {
      tinyxml2::XMLElement* link = links.at(body.name);
      if (tinyxml2::XMLElement* inertial = link->FirstChildElement("inertial")) {
        link->DeleteChild(inertial);
      }
    }
  }
  const RobotModel fixed_share = load_urdf(path, printed(stripped), options);

  UrdfExport out;
  tinyxml2::XMLDocument document;
  parse(document, text);
  const auto links = links_by_name(document);
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    Inertial identified, fixed;
    for (int slot = 0; slot < kInertialParams; ++slot) {
      const int k = indices[b][static_cast<std::size_t>(slot)];
      if (k < 0)
        throw std::logic_error("export: body '" + tree.bodies[b].name + "' lacks a parameter");
      identified[slot] = standard[k];
      fixed[slot] = fixed_share.known_values[static_cast<std::size_t>(k)].value_or(0.0);
    }
    tinyxml2::XMLElement* link = links.at(tree.bodies[b].name);
    const Inertial own = identified - fixed;
    if (fixed.cwiseAbs().maxCoeff() == 0 || is_physical(own)) {
      write_inertial(link, own, options.angle_tolerance);
      continue;
    }
    // The fixed links were thought heavier (or otherwise shaped) than the data allow: the
    // moving link carries the whole identified body, and nothing is counted twice.
    std::vector<std::string> removed;
    for (const std::string& name : fixed_links_below(document, tree.bodies[b].name)) {
      tinyxml2::XMLElement* fixed_link = links.at(name);
      if (tinyxml2::XMLElement* inertial = fixed_link->FirstChildElement("inertial")) {
        fixed_link->DeleteChild(inertial);
        removed.push_back(name);
      }
    }
    write_inertial(link, identified, options.angle_tolerance);
    out.warnings.push_back(
        path + ":" + std::to_string(link->GetLineNum()) + ": warning: link '" +
        tree.bodies[b].name + "': the identified body (" + text_of(identified[9]) +
        " kg) less the a-priori inertials of the links fixed to it (" + text_of(fixed[9]) +
        " kg) is no physical body; '" + tree.bodies[b].name +
        "' takes the whole body, and the <inertial>" + (removed.size() > 1 ? "s of " : " of ") +
        joined(removed) + (removed.size() > 1 ? " are removed" : " is removed"));
  }
  replace_comment(document, comment_text(description, standard, note));
  out.text = printed(document);
  return out;
}

}  // namespace modelgen
