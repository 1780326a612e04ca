// JSON input files of modelid (parameters, estimates, a-priori values), read the same way: one
// parser, positions for every key, and the traps of plain JSON parsing refused (a key given
// twice, where the last silently won; a number out of range, which was an internal error).
#pragma once

#include <map>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "modelgen/model/error.hpp"

namespace modelgen::io {

/// A parsed JSON file with the position of every value, by JSON pointer ("/parameters/3/name").
struct JsonDocument {
  std::string path;
  nlohmann::json value;
  /// Where the value at `pointer` is written: the line and column of its key in an object, of
  /// its first character in an array; the file alone when the pointer is unknown.
  SourceLocation at(const std::string& pointer) const;

  std::map<std::string, std::pair<int, int>> positions;  ///< pointer -> (line, column), 1-based
};

/// `pointer` extended by one object key or array index, escaped as RFC 6901 says.
std::string json_pointer(const std::string& pointer, std::string_view token);

/// The JSON document in `path`. Throws InputError naming the file, line and column when the
/// file cannot be opened, is not valid JSON, holds a number beyond the range of a double
/// (`1e999`) or gives a key twice in one object (both lines named).
JsonDocument read_json_document(const std::string& path);

/// read_json_document(path).value.
nlohmann::json read_json_file(const std::string& path);

}  // namespace modelgen::io
