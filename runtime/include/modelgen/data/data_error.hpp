// The error every data function throws for a bad data file or trajectory.
#pragma once

#include <stdexcept>

namespace modelgen {

/// A problem with a data file; what() reads "file:line (column NAME): error: message", the line
/// and column parts when known.
class DataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace modelgen
