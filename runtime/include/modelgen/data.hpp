// Transitional: what transmission.hpp takes from the data domain, until the drive chain moves
// to the model core. New code includes modelgen/data/*.hpp.
#pragma once

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
