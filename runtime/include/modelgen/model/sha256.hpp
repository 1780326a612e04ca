// SHA-256 of input bytes (through OpenSSL), for the banners and manifests of generated files.
#pragma once

#include <string>
#include <string_view>

namespace modelgen {

/// The 64 lowercase hex digits of SHA-256(bytes).
std::string sha256_hex(std::string_view bytes);

}  // namespace modelgen
