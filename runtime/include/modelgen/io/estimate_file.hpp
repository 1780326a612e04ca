// The estimate file of modelid (EST.json): what `fit -o` writes, and the check that an
// estimate given to `predict` belongs to the model it is used with. The parameter values are
// read back by read_base_parameters (runtime/cli/parameter_file.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::io {

struct EstimatedParameter {
  std::string name;             ///< base parameter name, e.g. "ZZ1R"
  double value = 0;             ///< SI units of the parameter (kg m^2, kg m, kg, N m s/rad, ...)
  double std_dev = 0;           ///< standard deviation, same unit (Gautier & Briot eq. 18)
  double rel_std_dev = 0;       ///< in %, +inf for a zero estimate (written as null)
  std::optional<double> truth;  ///< from fit --truth
};

/// The essential parameters (Gautier & Briot, iterative elimination with ratio r_sigma).
struct EssentialEstimate {
  double r_sigma = 0;
  std::vector<std::string> kept;               ///< in base parameter order
  std::vector<std::string> eliminated;         ///< in elimination order
  std::vector<EstimatedParameter> parameters;  ///< the kept ones, re-estimated
  double rel_error_norm = 0;                   ///< of the fitted equations
  double condition_number = 0;
};

/// A body's mass distribution for people: mass, centre of mass and inertia about it, in the
/// body frame (SI units), beside the description's a-priori values, and who decided each
/// (modelgen/estimation/link_summary.hpp).
struct LinkInertial {
  std::string body;
  double mass = 0;
  std::array<double, 3> com{};
  std::array<double, 6> inertia_com{};        ///< xx, xy, xz, yy, yz, zz (tensor entries)
  std::array<double, 3> principal_moments{};  ///< of inertia_com, ascending
  struct APriori {
    double mass = 0;
    std::array<double, 3> com{};
    std::array<double, 3> principal_moments{};
  };
  std::optional<APriori> a_priori;
  /// "data" or "prior" for the mass, the centre of mass and the principal moments.
  std::string mass_decided_by, com_decided_by, moments_decided_by;
  std::vector<std::string> far_from_a_priori;  ///< why the link is far from its a-priori values
  /// base parameters it enters where the data reject its a-priori values, e.g. "MY5R -14.6 sd"
  std::vector<std::string> a_priori_rejected_in;
  std::optional<double> region_extent;         ///< in its geometric region; above 1: outside
};

/// A drive parameter of the consistent fit and whether the data decided it alone ("data") or
/// the regrouping left it to the prior ("prior"; modelgen/estimation/link_summary.hpp).
struct DriveParameter {
  std::string name;
  double value = 0;
  std::optional<double> a_priori;
  std::string decided_by;
  std::vector<std::string> regrouped_with;
};

/// What fit --physical adds; the consistent base estimate itself is EstimateFile::parameters.
struct PhysicalBlock {
  double prior_weight = 0;
  std::string prior_weight_rule;  ///< "default" (the rule of --physical) or "given"
  double cost_increase = 0;  ///< of the weighted sum of squares, in sigma^2
  bool converged = true;     ///< the optimiser met its tolerance (else not the optimum)
  double unconstrained_rel_error_norm = 0;
  std::vector<std::string> binding_constraints;
  std::vector<std::string> prior_notes;  ///< singular a-priori bodies spread for the prior
  std::vector<EstimatedParameter> unconstrained;               ///< the fit without constraints
  std::vector<std::pair<std::string, double>> standard;        ///< consistent, by standard name
  std::vector<LinkInertial> links;
  std::vector<DriveParameter> drives;
};

struct EstimateFile {
  std::string model;                           ///< IdentificationModel::name()
  std::string description_sha256;              ///< of the description the model was made from
  std::string method;                          ///< "IDIM-OLS", "IDIM-WLS", "PIM-WLS"
  std::vector<EstimatedParameter> parameters;  ///< every base parameter, in model order
  double rel_error_norm = 0;                   ///< ||tau - W beta|| / ||tau||
  double condition_number = 0;
  double residual_std = 0;                  ///< sigma_rho (eq. 17)
  std::vector<double> rms_per_axis;         ///< rms torque error per joint
  std::vector<double> rms_torque_per_axis;  ///< rms measured torque per joint
  long long samples = 0;
  std::vector<std::string> data;  ///< the --data files as given
  /// The data options the fit was run with, as command-line words (data_option_words).
  std::vector<std::string> data_options;
  std::optional<EssentialEstimate> essential;
  std::optional<PhysicalBlock> physical;
};

/// The JSON text of an estimate: {"model", "description_sha256", "method", "samples", "data",
/// "data_options", "rel_error_norm", "condition_number", "residual_std", "rms_per_axis",
/// "rms_torque_per_axis", "parameters": [{"name", "value", "std", "rel_std", "truth"?}],
/// "essential"?: {"r_sigma", "kept", "eliminated", "parameters", "rel_error_norm",
/// "condition_number"}, "standard"?: {"XX1": ..., ...}, "links"?: [{"body", "mass", "com",
/// "inertia_com", "principal_moments", "decided_by": {"mass", "com", "principal_moments"},
/// "a_priori"?: {"mass", "com", "principal_moments"}, "far_from_a_priori": [...],
/// "a_priori_rejected_in"?: [...],
/// "region_extent"?}],
/// "drives"?: [{"name", "value", "a_priori"?, "decided_by", "regrouped_with"}],
/// "physical"?: {"prior_weight", "prior_weight_rule", "cost_increase", "binding_constraints",
/// "prior_notes", "unconstrained_rel_error_norm", "unconstrained": [...]}}. Non-finite numbers are
/// written as null.
std::string estimate_json(const EstimateFile& estimate);

/// Refuses a parameter file made for another model: when the JSON file at `path` has a
/// non-empty "description_sha256" that differs from model.description_sha256(), throws
/// InputError "PATH: error: the estimate belongs to another model ...". Files without the field
/// (hand-written parameter files) pass. Throws InputError for a file that cannot be read or is
/// not JSON, or whose field is not a string.
/// `what` names the file in the message ("estimate", "truth").
void check_estimate_model(const std::string& path, const IdentificationModel& model,
                          const std::string& what = "estimate");
/// The same for a document already read (read_json_document), so that a command reads its
/// parameter file once.
void check_estimate_model(const JsonDocument& document, const IdentificationModel& model,
                          const std::string& what = "estimate");

/// The "data_options" of the estimate file at `path` (words as fit wrote them), or nothing
/// when the file has none (hand-written parameter files, estimates of older versions).
/// Throws std::runtime_error "PATH: error: ..." when the field is not a list of strings.
std::optional<std::vector<std::string>> read_data_options(const std::string& path);
/// The same for a document already read.
std::optional<std::vector<std::string>> read_data_options(const JsonDocument& document);

}  // namespace modelgen::io
