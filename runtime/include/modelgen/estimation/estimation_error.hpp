// The error every estimation function throws for input it cannot estimate from.
#pragma once

#include "modelgen/model/error.hpp"

namespace modelgen {

/// Bad estimation input: sizes that do not match, NaN/inf, fewer rows than parameters, or a
/// rank-deficient W. what() says which, in words; where() names the data file and column when
/// the input came from one.
class EstimationError : public Error {
 public:
  using Error::Error;
};

}  // namespace modelgen
