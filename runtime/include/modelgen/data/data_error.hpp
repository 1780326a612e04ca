// The error every data function throws for a bad data file or trajectory.
#pragma once

#include "modelgen/model/error.hpp"

namespace modelgen {

/// A problem with a data file; what() reads "file:line (column NAME): error: message", the line
/// and column parts when known. where() holds the file, line and column name (field) as far as
/// they are known.
class DataError : public Error {
 public:
  using Error::Error;
};

}  // namespace modelgen
