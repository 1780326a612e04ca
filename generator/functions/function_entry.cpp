// Sizes of the arrays a registry entry declares.

#include "generator/functions/function_entry.hpp"

namespace modelgen::gen {

int extent_size(Extent extent, const ModelSizes& sizes) {
  switch (extent) {
    case Extent::kOne:
      return 1;
    case Extent::kDof:
      return sizes.dof;
    case Extent::kState:
      return 3 * sizes.dof;
    case Extent::kStandardParams:
      return sizes.standard_params;
    case Extent::kBaseParams:
      return sizes.base_params;
    case Extent::kDriveParams:
      return sizes.drive_params;
    case Extent::kDriveRegressorEntries:
      return sizes.drive_regressor_entries;
  }
  return 0;
}

int array_size(const ArraySpec& array, const ModelSizes& sizes) {
  return extent_size(array.rows, sizes) * extent_size(array.cols, sizes);
}

}  // namespace modelgen::gen
