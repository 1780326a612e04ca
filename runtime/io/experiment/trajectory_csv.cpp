// CSV trajectories: header-driven column lookup, every field checked, errors positioned.

#include "modelgen/io/experiment/trajectory_csv.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "modelgen/io/experiment/plausible_magnitude.hpp"
#include "modelgen/model/number_text.hpp"

namespace modelgen::io {

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

// Fails unless the file is within modelid's size limit (checked before reading it).
void check_file_size(const std::string& path) {
  std::error_code size_error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, size_error);
  if (!size_error && bytes > kMaxDataFileBytes) {
    fail(path, 0, "",
         "the file has " + std::to_string(bytes >> 20) + " MiB, above modelid's limit of " +
             std::to_string(kMaxDataFileBytes >> 20) +
             " MiB per data file: split it into several experiments");
  }
}

// One read of a trajectory CSV: the header, the columns it names, the rows, then the checks
// that need all rows.
class TrajectoryCsvReader {
 public:
  TrajectoryCsvReader(const std::string& path, int dof, EffortColumns effort, std::istream& in)
      : path_(path), dof_(dof), effort_(effort), in_(in) {}

  Trajectory read() {
    read_header();
    find_columns();
    check_references_complete();
    check_derivatives_complete();
    read_rows();
    if (rows_.size() < 3) fail(path_, line_number_, "", "fewer than 3 samples");
    check_time_steps();
    if (effort_ == EffortColumns::kRequired) check_some_effort();
    return trajectory();
  }

 private:
  // The first line that is not blank.
  void read_header() {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      if (line.find_first_not_of(" \t\r") != std::string::npos) break;
    }
    header_ = split(line);
    for (std::size_t c = 0; c < header_.size(); ++c) {
      const auto [at, added] = column_.emplace(header_[c], static_cast<int>(c));
      // Which of two same-named columns is meant cannot be known.
      if (!added && !header_[c].empty()) {
        fail(path_, line_number_, header_[c],
             "column '" + header_[c] + "' appears twice in the header (fields " +
                 std::to_string(at->second + 1) + " and " + std::to_string(c + 1) + ")");
      }
    }
  }

  int find(const std::string& name, bool required) const {
    auto found = column_.find(name);
    if (found != column_.end()) return found->second;
    if (required) {
      std::string present;
      for (const std::string& h : header_) present += (present.empty() ? "" : ", ") + h;
      fail(path_, line_number_, name,
           "missing column '" + name + "' (the header has: " + present + "); expected t, q1..q" +
               std::to_string(dof_) + ", tau1..tau" + std::to_string(dof_) +
               " (or motor currents i1..i" + std::to_string(dof_) +
               ") and optionally dq1.., ddq1..");
    }
    return -1;
  }

  void find_columns() {
    t_column_ = find("t", true);
    // Torques or currents: decided by the first joint's column, then required for every joint.
    if (column_.count("tau1") && column_.count("i1")) {
      fail(path_, line_number_, "i1", "both torque (tau) and current (i) columns: give one kind");
    }
    if (column_.count("i1")) {
      measured_ = Measured::kCurrent;
    } else if (!column_.count("tau1") && effort_ == EffortColumns::kOptional) {
      measured_ = Measured::kNothing;
    }
    effort_prefix_ = measured_ == Measured::kCurrent ? "i" : "tau";
    q_.assign(dof_, 0);
    tau_.assign(dof_, -1);
    dq_.assign(dof_, 0);
    ddq_.assign(dof_, 0);
    qr_.assign(dof_, 0);
    for (int j = 0; j < dof_; ++j) {
      const std::string k = std::to_string(j + 1);
      q_[j] = find("q" + k, true);
      if (measured_ != Measured::kNothing) tau_[j] = find(effort_prefix_ + k, true);
      dq_[j] = find("dq" + k, false);
      ddq_[j] = find("ddq" + k, false);
      qr_[j] = find("qr" + k, false);
      reference_ = reference_ && qr_[j] >= 0;
      any_reference_ = any_reference_ || qr_[j] >= 0;
      velocity_ = velocity_ && dq_[j] >= 0 && ddq_[j] >= 0;
      any_derivative_ = any_derivative_ || dq_[j] >= 0 || ddq_[j] >= 0;
    }
  }

  // A closed-loop method given the references of some joints only would take the others' as 0.
  void check_references_complete() const {
    if (!any_reference_ || reference_) return;
    for (int j = 0; j < dof_; ++j) {
      if (qr_[j] < 0) {
        fail(path_, line_number_, "qr" + std::to_string(j + 1),
             "missing column 'qr" + std::to_string(j + 1) +
                 "': reference positions are given for "
                 "some joints, give qr1..qr" +
                 std::to_string(dof_) + " or none");
      }
    }
  }

  // Velocities without accelerations (or some axes only) would be silently ignored, the
  // derivatives all taken from the positions: refused, so that the user chooses.
  void check_derivatives_complete() const {
    if (!any_derivative_ || velocity_) return;
    for (int j = 0; j < dof_; ++j) {
      const std::string k = std::to_string(j + 1);
      for (const auto& [name, index] :
           {std::pair{"dq" + k, dq_[j]}, std::pair{"ddq" + k, ddq_[j]}}) {
        if (index >= 0) continue;
        fail(path_, line_number_, name,
             "missing column '" + name + "': velocities and accelerations are used together, " +
                 "dq1..dq" + std::to_string(dof_) + " and ddq1..ddq" + std::to_string(dof_) +
                 "; give all of them, or none (then both come from the positions)");
      }
    }
  }

  // The fields of one data line as numbers, every one checked.
  std::vector<double> parse_row(const std::string& line) const {
    const std::vector<std::string> fields = split(line);
    if (fields.size() != header_.size()) {
      fail(path_, line_number_, "",
           "expected " + std::to_string(header_.size()) + " fields like the header, found " +
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
        fail(path_, line_number_, header_[c], "'" + text + "' is not a number");
      }
      if (!std::isfinite(value)) fail(path_, line_number_, header_[c], "value is NaN or infinite");
      if (const auto p = plausible_magnitude(header_[c]); p && std::abs(value) > p->bound) {
        fail(path_, line_number_, header_[c],
             "value " + text + " is beyond any robot (|" + p->kind + "| up to " + brief(p->bound) +
                 " " + p->unit + "): a unit or column slip?");
      }
      values[c] = value;
    }
    return values;
  }

  void read_rows() {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      std::vector<double> values = parse_row(line);
      if (!rows_.empty() && !(values[t_column_] > rows_.back()[t_column_])) {
        fail(path_, line_number_, "t",
             "time does not increase (" + format(values[t_column_]) + " after " +
                 format(rows_.back()[t_column_]) + ")");
      }
      if (rows_.size() == kMaxDataRows) {
        fail(path_, line_number_, "",
             "more than " + std::to_string(kMaxDataRows) +
                 " samples, modelid's limit per data file (the regressor of one sample takes "
                 "about 3 KB for six axes): split the file into several experiments or decimate "
                 "it first");
      }
      rows_.push_back(std::move(values));
      row_line_.push_back(line_number_);
    }
  }

  // Holes in the time stamps, against the median step.
  void check_time_steps() const {
    std::vector<double> steps(rows_.size() - 1);
    for (std::size_t s = 0; s + 1 < rows_.size(); ++s) {
      steps[s] = rows_[s + 1][t_column_] - rows_[s][t_column_];
    }
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t s = 0; s < steps.size(); ++s) {
      if (steps[s] > kMaxGapSteps * median) {
        fail(path_, row_line_[s + 1], "t",
             "time jumps from " + brief(rows_[s][t_column_]) + " s (line " +
                 std::to_string(row_line_[s]) + ") to " + brief(rows_[s + 1][t_column_]) + " s, " +
                 brief(std::round(steps[s] / median)) + " sample times (median " + brief(median) +
                 " s); a hole longer than " + brief(kMaxGapSteps) +
                 " sample times is not filled with invented samples: split the file at the "
                 "hole into two experiments (--data A --data B)");
      }
    }
  }

  void check_some_effort() const {
    bool any_effort = false;
    for (const std::vector<double>& row : rows_) {
      for (int j = 0; j < dof_; ++j) any_effort = any_effort || row[tau_[j]] != 0;
    }
    if (!any_effort) {
      fail(path_, 0, "",
           "every " + std::string(measured_ == Measured::kCurrent ? "current" : "torque") + " (" +
               effort_prefix_ + "1.." + effort_prefix_ + std::to_string(dof_) +
               ") is zero: there is nothing to identify from");
    }
  }

  Trajectory trajectory() const {
    Trajectory out;
    out.source = path_;
    const Eigen::Index n = static_cast<Eigen::Index>(rows_.size());
    out.t.resize(n);
    out.q.resize(n, dof_);
    out.tau = Eigen::MatrixXd::Zero(n, dof_);
    out.measured = measured_;
    out.dq = Eigen::MatrixXd::Zero(n, dof_);
    out.ddq = Eigen::MatrixXd::Zero(n, dof_);
    out.has_velocity = velocity_;
    if (reference_) out.qr.resize(n, dof_);
    for (Eigen::Index s = 0; s < n; ++s) {
      out.t[s] = rows_[s][t_column_];
      for (int j = 0; j < dof_; ++j) {
        out.q(s, j) = rows_[s][q_[j]];
        if (tau_[j] >= 0) out.tau(s, j) = rows_[s][tau_[j]];
        if (reference_) out.qr(s, j) = rows_[s][qr_[j]];
        if (velocity_) {
          out.dq(s, j) = rows_[s][dq_[j]];
          out.ddq(s, j) = rows_[s][ddq_[j]];
        }
      }
    }
    return out;
  }

  const std::string& path_;
  const int dof_;
  const EffortColumns effort_;
  std::istream& in_;
  int line_number_ = 0;
  std::vector<std::string> header_;
  std::map<std::string, int> column_;
  // The column of each quantity per joint; -1 where absent.
  int t_column_ = -1;
  std::vector<int> q_, tau_, dq_, ddq_, qr_;
  Measured measured_ = Measured::kTorque;
  std::string effort_prefix_;
  bool velocity_ = true, any_derivative_ = false, reference_ = true, any_reference_ = false;
  std::vector<std::vector<double>> rows_;
  std::vector<int> row_line_;  // the line of each row, for messages about time steps
};

}  // namespace

Trajectory read_trajectory_csv(const std::string& path, int dof, EffortColumns effort) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "", "cannot open the file");
  check_file_size(path);
  return TrajectoryCsvReader(path, dof, effort, in).read();
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

// Revolute or prismatic alike: 1e4 rad is 1 600 turns, 1e4 rad/s 95 000 rpm at the joint (a dq
// of 1.2e29 once made W rank-deficient with no word of where).
std::optional<PlausibleMagnitude> plausible_magnitude(const std::string& column) {
  static constexpr PlausibleMagnitude kPlausible[] = {
      {"ddq", 1e7, "rad/s^2 or m/s^2"}, {"dq", 1e4, "rad/s or m/s"}, {"qr", 1e4, "rad or m"},
      {"q", 1e4, "rad or m"},           {"tau", 1e9, "N m or N"},    {"i", 1e6, "A"}};
  for (const PlausibleMagnitude& p : kPlausible) {
    const std::string prefix = p.kind;
    if (column.size() > prefix.size() && column.compare(0, prefix.size(), prefix) == 0 &&
        column.find_first_not_of("0123456789", prefix.size()) == std::string::npos) {
      return p;
    }
  }
  return std::nullopt;
}

}  // namespace modelgen::io
