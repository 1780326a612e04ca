// std::call_once: the first evaluation compiles (or loads from the cache) exactly once, also
// when several threads evaluate at once, and later calls cost one atomic load.

#include "runtime/cli/compiled/compiled_on_first_use.hpp"

namespace modelgen::internal {

CompiledOnFirstUse::CompiledOnFirstUse(std::unique_ptr<IdentificationModel> reference,
                                       std::filesystem::path path, LoadOptions options)
    : reference_(std::move(reference)), path_(std::move(path)), options_(std::move(options)) {}

const ModelLibrary* CompiledOnFirstUse::library() const {
  std::call_once(tried_, [this] {
    library_ = compiled_model({path_, options_, reference_.get()});
    if (library_) compiled_ = library_->identification_model();
  });
  return library_ ? &*library_ : nullptr;
}

const IdentificationModel& CompiledOnFirstUse::active() const {
  library();
  return compiled_ ? *compiled_ : *reference_;
}

}  // namespace modelgen::internal
