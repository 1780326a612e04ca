// The truth of `simulate --drive` from a drive-parameter file, the load added to the payload link
// as MlProblem::drive_parameters does (runtime/src/ml/problem_impl.hpp), and the drive model's
// motor torques.

#include "runtime/cli/simulate/drive_simulation.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <vector>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/io/drive_parameter_file.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/data/drive_parameter_checks.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// "XX12" -> "12": the link or motor number a parameter name ends with.
std::string number_of(const std::string& name) {
  const std::size_t digits = name.find_last_not_of("0123456789") + 1;
  return name.substr(digits);
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

// The defaults taken, compactly: inertial parameters counted per link, drive and load
// parameters by name (grouped by kind), efficiencies taken as 1 apart, a missing load in two
// words.
std::string defaulted_note(const std::string& path, const std::vector<std::string>& names,
                           const std::vector<bool>& given, int inertial, bool load_given) {
  // Links in order of first appearance (the standard order), with missing and total counts.
  std::vector<std::string> links;
  std::map<std::string, std::pair<int, int>> counts;
  std::map<std::string, std::vector<std::string>> by_kind;  // "JM", "Rv", "Rc", "load_"
  std::vector<std::string> one_names;
  int missing_inertial = 0;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const bool is_inertial = static_cast<int>(k) < inertial;
    const bool is_load = static_cast<int>(k) >= static_cast<int>(names.size()) - kLoadParams;
    if (is_inertial) {
      const std::string link = number_of(names[k]);
      if (!counts.count(link)) links.push_back(link);
      ++counts[link].second;
      if (!given[k]) ++counts[link].first, ++missing_inertial;
    } else if (given[k] || (is_load && !load_given)) {
      continue;
    } else if (names[k].compare(0, 2, "Rz") == 0) {
      one_names.push_back(names[k]);
    } else {
      by_kind[is_load ? "load_" : names[k].substr(0, 2)].push_back(names[k]);
    }
  }
  std::vector<std::string> zero;
  if (missing_inertial > 0) {
    std::vector<std::string> whole, partial;
    for (const std::string& link : links) {
      const auto [missing, total] = counts[link];
      if (missing == total) whole.push_back(link);
      if (missing > 0 && missing < total) {
        partial.push_back(std::to_string(missing) + " of link " + link);
      }
    }
    if (!whole.empty()) {
      partial.insert(
          partial.begin(),
          std::string(whole.size() == 1 ? "all of link " : "all of links ") + joined(whole, " "));
    }
    zero.push_back(std::to_string(missing_inertial) + " inertial parameters (" +
                   joined(partial, ", ") + ")");
  }
  for (const char* kind : {"JM", "Rv", "Rc", "load_"}) {
    if (by_kind.count(kind)) zero.push_back(joined(by_kind[kind], " "));
  }
  std::vector<std::string> parts;
  if (!zero.empty()) parts.push_back("0 for " + joined(zero, ", "));
  if (!one_names.empty()) parts.push_back("1 for " + joined(one_names, " "));
  if (!load_given) parts.push_back("no load");
  return parts.empty() ? "" : "not in " + path + ": " + joined(parts, "; ");
}

}  // namespace

DriveTruth read_drive_truth(const std::string& path, const modelgen::RobotModel& description,
                            const DriveModel& model) {
  const std::vector<std::string> names = ml_param_names(model);
  const std::map<std::string, double> values = read_drive_parameter_values(path, names);
  // A simulation of a robot that cannot exist would make data no robot gives.
  const std::vector<std::string> violations = drive_parameter_violations(values, description.tree);
  if (!violations.empty()) {
    std::string list;
    for (const std::string& v : violations) list += (list.empty() ? "" : "; ") + v;
    throw std::runtime_error(path + ": error: these values cannot be those of a physical robot: " +
                             list);
  }
  const int P = model.num_params();
  const int inertial = P - kDriveParamsPerMotor * model.dof();

  Eigen::VectorXd all(static_cast<Eigen::Index>(names.size()));
  std::vector<bool> given(names.size(), false);
  bool load_given = false;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto found = values.find(names[k]);
    const bool is_rz = names[k].compare(0, 2, "Rz") == 0 && static_cast<int>(k) >= inertial &&
                       static_cast<int>(k) < P;
    given[k] = found != values.end();
    all[static_cast<Eigen::Index>(k)] = given[k] ? found->second : (is_rz ? 1.0 : 0.0);
    if (given[k] && static_cast<int>(k) >= P) load_given = true;
    // Eq. 8 divides by R_z: an efficiency is a positive factor.
    if (is_rz && given[k] && !(found->second > 0)) {
      throw std::runtime_error(path + ": error: '" + names[k] +
                               "' is an efficiency and must be positive, not " +
                               shortest(found->second));
    }
  }

  DriveTruth truth;
  truth.theta = all.head(P);
  truth.note = defaulted_note(path, names, given, inertial, load_given);
  if (!load_given) return truth;
  if (description.payload_body < 0) {
    throw std::runtime_error(path + ": error: a load is given but " + description.source_file +
                             " names no payload link (add 'payload: {link: N}')");
  }
  const LoadParameters load = LoadParameters::from_vector(all.data() + P);
  const std::vector<std::string> warnings = physical_consistency_warnings(load);
  if (!warnings.empty()) {
    throw std::runtime_error(
        path + ": error: the load is not physically consistent: " + joined(warnings, "; "));
  }
  // The load is part of the payload link (Swevers section 2): its standard parameters add to
  // the link's own XXj .. Mj.
  const std::string link = std::to_string(description.payload_body + 1);
  const std::array<double, 10> standard = standard_from_load(load);
  const char* stems[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
  for (int m = 0; m < 10; ++m) {
    const auto at = std::find(names.begin(), names.begin() + inertial, stems[m] + link);
    if (at == names.begin() + inertial) {
      throw std::runtime_error(path + ": error: the payload link " + link + " of " +
                               description.source_file + " has no parameter '" + stems[m] + link +
                               "'");
    }
    truth.theta[at - names.begin()] += standard[m];
  }
  return truth;
}

Eigen::MatrixXd motor_torques(DriveModel& model, const Trajectory& x, const Eigen::VectorXd& theta,
                              Progress& progress) {
  // Blocks bound one at a time: the reference model stores a regressor per bound sample.
  constexpr Eigen::Index kBlock = 1024;
  const Eigen::Index samples = x.t.size();
  Eigen::MatrixXd tau_M(samples, model.dof());
  Eigen::VectorXd row(model.dof());
  for (Eigen::Index begin = 0; begin < samples; begin += kBlock) {
    progress.update(begin);
    const Eigen::Index n = std::min(kBlock, samples - begin);
    model.set_samples(x.q.middleRows(begin, n), x.dq.middleRows(begin, n),
                      x.ddq.middleRows(begin, n));
    for (Eigen::Index s = 0; s < n; ++s) {
      model.torque(s, theta.data(), row.data());
      tau_M.row(begin + s) = row.transpose();
    }
  }
  return tau_M;
}

}  // namespace modelgen::internal
