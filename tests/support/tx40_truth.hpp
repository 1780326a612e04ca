// The simulated Staubli TX-40's true base parameters, shared by the identification tests that
// make their own data (open loop in tx40_identification_test, closed loop in
// closed_loop_preparation_test).
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"

namespace modelgen::test {

/// The true base parameters of robots/tx40.yaml in `model`'s base_param_names() order (kg m^2,
/// kg m, N m s/rad, N m): Gautier & Briot Table II where the paper has the parameter, the
/// description's a-priori drive values, and small plausible values for the rest (the source of
/// each value is in tx40_truth.cpp). A name the table lacks is NaN.
Eigen::VectorXd tx40_true_base(const IdentificationModel& model);

/// How many names the table has (one per base parameter of robots/tx40.yaml).
std::size_t tx40_true_base_entries();

}  // namespace modelgen::test
