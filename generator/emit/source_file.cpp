// The sources: NAME.cpp with the name tables and the drive chain as number literals of the first
// scalar type; NAME_<function>.cpp with one entry point's definition per scalar type, so that a
// build compiles the functions in parallel and a firmware links only the files it calls (no
// section garbage collection needed). An input array a body never reads is marked unused, so
// the code compiles warning-free with -Wextra.

#include "generator/emit/source_file.hpp"

#include <cctype>

#include "generator/emit/banner.hpp"
#include "generator/emit/code_list.hpp"
#include "generator/emit/identified_constants.hpp"
#include "generator/emit/printer.hpp"
#include "generator/emit/prototype.hpp"

namespace modelgen::gen {

namespace {

bool uses_array(const FunctionBody& body, const std::string& array) {
  // A body uses an input array when some statement reads array[...] or passes it to a call
  // ("(q," or " q)"); trailing comments, which may name inputs (the columns of a Jacobian), do
  // not count.
  for (const std::string& full_line : body.lines) {
    const std::string line = full_line.substr(0, full_line.find("//"));
    for (std::size_t at = line.find(array); at != std::string::npos;
         at = line.find(array, at + 1)) {
      const bool inside_name =
          at > 0 && (std::isalnum(static_cast<unsigned char>(line[at - 1])) || line[at - 1] == '_');
      if (inside_name) continue;
      const std::size_t end = at + array.size();
      if (end < line.size() && (line[end] == '[' || line[end] == ',' || line[end] == ')')) {
        return true;
      }
    }
  }
  return false;
}

std::string definition(const EmittedFunction& function, std::size_t s, Scalar scalar) {
  const FunctionBody& body = function.bodies[s];
  return Printer(embedded_template("function_definition"))
      .set("signature", function_prototype(function, scalar, true))
      .set_block(
          "unused",
          [&](CodeWriter& out) {
            for (const std::string& array : function.inputs) {
              if (uses_array(body, array)) continue;
              out.line(without_final_newline(
                  Printer(embedded_template("unused_parameter")).set("parameter", array).render()));
            }
          })
      .set_block("body",
                 [&](CodeWriter& out) {
                   for (const std::string& line : body.lines) out.line(line);
                 })
      .render();
}


bool calls_std(const EmittedFunction& function) {
  for (const FunctionBody& body : function.bodies) {
    for (const std::string& line : body.lines) {
      if (line.find("std::") != std::string::npos) return true;
    }
  }
  return false;
}

std::vector<double> as_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

void write_matrix_rows(const Eigen::MatrixXd& matrix, Scalar scalar, CodeWriter& out) {
  // One row per line, so the matrix reads as written.
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) {
    std::vector<double> row(matrix.cols());
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) row[c] = matrix(r, c);
    write_number_list(row, scalar, out);
  }
}

}  // namespace

std::string render_source(const RenderInput& in) {
  std::vector<std::string> standard_names, base_names;
  for (const StandardParam& p : in.model.tree.params) standard_names.push_back(p.name);
  for (const BaseParameter& b : in.base.params) base_names.push_back(b.name);
  const DriveChain& drives = in.model.drives;
  // The drive-chain constants take the first scalar type asked for.
  const Scalar scalar = in.input.scalars.front();
  return Printer(embedded_template("model.cpp"))
      .set("banner", render_banner(in.source_name(), in))
      .set("header", in.header_name())
      .set("robot", in.model.name)
      .set("scalar", scalar_name(scalar))
      .set_block("standard_param_names",
                 [&](CodeWriter& out) { write_name_list(standard_names, out); })
      .set_block("base_param_names", [&](CodeWriter& out) { write_name_list(base_names, out); })
      .set_block("drive_param_names",
                 [&](CodeWriter& out) { write_name_list(in.drive_param_names, out); })
      .set_block("drive_regressor_index",
                 [&](CodeWriter& out) {
                   std::vector<std::string> items;
                   for (int k : in.drive_regressor_index) items.push_back(std::to_string(k));
                   write_list(items, out);
                 })
      .set_block("motor_from_joint",
                 [&](CodeWriter& out) { write_matrix_rows(drives.motor_from_joint, scalar, out); })
      .set_block("torque_constant",
                 [&](CodeWriter& out) {
                   write_number_list(as_vector(drives.torque_constant), scalar, out);
                 })
      .set_block(
          "joint_offset",
          [&](CodeWriter& out) { write_number_list(as_vector(drives.joint_offset), scalar, out); })
      .set_block("identified_definitions",
                 [&](CodeWriter& out) { write_identified_definitions(in, out); })
      .render();
}

std::string render_function_source(const RenderInput& in, const EmittedFunction& function) {
  const std::string file = in.function_source_name(function.name);
  return Printer(embedded_template("function.cpp"))
      .set("banner", render_banner(file, in, std::span<const EmittedFunction>(&function, 1)))
      .set("header", in.header_name())
      .set("robot", in.model.name)
      .set_block("includes",
                 [&](CodeWriter& out) {
                   // <cmath> only where a body calls std::sin or std::cos: parsing it is a
                   // third of the compile time of a small function's file.
                   if (calls_std(function)) {
                     out.blank();
                     out.line("#include <cmath>");
                   }
                 })
      .set_block("definitions",
                 [&](CodeWriter& out) {
                   for (std::size_t s = 0; s < in.input.scalars.size(); ++s) {
                     if (s > 0) out.blank();
                     out.lines_of(definition(function, s, in.input.scalars[s]));
                   }
                 })
      .render();
}

}  // namespace modelgen::gen
