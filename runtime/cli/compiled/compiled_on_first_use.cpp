// std::call_once: the first evaluation loads a model built at build time, or else compiles it
// (or loads it from the cache), exactly once, also when several threads evaluate at once; later
// calls cost one atomic load.

#include "runtime/cli/compiled/compiled_on_first_use.hpp"

#include "runtime/cli/compiled/prebuilt_models.hpp"

namespace modelgen::internal {

CompiledOnFirstUse::CompiledOnFirstUse(std::unique_ptr<IdentificationModel> reference,
                                       std::filesystem::path path, LoadOptions options)
    : reference_(std::move(reference)), path_(std::move(path)), options_(std::move(options)) {}

const ModelLibrary* CompiledOnFirstUse::library() const {
  std::call_once(tried_, [this] {
    const DescriptionToCompile description{path_, options_, reference_.get()};
    library_ = prebuilt_model(description);
    if (!library_) library_ = compiled_model(description);
    if (library_) compiled_ = library_->identification_model();
  });
  return library_ ? &*library_ : nullptr;
}

const IdentificationModel& CompiledOnFirstUse::active() const {
  library();
  return compiled_ ? *compiled_ : *reference_;
}

}  // namespace modelgen::internal
