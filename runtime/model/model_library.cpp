// Opening a generated model's shared library: dlopen, the entry point, then the table's checks
// in the order that lets each read only what the previous ones vouched for (the version and
// size before any other member, the sizes before the arrays they size).

#include "modelgen/model/model_library.hpp"

#include <dlfcn.h>

#include <stdexcept>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/generated_format.hpp"

namespace modelgen {

namespace {

std::string dl_error() {
  const char* text = dlerror();
  return text != nullptr ? text : "unknown reason";
}

// The first check that fails, as the message's reason; empty when every one passes.
std::string size_problem(const modelgen_loadable_table& t) {
  if (t.dof < 1 || t.dof > kMaxMovingJoints) {
    return "its dof is " + std::to_string(t.dof) + ", not 1 to " + std::to_string(kMaxMovingJoints);
  }
  if (t.standard_params < 1 || t.base_params < 1 || t.drive_params < 1 ||
      t.drive_regressor_entries < 1) {
    return "a parameter count is not positive (standard " + std::to_string(t.standard_params) +
           ", base " + std::to_string(t.base_params) + ", drive " + std::to_string(t.drive_params) +
           ", drive regressor entries " + std::to_string(t.drive_regressor_entries) + ")";
  }
  if (t.base_params > t.standard_params) {
    return "it has more base parameters (" + std::to_string(t.base_params) +
           ") than standard ones (" + std::to_string(t.standard_params) + ")";
  }
  if (t.drive_regressor_entries > t.dof * t.drive_params) {
    return "its drive regressor has " + std::to_string(t.drive_regressor_entries) +
           " entries, more than dof x drive parameters";
  }
  return "";
}

std::string pointer_problem(const modelgen_loadable_table& t) {
  const void* arrays[] = {t.name,
                          t.standard_param_names,
                          t.base_param_names,
                          t.drive_param_names,
                          t.drive_regressor_index,
                          t.motor_from_joint,
                          t.torque_constant,
                          t.joint_offset};
  for (const void* p : arrays) {
    if (p == nullptr) return "a name or constant array is missing (null)";
  }
  const bool functions = t.idim_regressor && t.power_regressor && t.inverse_dynamics &&
                         t.mass_matrix && t.mass_matrix_and_bias && t.inverse_dynamics_state_jacobian &&
                         t.base_from_standard && t.drive_regressor &&
                         t.drive_torque_given_regressor && t.drive_torque_jacobian_given_regressor;
  if (!functions) return "a function is missing (null)";
  const auto named = [](const char* const* names, int count) {
    for (int k = 0; k < count; ++k) {
      if (names[k] == nullptr) return false;
    }
    return true;
  };
  if (!named(t.standard_param_names, t.standard_params) ||
      !named(t.base_param_names, t.base_params) || !named(t.drive_param_names, t.drive_params)) {
    return "a parameter name is missing (null)";
  }
  for (int p = 0; p < t.drive_regressor_entries; ++p) {
    const int k = t.drive_regressor_index[p];
    if (k < 0 || k >= t.dof * t.drive_params || (p > 0 && k <= t.drive_regressor_index[p - 1])) {
      return "its drive regressor index is not increasing places of the dof x drive parameters "
             "regressor (entry " +
             std::to_string(p) + ")";
    }
  }
  return "";
}

// The table's checks, in order; throws at the first that fails.
void check_table(const modelgen_loadable_table& t, const std::string& path,
                 const std::string& description_sha256) {
  const auto refuse = [&](const std::string& message) { throw ModelLibraryError(path, message); };
  const std::string regenerate = ": generate it again with this modelgen (--loadable)";
  if (t.abi_version != MODELGEN_LOADABLE_ABI_VERSION) {
    refuse("model table version " + std::to_string(t.abi_version) + ", this runtime reads " +
           std::to_string(MODELGEN_LOADABLE_ABI_VERSION) + regenerate);
  }
  if (t.struct_size != static_cast<int>(sizeof(modelgen_loadable_table))) {
    refuse("model table of " + std::to_string(t.struct_size) + " bytes, this runtime's has " +
           std::to_string(sizeof(modelgen_loadable_table)) + ": built against another layout" +
           regenerate);
  }
  if (t.format_version != kGeneratedFormatVersion) {
    refuse("generated format " + std::to_string(t.format_version) + ", this runtime reads " +
           std::to_string(kGeneratedFormatVersion) + regenerate);
  }
  if (t.input_sha256 == nullptr || description_sha256 != t.input_sha256) {
    refuse("built for another description: generated from SHA-256 " +
           std::string(t.input_sha256 != nullptr ? t.input_sha256 : "(none)") +
           ", the description's is " + description_sha256);
  }
  if (std::string problem = size_problem(t); !problem.empty()) {
    refuse("bad model table: " + problem);
  }
  if (std::string problem = pointer_problem(t); !problem.empty()) {
    refuse("bad model table: " + problem);
  }
}

}  // namespace

ModelLibraryError::ModelLibraryError(const std::string& path, const std::string& message)
    : Error(SourceLocation{path}, path + ": error: " + message) {}

ModelLibrary ModelLibrary::open(const std::string& path, const std::string& description_sha256) {
  if (description_sha256.size() != 64) {
    throw std::invalid_argument(
        "ModelLibrary::open: the description's SHA-256 must be 64 hex "
        "digits, got '" +
        description_sha256 + "'");
  }
  // dlopen searches the library path for a name without '/': make it the file named.
  const std::string file = path.find('/') == std::string::npos ? "./" + path : path;
  dlerror();
  void* raw = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (raw == nullptr) throw ModelLibraryError(path, "cannot load the model library: " + dl_error());
  std::shared_ptr<void> handle(raw, [](void* h) { dlclose(h); });
  dlerror();
  void* symbol = dlsym(raw, MODELGEN_LOADABLE_SYMBOL);
  if (symbol == nullptr) {
    throw ModelLibraryError(
        path, "not a modelgen model library (made by modelgen --loadable): " + dl_error());
  }
  const auto entry = reinterpret_cast<modelgen_loadable_entry>(symbol);
  const modelgen_loadable_table* table = entry();
  if (table == nullptr) {
    throw ModelLibraryError(path, std::string(MODELGEN_LOADABLE_SYMBOL) + " returned no table");
  }
  check_table(*table, path, description_sha256);
  return ModelLibrary(std::move(handle), table, path);
}

}  // namespace modelgen
