// The table of fit's methods and their estimators: the linear IDIM and PIM fits (Gautier &
// Briot eq. 14-20), IDIM-IV and DIDIM under the controller, the projection method (Bona &
// Curatella eq. 10-12), ML-EIV (eq. 13-16) and the ML route of the drive model (Swevers 2002).

#include "runtime/cli/fit/fit_methods.hpp"

#include <stdexcept>

#include "runtime/cli/fit/closed_loop_fit.hpp"
#include "runtime/cli/fit/eiv_fit.hpp"
#include "runtime/cli/fit/projection_fit.hpp"

namespace modelgen::internal {

namespace {

template <Method method>
Identification linear(const FitContext& fit) {
  return identify(fit.model, fit.experiments.data, method, fit.options);
}

template <ClosedLoopMethod method>
Identification closed_loop(const FitContext& fit) {
  return fit_closed_loop(fit.args, fit.model, fit.experiments, fit.options.min_speed, method,
                         fit.report, fit.log);
}

Identification projection(const FitContext& fit) {
  return fit_projection(fit.args, fit.model, fit.experiments, fit.options.min_speed, fit.report,
                        fit.log);
}

Identification errors_in_variables(const FitContext& fit) {
  return fit_eiv(fit.model, fit.experiments, fit.report, fit.log);
}

// The closed-loop methods work on the controller's clock, on joint-side records.
void check_closed_loop(const CommandLine& args) {
  const std::string& method = args.one("--method");
  if (!args.has("--controller")) {
    throw UsageError{"--method " + method +
                     " simulates the robot under its controller: give --controller C.yaml"};
  }
  if (args.has("--motor-side") || args.has("--periodic")) {
    throw UsageError{fit_method(method).label +
                     " works on joint-side records on the controller's clock, without "
                     "--motor-side or --periodic"};
  }
}

void check_projection(const CommandLine& args) {
  if (args.has("--motor-side") || args.has("--periodic")) {
    throw UsageError{
        "the projection method (--method pm) works on joint-side records, without "
        "--motor-side or --periodic"};
  }
}

std::vector<FitMethod> make_fit_methods() {
  return {
      {.name = "ols",
       .label = "IDIM-OLS",
       .summary = "ordinary least squares on the inverse dynamic model (Gautier & Briot eq. "
                  "14-19)",
       .estimate = linear<Method::kOls>},
      {.name = "wls",
       .label = "IDIM-WLS",
       .summary = "weighted least squares, one weight per joint (eq. 20)",
       .estimate = linear<Method::kWls>},
      {.name = "pim-wls",
       .label = "PIM-WLS",
       .summary = "the power identification model, weighted (eq. 8-12)",
       .estimate = linear<Method::kPimWls>},
      {.name = "iv",
       .label = "IDIM-IV",
       .summary = "instrumental variables from a simulation under --controller (closed loop, "
                  "Janot et al. 2014)",
       .keeps_records = true,
       .check = check_closed_loop,
       .estimate = closed_loop<ClosedLoopMethod::kIv>},
      {.name = "didim",
       .label = "DIDIM",
       .summary = "the direct and inverse dynamic model under --controller (closed loop, Gautier "
                  "et al. 2013)",
       .keeps_records = true,
       .check = check_closed_loop,
       .estimate = closed_loop<ClosedLoopMethod::kDidim>},
      {.name = "pm",
       .label = "PM (projection, IDIM-WLS)",
       .summary = "the projection method on closed-loop records (Bona & Curatella eq. 10-12)",
       .keeps_records = true,
       .check = check_projection,
       .estimate = projection},
      {.name = "ml",
       .label = "ML",
       .summary = "maximum likelihood of the nonlinear drive model with a-priori link values "
                  "(Swevers et al. 2002, eq. 18; --approach)",
       .route = FitRoute::kDriveModel},
      {.name = "ml-eiv",
       .label = "ML-EIV",
       .summary = "errors-in-variables maximum likelihood on averaged periods (Bona & Curatella "
                  "eq. 13-16)",
       .keeps_records = true,  // a record's reference columns mark a closed loop
       .check = check_eiv_arguments,
       .estimate = errors_in_variables},
  };
}

}  // namespace

const std::vector<FitMethod>& fit_methods() {
  static const std::vector<FitMethod> methods = make_fit_methods();
  return methods;
}

const FitMethod& fit_method(const std::string& name) {
  for (const FitMethod& method : fit_methods()) {
    if (method.name == name) return method;
  }
  throw std::logic_error("fit_method: '" + name + "' is not in the table of methods");
}

}  // namespace modelgen::internal
