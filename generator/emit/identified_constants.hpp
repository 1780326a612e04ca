// The identified base parameters of `modelgen --params` as constants of the generated code: one
// array in the first scalar type generated, and a float copy for float entry points after
// double ones, so that firmware reads float literals rather than converting at run time.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/number_format.hpp"
#include "generator/emit/printer.hpp"

namespace modelgen::gen {

struct RenderInput;

/// The array holding the identified base parameters for entry points of `scalar`, when the
/// entry points are generated for `scalars`: kIdentifiedBase in the first scalar type,
/// kIdentifiedBaseFloat for float after double.
std::string identified_base_array(Scalar scalar, const std::vector<Scalar>& scalars);

/// The header's declarations of the arrays; nothing without an estimate.
void write_identified_declarations(const RenderInput& in, CodeWriter& out);

/// The source's definitions, one value per line with its base parameter name; nothing without
/// an estimate.
void write_identified_definitions(const RenderInput& in, CodeWriter& out);

}  // namespace modelgen::gen
