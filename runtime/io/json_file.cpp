// JSON input files through nlohmann::json, in one SAX pass over the text: each event builds
// the document (nlohmann's own DOM builder) and records where its value starts in a tree shaped
// like the document; duplicated keys, unparsable numbers and nesting beyond the limit are
// refused with their position. Every step is linear in the text: positions come from line
// starts found once, and no value carries the path to it.

#include "modelgen/io/json_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

namespace modelgen::io {

namespace {

// An iterator over the text that counts the characters the parser has consumed, so the SAX
// callbacks below know where they are (nlohmann::json 3.11 passes no position to them).
struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* at;
  std::size_t* consumed;

  reference operator*() const { return *at; }
  CountingIterator& operator++() {
    ++at;
    ++*consumed;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const CountingIterator& other) const { return at == other.at; }
  bool operator!=(const CountingIterator& other) const { return at != other.at; }
};

// The kinds of scalar values, by how their text ends.
enum class Scalar { kString, kWord, kNumber };

// The SAX handler: positions here, the document by nlohmann's DOM builder (the one
// json::parse uses), which the events are passed on to.
class PositionRecorder : public nlohmann::json_sax<nlohmann::json> {
 public:
  PositionRecorder(const std::string& path, const std::string& text, const std::size_t& consumed,
                   JsonDocument& document)
      : path_(path), text_(text), consumed_(consumed), document_(document), dom_(document.value) {
    line_starts_.push_back(0);
    for (std::size_t k = 0; k < text.size(); ++k) {
      if (text[k] == '\n') line_starts_.push_back(k + 1);
    }
  }

  bool null() override { return value(Scalar::kWord) && dom_.null(); }
  bool boolean(bool v) override { return value(Scalar::kWord) && dom_.boolean(v); }
  bool number_integer(number_integer_t v) override {
    return value(Scalar::kNumber) && dom_.number_integer(v);
  }
  bool number_unsigned(number_unsigned_t v) override {
    return value(Scalar::kNumber) && dom_.number_unsigned(v);
  }
  bool number_float(number_float_t v, const string_t& s) override {
    return value(Scalar::kNumber) && dom_.number_float(v, s);
  }
  bool string(string_t& v) override { return value(Scalar::kString) && dom_.string(v); }
  bool binary(binary_t& v) override { return value(Scalar::kString) && dom_.binary(v); }
  bool start_object(std::size_t n) override { return open(true) && dom_.start_object(n); }
  bool start_array(std::size_t n) override { return open(false) && dom_.start_array(n); }
  bool end_object() override { return close() && dom_.end_object(); }
  bool end_array() override { return close() && dom_.end_array(); }

  bool key(string_t& key) override {
    // The parser has just read the key's closing quote.
    const std::pair<int, int> here = line_column(opening_quote(last_read()));
    auto& members = frames_.back()->inside->members;
    const auto [earlier, inserted] = members.try_emplace(key);
    if (!inserted) {
      throw InputError({path_, here.first, here.second},
                       "key '" + key + "' is given twice in one object (first at line " +
                           std::to_string(earlier->second.line) +
                           "); JSON keeps only one of them, so give each key once");
    }
    earlier->second.line = here.first;
    earlier->second.column = here.second;
    member_ = &earlier->second;
    return dom_.key(key);
  }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& error) override {
    // `position` counts the characters read, the offending one last. The token string does not
    // say where a token starts: a one-character token ("]") does not reset it, so it may hold
    // the tokens before it, control characters spelled "<U+000A>". A number out of range (406)
    // is a token of its own and is pointed at from its first digit. The library's own prefix
    // and position are dropped from the message.
    const std::size_t start = error.id == 406 && position >= last_token.size()
                                  ? position - last_token.size()
                              : position > 0 ? position - 1
                                             : 0;
    const std::pair<int, int> where = line_column(start);
    std::string message = error.what();
    if (const std::size_t end = message.find("] "); end != std::string::npos) {
      message.erase(0, end + 2);
    }
    if (message.rfind("parse error at line ", 0) == 0) {
      if (const std::size_t colon = message.find(": "); colon != std::string::npos) {
        message.erase(0, colon + 2);
      }
    }
    if (error.id == 406) message += " (beyond the range of a double)";
    throw InputError({path_, where.first, where.second}, "not valid JSON: " + message);
  }

 private:
  // 1-based line and column of the character at `offset`: a binary search among the line
  // starts, which are found once (counting from the file's start for every value made the
  // reader quadratic in the file's size).
  std::pair<int, int> line_column(std::size_t offset) const {
    const auto after = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
    const std::size_t line = static_cast<std::size_t>(after - line_starts_.begin());
    return {static_cast<int>(line), static_cast<int>(offset - line_starts_[line - 1]) + 1};
  }

  // The offset of the last character the parser has read.
  std::size_t last_read() const { return consumed_ == 0 ? 0 : consumed_ - 1; }

  // The opening quote of the string whose closing quote is at `close_quote`: the last
  // unescaped quote before it.
  std::size_t opening_quote(std::size_t close_quote) const {
    std::size_t open_quote = close_quote;
    while (open_quote > 0) {
      --open_quote;
      if (text_[open_quote] != '"') continue;
      std::size_t backslashes = 0;
      while (open_quote > backslashes && text_[open_quote - backslashes - 1] == '\\') ++backslashes;
      if (backslashes % 2 == 0) break;
    }
    return open_quote;
  }

  static bool in_number(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.' ||
           c == 'e' || c == 'E';
  }

  // The offset of the first character of the scalar the parser has just read, found by
  // walking back over it alone (linear in the text overall). A string or a literal ends with
  // the last character read; a number is known to end only once the character after it was
  // read, so that one is stepped over first.
  std::size_t scalar_start(Scalar kind) const {
    std::size_t at = last_read();
    switch (kind) {
      case Scalar::kString:
        return opening_quote(at);
      case Scalar::kWord:
        while (at > 0 && std::isalpha(static_cast<unsigned char>(text_[at - 1]))) --at;
        return at;
      case Scalar::kNumber:
        if (at > 0 && !in_number(text_[at])) --at;
        while (at > 0 && in_number(text_[at - 1])) --at;
        return at;
    }
    return at;
  }

  // The position of the value that starts at `start`: the root, the member whose key was just
  // read (at its key), or the next element of the open array (at its first character).
  JsonPosition& place(std::size_t start) {
    if (frames_.empty()) {
      document_.root.line = document_.root.column = 1;
      return document_.root;
    }
    if (frames_object_.back()) return *member_;
    const std::pair<int, int> where = line_column(start);
    JsonPosition& element = frames_.back()->inside->elements.emplace_back();
    element.line = where.first;
    element.column = where.second;
    return element;
  }

  bool value(Scalar kind) {
    // Only an element of an array is placed at its own first character: the walk back is
    // skipped elsewhere.
    const bool element = !frames_.empty() && !frames_object_.back();
    place(element ? scalar_start(kind) : 0);
    return true;
  }
  bool open(bool object) {
    // Each level costs a frame, and nlohmann::json recurses as deep when it copies or prints
    // the document: a depth no file of modelid has is refused before it costs anything.
    if (frames_.size() >= static_cast<std::size_t>(kMaxJsonDepth)) {
      const std::pair<int, int> where = line_column(last_read());
      throw InputError({path_, where.first, where.second},
                       std::string("this ") + (object ? "object" : "array") + " is nested " +
                           std::to_string(frames_.size() + 1) +
                           " levels deep, beyond the limit of " + std::to_string(kMaxJsonDepth) +
                           " (README, Limits); parameter and estimate files nest a few levels");
    }
    // The open containers are the last elements of their arrays (or members, which do not
    // move), and an array grows only once its open element is closed: the pointers stay valid.
    JsonPosition& here = place(last_read());  // the bracket just read
    here.inside = std::make_unique<JsonPositionsInside>();
    frames_.push_back(&here);
    frames_object_.push_back(object);
    return true;
  }
  bool close() {
    frames_.pop_back();
    frames_object_.pop_back();
    return true;
  }

  const std::string& path_;
  const std::string& text_;
  const std::size_t& consumed_;
  JsonDocument& document_;
  nlohmann::detail::json_sax_dom_parser<nlohmann::json> dom_;
  std::vector<std::size_t> line_starts_;  // offset of the first character of each line
  std::vector<JsonPosition*> frames_;     // the open arrays and objects, outermost first
  std::vector<bool> frames_object_;       // whether each is an object
  JsonPosition* member_ = nullptr;        // the member whose key was read last
};

// The next token of a JSON pointer from `at` (just after a '/'), unescaped as RFC 6901 says.
std::string pointer_token(const std::string& pointer, std::size_t& at) {
  std::string token;
  for (; at < pointer.size() && pointer[at] != '/'; ++at) {
    if (pointer[at] == '~' && at + 1 < pointer.size() &&
        (pointer[at + 1] == '0' || pointer[at + 1] == '1')) {
      token += pointer[++at] == '0' ? '~' : '/';
    } else {
      token += pointer[at];
    }
  }
  return token;
}

}  // namespace

SourceLocation JsonDocument::at(const std::string& pointer) const {
  const JsonPosition* node = &root;
  std::size_t at = 0;
  while (at < pointer.size()) {
    if (pointer[at] != '/' || node->inside == nullptr) return {path};
    ++at;
    const std::string token = pointer_token(pointer, at);
    const JsonPositionsInside& inside = *node->inside;
    if (const auto member = inside.members.find(token); member != inside.members.end()) {
      node = &member->second;
      continue;
    }
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
    if (token.empty() || ec != std::errc() || end != token.data() + token.size() ||
        index >= inside.elements.size()) {
      return {path};
    }
    node = &inside.elements[index];
  }
  if (node->line == 0) return {path};
  return {path, node->line, node->column};
}

std::string json_pointer(const std::string& pointer, std::string_view token) {
  std::string out = pointer + "/";
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

JsonDocument read_json_document(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path}, "cannot open the file");
  std::error_code size_error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, size_error);
  if (!size_error && bytes > kMaxJsonBytes) {
    throw InputError({path}, "the file has " + std::to_string(bytes) +
                                 " bytes, beyond the limit of " +
                                 std::to_string(kMaxJsonBytes >> 20) +
                                 " MiB a parameter or estimate file may hold (README, Limits)");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  JsonDocument document;
  document.path = path;
  std::size_t consumed = 0;
  PositionRecorder recorder(path, text, consumed, document);
  const CountingIterator first{text.data(), &consumed};
  const CountingIterator last{text.data() + text.size(), &consumed};
  nlohmann::json::sax_parse(first, last, &recorder);
  return document;
}

nlohmann::json read_json_file(const std::string& path) { return read_json_document(path).value; }

}  // namespace modelgen::io
