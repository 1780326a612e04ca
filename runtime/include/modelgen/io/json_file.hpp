// JSON input files of modelid (parameters, estimates, a-priori values), read the same way: one
// parser, positions for every key, and the traps of plain JSON parsing refused (a key given
// twice, where the last silently won; a number out of range, which was an internal error;
// nesting or a size no such file has, which cost time and memory beyond any use).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "modelgen/model/error.hpp"

namespace modelgen::io {

/// Arrays and objects nested deeper than this are refused: modelid's files nest four levels
/// at most, and a file nested 100 000 deep (200 KB of brackets) took time and memory with
/// the square of its depth, and recursions that deep in nlohmann::json.
inline constexpr int kMaxJsonDepth = 64;
/// Larger files are refused before they are read: an estimate of a 32-joint robot is about
/// 150 KB, while a MiB of small arrays takes up to a second to read, document and positions.
inline constexpr std::uintmax_t kMaxJsonBytes = 1u << 20;  // 1 MiB

struct JsonPositionsInside;

/// Where a value of a document is written, and where the values inside it are.
struct JsonPosition {
  int line = 0;                                 ///< 1-based
  int column = 0;                               ///< 1-based, in bytes
  std::unique_ptr<JsonPositionsInside> inside;  ///< null for a scalar
};

/// The positions of the elements of an array by index, of the members of an object by key.
struct JsonPositionsInside {
  std::vector<JsonPosition> elements;
  std::map<std::string, JsonPosition, std::less<>> members;
};

/// A parsed JSON file with the position of every value.
struct JsonDocument {
  std::string path;
  nlohmann::json value;
  /// Where the value at the JSON pointer `pointer` ("/parameters/3/name", RFC 6901) is
  /// written: the line and column of its key in an object, of its first character in an array;
  /// the file alone when the pointer names no value of the document.
  SourceLocation at(const std::string& pointer) const;

  JsonPosition root;  ///< the document's value at 1:1
};

/// `pointer` extended by one object key or array index, escaped as RFC 6901 says.
std::string json_pointer(const std::string& pointer, std::string_view token);

/// The JSON document in `path`. Throws InputError naming the file, line and column when the
/// file cannot be opened, is larger than kMaxJsonBytes, is not valid JSON, holds a number
/// beyond the range of a double (`1e999`), nests arrays and objects deeper than kMaxJsonDepth
/// or gives a key twice in one object (both lines named). Time and memory grow linearly with
/// the file's size.
JsonDocument read_json_document(const std::string& path);

/// read_json_document(path).value.
nlohmann::json read_json_file(const std::string& path);

}  // namespace modelgen::io
