// A hand-made model library for the loader's refusals (model_library_test.cpp): a one-joint table
// in the runtime's own layout, valid as it stands, with one thing changed by a definition at
// compile time (-DFAKE_ABI_VERSION=1, -DFAKE_FORMAT_VERSION=4, -DFAKE_STRUCT_SIZE=8,
// -DFAKE_DOF=0, -DFAKE_NULL_FUNCTION). Its functions are never called.

#include "modelgen/model/loadable_model.h"

#ifndef FAKE_ABI_VERSION
#define FAKE_ABI_VERSION MODELGEN_LOADABLE_ABI_VERSION
#endif
#ifndef FAKE_STRUCT_SIZE
#define FAKE_STRUCT_SIZE static_cast<int>(sizeof(modelgen_loadable_table))
#endif
#ifndef FAKE_DOF
#define FAKE_DOF 1
#endif

namespace {

void state_function(const double*, const double*, const double*, double*) {}
void torques(const double*, const double*, const double*, const double*, double*) {}
void mass_matrix(const double*, const double*, double*) {}
void mass_matrix_and_bias(const double*, const double*, const double*, double*, double*) {}
void base_from_standard(const double*, double*) {}
void drive_torque(const double*, const double*, double*) {}
void drive_jacobian(const double*, const double*, double*, double*) {}

const char* const kStandard[] = {"ZZ1", "Fv1"};
const char* const kBase[] = {"ZZ1"};
const char* const kDrive[] = {"ZZ1", "JM1", "Rv1", "Rc1", "Rz1"};
const int kIndex[] = {0, 1};
const double kOne[] = {1.0};
const double kZero[] = {0.0};

const modelgen_loadable_table kTable = {FAKE_ABI_VERSION,
                                        FAKE_STRUCT_SIZE,
                                        FAKE_FORMAT_VERSION,
                                        "fake",
                                        FAKE_SHA256,
                                        FAKE_DOF,
                                        2,
                                        1,
                                        5,
                                        2,
                                        kStandard,
                                        kBase,
                                        kDrive,
                                        kIndex,
                                        kOne,
                                        kZero,
                                        kZero,
#ifdef FAKE_NULL_FUNCTION
                                        nullptr,
#else
                                        state_function,
#endif
                                        state_function,
                                        torques,
                                        mass_matrix,
                                        mass_matrix_and_bias,
                                        torques,
                                        base_from_standard,
                                        state_function,
                                        drive_torque,
                                        drive_jacobian};

}  // namespace

extern "C" const modelgen_loadable_table* modelgen_loadable_model_v1(void) { return &kTable; }
