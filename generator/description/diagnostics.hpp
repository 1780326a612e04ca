// Positions in input files and the one error type a bad description raises. Every message
// names the file, the line and column where known, and what is wrong in the user's words.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace modelgen::gen {

struct SourceLocation {
  std::string file;
  int line = 0;    ///< 1-based; 0 when unknown
  int column = 0;  ///< 1-based; 0 when unknown

  /// "file:line:column", leaving out the parts that are unknown.
  std::string to_string() const;
};

/// A problem with the user's input. what() reads "file:line:column: error: message".
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message);

  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

/// The candidate closest to `word` by edit distance, if it is close enough to be a likely typo
/// (distance at most a third of the word's length, at least 1); otherwise empty.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

/// " (did you mean 'x'?)" for the closest candidate, or empty.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace modelgen::gen
