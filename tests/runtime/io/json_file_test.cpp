// The JSON reader of modelid's files (modelgen/io/json_file.hpp): the line and column of every
// key and array element, also far into a long file and after multi-byte and escaped text, and
// nesting beyond kMaxJsonDepth refused at the bracket that goes too deep, for a file of
// 100 000 levels as for one of 65 (such a file once took time and memory with the square of its
// depth).

#include <string>

#include <gtest/gtest.h>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/error.hpp"
#include "tests/support/cli_runner.hpp"

namespace modelgen {
namespace {

// The document of `text`, written to a file of the test's own.
io::JsonDocument read(const std::string& text) {
  const auto path = test::test_folder("json") / "file.json";
  test::write_text(path, text);
  return io::read_json_document(path.string());
}

// The message of the InputError that reading `text` throws, without the file's path.
std::string refusal(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return std::to_string(e.where().line) + ":" + std::to_string(e.where().column) + ": " +
           e.message();
  }
  return "no error";
}

std::pair<int, int> at(const io::JsonDocument& document, const std::string& pointer) {
  const SourceLocation where = document.at(pointer);
  return {where.line, where.column};
}

TEST(JsonFile, KeysAndElementsHaveTheirLineAndColumn) {
  const io::JsonDocument document = read(
      "{\n"
      "  \"base\": {\"ZZ1R\": 1.5,\n"
      "           \"a\\\"b\": 2},\n"
      "  \"list\": [1,\n"
      "     {\"\xc3\xa9\": 2}, [3, 4],\n"
      "\n"
      "    {\"x\": null}]\n"
      "}\n");
  EXPECT_EQ(at(document, ""), std::make_pair(1, 1));
  EXPECT_EQ(at(document, "/base"), std::make_pair(2, 3));
  EXPECT_EQ(at(document, "/base/ZZ1R"), std::make_pair(2, 12));
  EXPECT_EQ(at(document, "/base/a\"b"), std::make_pair(3, 12));
  EXPECT_EQ(at(document, "/list"), std::make_pair(4, 3));
  EXPECT_EQ(at(document, "/list/0"), std::make_pair(4, 12));
  EXPECT_EQ(at(document, "/list/1"), std::make_pair(5, 6));
  EXPECT_EQ(at(document, "/list/1/\xc3\xa9"), std::make_pair(5, 7));
  // Columns count bytes: the two bytes of the key put what follows one column further.
  EXPECT_EQ(at(document, "/list/2"), std::make_pair(5, 17));
  EXPECT_EQ(at(document, "/list/2/1"), std::make_pair(5, 21));
  EXPECT_EQ(at(document, "/list/3"), std::make_pair(7, 5));
  EXPECT_EQ(at(document, "/list/3/x"), std::make_pair(7, 6));
  // An unknown pointer names the file alone.
  EXPECT_EQ(at(document, "/nothing"), std::make_pair(0, 0));
}

// Scalars in arrays are placed at their first character: the opening quote of a string (even
// one holding escaped quotes, commas and brackets), the first letter of true, false and null,
// the sign or first digit of a number. (Strings and literals were once placed at their last
// character, numbers at their last digit.)
TEST(JsonFile, ScalarsInArraysAreAtTheirFirstCharacter) {
  const io::JsonDocument document = read(
      "{\"kept\": [\"ZZ1R\", \"a,]\\\"b\",\n"
      "  true, false,  null,\n"
      "   -1.5e3, 0 , 12345]}\n");
  EXPECT_EQ(at(document, "/kept/0"), std::make_pair(1, 11));
  EXPECT_EQ(at(document, "/kept/1"), std::make_pair(1, 19));
  EXPECT_EQ(at(document, "/kept/2"), std::make_pair(2, 3));
  EXPECT_EQ(at(document, "/kept/3"), std::make_pair(2, 9));
  EXPECT_EQ(at(document, "/kept/4"), std::make_pair(2, 17));
  EXPECT_EQ(at(document, "/kept/5"), std::make_pair(3, 4));
  EXPECT_EQ(at(document, "/kept/6"), std::make_pair(3, 12));
  EXPECT_EQ(at(document, "/kept/7"), std::make_pair(3, 16));
  EXPECT_EQ(document.value["kept"][1], "a,]\"b");
}

TEST(JsonFile, PositionsFarIntoALongFile) {
  std::string text = "[";
  for (int k = 0; k < 200000; ++k) text += k == 0 ? "\n0" : ",\n  0";
  text += ", {\"last\": true}]\n";
  const io::JsonDocument document = read(text);
  EXPECT_EQ(at(document, "/199999"), std::make_pair(200001, 3));
  EXPECT_EQ(at(document, "/200000"), std::make_pair(200001, 6));
  EXPECT_EQ(at(document, "/200000/last"), std::make_pair(200001, 7));
}

TEST(JsonFile, SyntaxErrorsKeepTheirPosition) {
  EXPECT_EQ(refusal("{\n  \"a\": 1,\n  \"a\": 2\n}"),
            "3:3: key 'a' is given twice in one object (first at line 2); JSON keeps only one of "
            "them, so give each key once");
  EXPECT_EQ(refusal("{\"a\": [1, 2,]}"),
            "1:13: not valid JSON: syntax error while parsing value - unexpected ']'; expected "
            "'[', '{', or a literal");
}

TEST(JsonFile, NestingUpToTheLimitIsRead) {
  const std::string text =
      std::string(io::kMaxJsonDepth, '[') + std::string(io::kMaxJsonDepth, ']');
  EXPECT_EQ(read(text).value.dump(), text);
}

TEST(JsonFile, NestingBeyondTheLimitIsRefusedAtItsBracket) {
  const int depth = io::kMaxJsonDepth + 1;
  EXPECT_EQ(refusal("{\"a\":\n" + std::string(depth - 1, '[') + std::string(depth - 1, ']') + "}"),
            "2:64: this array is nested 65 levels deep, beyond the limit of 64 (README, Limits); "
            "parameter and estimate files nest a few levels");
  // 200 KB of brackets, the fuzzer's file: refused at the same bracket, without going deeper.
  EXPECT_EQ(refusal(std::string(100000, '[') + std::string(100000, ']')),
            "1:65: this array is nested 65 levels deep, beyond the limit of 64 (README, Limits); "
            "parameter and estimate files nest a few levels");
  // Objects after a line of 100 000 spaces: the column counts from the line's start.
  std::string objects(100000, ' ');
  objects += '\n';
  for (int k = 0; k < 100000; ++k) objects += "{\"a\":";
  EXPECT_EQ(refusal(objects),
            "2:321: this object is nested 65 levels deep, beyond the limit of 64 (README, "
            "Limits); parameter and estimate files nest a few levels");
}

TEST(JsonFile, FilesBeyondTheSizeLimitAreRefusedUnread) {
  const auto path = test::test_folder("json") / "large.json";
  test::write_text(path, "[" + std::string(io::kMaxJsonBytes - 2, ' ') + "]");
  EXPECT_EQ(io::read_json_document(path.string()).value, nlohmann::json::array());
  test::write_text(path, "[" + std::string(io::kMaxJsonBytes - 1, ' ') + "]");
  try {
    io::read_json_document(path.string());
    ADD_FAILURE() << "a file of " << io::kMaxJsonBytes + 1 << " bytes was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(),
              "the file has 1048577 bytes, beyond the limit of 1 MiB a parameter or "
              "estimate file may hold (README, Limits)");
    EXPECT_EQ(e.where().line, 0);
  }
}

}  // namespace
}  // namespace modelgen
