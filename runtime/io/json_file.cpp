// JSON input files through nlohmann::json: a SAX pass over the text records where each key
// and element starts and refuses duplicated keys and unparsable numbers with their position,
// then the document is built from the same text.

#include "modelgen/io/json_file.hpp"

#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>
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

class PositionRecorder : public nlohmann::json_sax<nlohmann::json> {
 public:
  PositionRecorder(const std::string& path, const std::string& text, const std::size_t& consumed,
                   JsonDocument& document)
      : path_(path), text_(text), consumed_(consumed), document_(document) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& key) override {
    // The parser has just read the key's closing quote; its opening quote is the last
    // unescaped one before it.
    std::size_t close_quote = consumed_ == 0 ? 0 : consumed_ - 1;
    std::size_t open_quote = close_quote;
    while (open_quote > 0) {
      --open_quote;
      if (text_[open_quote] != '"') continue;
      std::size_t backslashes = 0;
      while (open_quote > backslashes && text_[open_quote - backslashes - 1] == '\\') ++backslashes;
      if (backslashes % 2 == 0) break;
    }
    Frame& frame = frames_.back();
    const std::pair<int, int> here = line_column(open_quote);
    const auto [earlier, inserted] = frame.keys.emplace(key, here);
    if (!inserted) {
      throw InputError({path_, here.first, here.second},
                       "key '" + key + "' is given twice in one object (first at line " +
                           std::to_string(earlier->second.first) +
                           "); JSON keeps only one of them, so give each key once");
    }
    frame.key = key;
    frame.key_position = here;
    return true;
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
  struct Frame {
    bool object = false;
    std::string pointer;
    std::size_t next_index = 0;
    std::map<std::string, std::pair<int, int>> keys;
    std::string key;
    std::pair<int, int> key_position;
  };

  // 1-based line and column of the character at `offset`.
  std::pair<int, int> line_column(std::size_t offset) const {
    int line = 1;
    std::size_t line_start = 0;
    for (std::size_t k = 0; k < offset && k < text_.size(); ++k) {
      if (text_[k] == '\n') {
        ++line;
        line_start = k + 1;
      }
    }
    return {line, static_cast<int>(offset - line_start) + 1};
  }

  // Records the pointer and position of the value that starts now; returns its pointer.
  std::string place() {
    if (frames_.empty()) {
      document_.positions[""] = {1, 1};
      return "";
    }
    Frame& parent = frames_.back();
    std::string pointer;
    std::pair<int, int> where;
    if (parent.object) {
      pointer = json_pointer(parent.pointer, parent.key);
      where = parent.key_position;
    } else {
      pointer = json_pointer(parent.pointer, std::to_string(parent.next_index++));
      // The parser has read the value's first character (and a scalar's first lookahead).
      std::size_t start = consumed_ == 0 ? 0 : consumed_ - 1;
      while (start > 0 && (text_[start] == ',' || text_[start] == ']' ||
                           std::isspace(static_cast<unsigned char>(text_[start])))) {
        --start;
      }
      where = line_column(start);
    }
    document_.positions[pointer] = where;
    return pointer;
  }

  bool value() {
    place();
    return true;
  }
  bool open(bool object) {
    Frame frame;
    frame.object = object;
    frame.pointer = place();
    frames_.push_back(std::move(frame));
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }

  const std::string& path_;
  const std::string& text_;
  const std::size_t& consumed_;
  JsonDocument& document_;
  std::vector<Frame> frames_;
};

}  // namespace

SourceLocation JsonDocument::at(const std::string& pointer) const {
  const auto found = positions.find(pointer);
  if (found == positions.end()) return {path};
  return {path, found->second.first, found->second.second};
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
  document.value = nlohmann::json::parse(text);
  return document;
}

nlohmann::json read_json_file(const std::string& path) { return read_json_document(path).value; }

}  // namespace modelgen::io
