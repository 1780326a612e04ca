// The drive model of a generated model loaded at run time (modelgen/model/model_library.hpp):
// GeneratedDriveModel (drive_model.hpp) on the library's drive_regressor and its
// _given_regressor functions, with the sizes read from the library's table.
#pragma once

#include <memory>

#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/model_library.hpp"

namespace modelgen {

/// The Swevers drive model of `library`, as GeneratedDriveModel: set_samples() stores the packed
/// drive regressor Y of every sample (samples x drive_regressor_entries doubles), torque() and
/// torque_jacobian() only read it (several threads at once are fine), and torque_jacobian()
/// leaves J's entries that are zero for every sample unwritten (the caller zeroes J once). It
/// keeps the library loaded.
std::unique_ptr<DriveModel> make_drive_model(const ModelLibrary& library);

}  // namespace modelgen
