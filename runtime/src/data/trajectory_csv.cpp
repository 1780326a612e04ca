// CSV trajectories: header-driven column lookup, every field checked, errors positioned.

#include "modelgen/data/trajectory_csv.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "modelgen/model/number_text.hpp"

namespace modelgen {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& column,
                       const std::string& message) {
  std::string where = path;
  if (line > 0) where += ":" + std::to_string(line);
  if (!column.empty()) where += " (column " + column + ")";
  throw DataError(SourceLocation{path, line, 0, column}, where + ": error: " + message);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) {
    const std::size_t first = field.find_first_not_of(" \t\r");
    const std::size_t last = field.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
  }
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

std::string format(double value) { return shortest_text(value); }

// Six significant digits: time stamps and steps in messages.
std::string brief(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// The longest step between two time stamps, in median sample times, that resampling may fill:
// a longer hole would be filled with invented samples (a 90 s hole at 10 ms gave 9 000), and
// a time stamp far off (1e9 s) with a uniform grid too large for memory.
constexpr double kMaxGapSteps = 100;

}  // namespace

Trajectory read_trajectory_csv(const std::string& path, int dof, EffortColumns effort) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "", "cannot open the file");
  std::error_code size_error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, size_error);
  if (!size_error && bytes > kMaxDataFileBytes) {
    fail(path, 0, "",
         "the file has " + std::to_string(bytes >> 20) + " MiB, above modelid's limit of " +
             std::to_string(kMaxDataFileBytes >> 20) +
             " MiB per data file: split it into several experiments");
  }
  std::string line;
  int line_number = 0;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") != std::string::npos) break;
  }
  header = split(line);
  std::map<std::string, int> column;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto [at, added] = column.emplace(header[c], static_cast<int>(c));
    // Which of two same-named columns is meant cannot be known.
    if (!added && !header[c].empty()) {
      fail(path, line_number, header[c],
           "column '" + header[c] + "' appears twice in the header (fields " +
               std::to_string(at->second + 1) + " and " + std::to_string(c + 1) + ")");
    }
  }
  auto find = [&](const std::string& name, bool required) {
    auto found = column.find(name);
    if (found != column.end()) return found->second;
    if (required) {
      std::string present;
      for (const std::string& h : header) present += (present.empty() ? "" : ", ") + h;
      fail(path, line_number, name,
           "missing column '" + name + "' (the header has: " + present + "); expected t, q1..q" +
               std::to_string(dof) + ", tau1..tau" + std::to_string(dof) +
               " (or motor currents i1..i" + std::to_string(dof) +
               ") and optionally dq1.., ddq1..");
    }
    return -1;
  };
  const int t_column = find("t", true);
  // Torques or currents: decided by the first joint's column, then required for every joint.
  Measured measured = Measured::kTorque;
  if (column.count("tau1") && column.count("i1")) {
    fail(path, line_number, "i1", "both torque (tau) and current (i) columns: give one kind");
  }
  if (column.count("i1")) {
    measured = Measured::kCurrent;
  } else if (!column.count("tau1") && effort == EffortColumns::kOptional) {
    measured = Measured::kNothing;
  }
  const std::string effort_prefix = measured == Measured::kCurrent ? "i" : "tau";
  std::vector<int> q(dof), tau(dof, -1), dq(dof), ddq(dof), qr(dof);
  bool velocity = true, any_derivative = false, reference = true, any_reference = false;
  for (int j = 0; j < dof; ++j) {
    const std::string k = std::to_string(j + 1);
    q[j] = find("q" + k, true);
    if (measured != Measured::kNothing) tau[j] = find(effort_prefix + k, true);
    dq[j] = find("dq" + k, false);
    ddq[j] = find("ddq" + k, false);
    qr[j] = find("qr" + k, false);
    reference = reference && qr[j] >= 0;
    any_reference = any_reference || qr[j] >= 0;
    velocity = velocity && dq[j] >= 0 && ddq[j] >= 0;
    any_derivative = any_derivative || dq[j] >= 0 || ddq[j] >= 0;
  }
  // A closed-loop method given the references of some joints only would take the others' as 0.
  if (any_reference && !reference) {
    for (int j = 0; j < dof; ++j) {
      if (qr[j] < 0) {
        fail(path, line_number, "qr" + std::to_string(j + 1),
             "missing column 'qr" + std::to_string(j + 1) + "': reference positions are given for "
             "some joints, give qr1..qr" + std::to_string(dof) + " or none");
      }
    }
  }
  // Velocities without accelerations (or some axes only) would be silently ignored, the
  // derivatives all taken from the positions: refused, so that the user chooses.
  if (any_derivative && !velocity) {
    for (int j = 0; j < dof; ++j) {
      const std::string k = std::to_string(j + 1);
      for (const auto& [name, index] : {std::pair{"dq" + k, dq[j]}, std::pair{"ddq" + k, ddq[j]}}) {
        if (index >= 0) continue;
        fail(path, line_number, name,
             "missing column '" + name + "': velocities and accelerations are used together, " +
                 "dq1..dq" + std::to_string(dof) + " and ddq1..ddq" + std::to_string(dof) +
                 "; give all of them, or none (then both come from the positions)");
      }
    }
  }

  std::vector<std::vector<double>> rows;
  std::vector<int> row_line;  // the line of each row, for messages about time steps
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = split(line);
    if (fields.size() != header.size()) {
      fail(path, line_number, "",
           "expected " + std::to_string(header.size()) + " fields like the header, found " +
               std::to_string(fields.size()));
    }
    std::vector<double> values(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string& text = fields[c];
      double value = 0;
      const char* first = text.data();
      if (!text.empty() && *first == '+') ++first;
      auto [end, ec] = std::from_chars(first, text.data() + text.size(), value);
      if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
        fail(path, line_number, header[c], "'" + text + "' is not a number");
      }
      if (!std::isfinite(value)) fail(path, line_number, header[c], "value is NaN or infinite");
      values[c] = value;
    }
    if (!rows.empty() && !(values[t_column] > rows.back()[t_column])) {
      fail(path, line_number, "t",
           "time does not increase (" + format(values[t_column]) + " after " +
               format(rows.back()[t_column]) + ")");
    }
    if (rows.size() == kMaxDataRows) {
      fail(path, line_number, "",
           "more than " + std::to_string(kMaxDataRows) +
               " samples, modelid's limit per data file (the regressor of one sample takes "
               "about 3 KB for six axes): split the file into several experiments or decimate "
               "it first");
    }
    rows.push_back(std::move(values));
    row_line.push_back(line_number);
  }
  if (rows.size() < 3) fail(path, line_number, "", "fewer than 3 samples");
  // Holes in the time stamps, against the median step.
  std::vector<double> steps(rows.size() - 1);
  for (std::size_t s = 0; s + 1 < rows.size(); ++s) {
    steps[s] = rows[s + 1][t_column] - rows[s][t_column];
  }
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  for (std::size_t s = 0; s < steps.size(); ++s) {
    if (steps[s] > kMaxGapSteps * median) {
      fail(path, row_line[s + 1], "t",
           "time jumps from " + brief(rows[s][t_column]) + " s (line " +
               std::to_string(row_line[s]) + ") to " + brief(rows[s + 1][t_column]) +
               " s, " + brief(std::round(steps[s] / median)) +
               " sample times (median " + brief(median) + " s); a hole longer than " +
               brief(kMaxGapSteps) +
               " sample times is not filled with invented samples: split the file at the "
               "hole into two experiments (--data A --data B)");
    }
  }
  if (effort == EffortColumns::kRequired) {
    bool any_effort = false;
    for (const std::vector<double>& row : rows) {
      for (int j = 0; j < dof; ++j) any_effort = any_effort || row[tau[j]] != 0;
    }
    if (!any_effort) {
      fail(path, 0, "", "every " +
                            std::string(measured == Measured::kCurrent ? "current" : "torque") +
                            " (" + effort_prefix + "1.." + effort_prefix + std::to_string(dof) +
                            ") is zero: there is nothing to identify from");
    }
  }

  Trajectory out;
  out.source = path;
  const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
  out.t.resize(n);
  out.q.resize(n, dof);
  out.tau = Eigen::MatrixXd::Zero(n, dof);
  out.measured = measured;
  out.dq = Eigen::MatrixXd::Zero(n, dof);
  out.ddq = Eigen::MatrixXd::Zero(n, dof);
  out.has_velocity = velocity;
  if (reference) out.qr.resize(n, dof);
  for (Eigen::Index s = 0; s < n; ++s) {
    out.t[s] = rows[s][t_column];
    for (int j = 0; j < dof; ++j) {
      out.q(s, j) = rows[s][q[j]];
      if (tau[j] >= 0) out.tau(s, j) = rows[s][tau[j]];
      if (reference) out.qr(s, j) = rows[s][qr[j]];
      if (velocity) {
        out.dq(s, j) = rows[s][dq[j]];
        out.ddq(s, j) = rows[s][ddq[j]];
      }
    }
  }
  return out;
}

void write_trajectory_csv(const std::string& path, const Trajectory& x) {
  // Written beside the destination and renamed at the end: never a half-written file.
  const std::string temporary = path + ".tmp-modelid";
  // The stream keeps errno of the call that failed: the message gives the system's reason.
  auto failed = [&path](int error) {
    return DataError(SourceLocation{path}, path + ": error: cannot write the file: " +
                                               (error != 0 ? std::strerror(error) : "write failed") +
                                               " (no file was changed)");
  };
  errno = 0;
  std::ofstream out(temporary);
  if (!out) throw failed(errno);
  const Eigen::Index dof = x.q.cols();
  std::vector<std::pair<const char*, const Eigen::MatrixXd*>> columns = {{"q", &x.q}};
  if (x.has_velocity) columns.insert(columns.end(), {{"dq", &x.dq}, {"ddq", &x.ddq}});
  columns.push_back({"tau", &x.tau});
  if (x.qr.size() != 0) columns.push_back({"qr", &x.qr});
  out << "t";
  for (const auto& [prefix, m] : columns) {
    for (Eigen::Index j = 0; j < dof; ++j) out << "," << prefix << j + 1;
  }
  out << "\n";
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    out << format(x.t[s]);
    for (const auto& [prefix, m] : columns) {
      for (Eigen::Index j = 0; j < dof; ++j) out << "," << format((*m)(s, j));
    }
    out << "\n";
  }
  out.close();
  const int write_error = out ? 0 : (errno != 0 ? errno : -1);
  if (write_error != 0 || std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = write_error != 0 ? std::max(write_error, 0) : errno;
    std::remove(temporary.c_str());
    throw failed(error);
  }
}

}  // namespace modelgen
