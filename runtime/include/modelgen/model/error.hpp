// Positions in input files and the error types modelgen raises: one base class, modelgen::Error,
// that every error about the user's input, data or an estimation derives from. Every message
// names the file, the line and column (or field) where known, and what is wrong in the user's
// words.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace modelgen {

struct SourceLocation {
  std::string file;
  int line = 0;    ///< 1-based; 0 when unknown
  int column = 0;  ///< 1-based; 0 when unknown
  std::string field = {};  ///< the key or column named by the message; empty when none

  /// "file:line:column", leaving out the parts that are unknown (the field is part of the
  /// message, in each error type's own words).
  std::string to_string() const;
};

/// The base of every error modelgen reports to its user (a description, a data file, an
/// estimation the data cannot support): what() is the whole message as printed, where() the
/// position as far as it is known. Programs catch this one type to print and exit non-zero.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  Error(SourceLocation where, const std::string& what)
      : std::runtime_error(what), where_(std::move(where)) {}

  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

/// A problem with the user's description or input file. what() reads
/// "file:line:column: error: message".
class InputError : public Error {
 public:
  InputError(SourceLocation where, const std::string& message);

  const std::string& message() const { return message_; }

 private:
  std::string message_;
};

/// The candidate closest to `word` by edit distance, if it is close enough to be a likely typo
/// (distance at most a third of the word's length, at least 1); otherwise empty.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

/// " (did you mean 'x'?)" for the closest candidate, or empty.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace modelgen
