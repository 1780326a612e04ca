/* The table a generated model built as a shared library hands to the runtime: `modelgen ROBOT -o
 * DIR --loadable` writes STEM_loadable.cpp, whose C entry point modelgen_loadable_model_v1()
 * returns it; modelgen/model/model_library.hpp loads the library and checks the table before it
 * uses anything. Plain C, so that the layout is the same on both sides of dlopen.
 *
 * templates/loadable.cpp.tmpl defines the identical struct in the generated file (generated code
 * needs nothing from this package): the two change together, with MODELGEN_LOADABLE_ABI_VERSION.
 * abi_version and struct_size stay the first two members in every version, so that a library of
 * another version is told apart by them, not by a crash; the entry point keeps its name. */
#pragma once

#ifdef __cplusplus
extern "C" {
#endif

/* The layout below; a library whose abi_version differs is refused. */
#define MODELGEN_LOADABLE_ABI_VERSION 2
/* The name of the entry point, of type modelgen_loadable_entry. */
#define MODELGEN_LOADABLE_SYMBOL "modelgen_loadable_model_v1"

/* Arrays are row-major, sizes as in the generated header (docs/generated-code.md). Every function
 * is the double entry point of the same name, which leaves the entries that are zero for every
 * input unwritten (the caller zeroes its arrays). */
typedef struct modelgen_loadable_table {
  int abi_version;          /* MODELGEN_LOADABLE_ABI_VERSION of the generator */
  int struct_size;          /* sizeof(modelgen_loadable_table) where the library was compiled */
  int format_version;       /* kFormatVersion of the generated header */
  const char* name;         /* the robot: the generated namespace */
  const char* input_sha256; /* of the description the code was generated from, 64 hex digits */
  int dof;
  int standard_params;
  int base_params;
  int drive_params;
  int drive_regressor_entries;
  const char* const* standard_param_names; /* standard_params names */
  const char* const* base_param_names;     /* base_params names */
  const char* const* drive_param_names;    /* drive_params names */
  const int* drive_regressor_index; /* drive_regressor_entries places in the dense regressor */
  const double* motor_from_joint;   /* dof x dof */
  const double* torque_constant;    /* dof */
  const double* joint_offset;       /* dof */
  void (*idim_regressor)(const double* q, const double* dq, const double* ddq, double* W);
  void (*power_regressor)(const double* q, const double* dq, const double* ddq, double* dh);
  void (*inverse_dynamics)(const double* q, const double* dq, const double* ddq, const double* beta,
                           double* tau);
  void (*mass_matrix)(const double* q, const double* beta, double* M);
  void (*mass_matrix_and_bias)(const double* q, const double* dq, const double* beta, double* M,
                               double* h);
  void (*inverse_dynamics_state_jacobian)(const double* q, const double* dq, const double* ddq,
                                          const double* beta, double* J);
  void (*base_from_standard)(const double* p_standard, double* beta);
  void (*drive_regressor)(const double* q, const double* dq, const double* ddq, double* Y);
  void (*drive_torque_given_regressor)(const double* Y, const double* theta, double* tau_M);
  void (*drive_torque_jacobian_given_regressor)(const double* Y, const double* theta, double* tau_M,
                                                double* J);
} modelgen_loadable_table;

typedef const modelgen_loadable_table* (*modelgen_loadable_entry)(void);

#ifdef __cplusplus
}
#endif
