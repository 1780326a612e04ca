// SHA-256 of input bytes (through OpenSSL): in the banners and manifests of generated files, and
// in estimates, to name the description a model was made from.
#pragma once

#include <string>
#include <string_view>

namespace modelgen {

/// The 64 lowercase hex digits of SHA-256(bytes).
std::string sha256_hex(std::string_view bytes);

}  // namespace modelgen
