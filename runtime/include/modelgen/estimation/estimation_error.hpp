// The error every estimation function throws for input it cannot estimate from.
#pragma once

#include <stdexcept>

namespace modelgen {

/// Bad estimation input: sizes that do not match, NaN/inf, fewer rows than parameters, or a
/// rank-deficient W. what() says which, in words.
class EstimationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace modelgen
