// The template printer alone (STYLE.md section 6): tiny inline templates against literal
// expected text for inline values, block indentation, empty blocks, $$, $# comments, and the
// positions named by the errors a generator bug raises.

#include "generator/emit/printer.hpp"

#include <climits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "generator/emit/template.hpp"

namespace modelgen::gen {
namespace {

// The message of the std::logic_error `f` throws; fails the test if it throws nothing.
template <typename F>
std::string logic_error_message(F f) {
  try {
    f();
  } catch (const std::logic_error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected std::logic_error";
  return "";
}

TEST(Printer, InlinePlaceholdersTakeTheirValueVerbatim) {
  const Template tmpl("t.tmpl", "namespace $robot$ {\nint x = $a$ + $b$;\n}\n");
  const std::string out =
      Printer(tmpl).set("robot", "kr150").set("a", "s1 * c2").set("b", "q[0]").render();
  EXPECT_EQ(out, "namespace kr150 {\nint x = s1 * c2 + q[0];\n}\n");
}

TEST(Printer, SamePlaceholderTwiceOnOneLine) {
  const Template tmpl("t.tmpl", "#ifndef $g$\n#define $g$\n#endif  // $g$\n");
  EXPECT_EQ(Printer(tmpl).set("g", "MODELGEN_KR150_HPP_").render(),
            "#ifndef MODELGEN_KR150_HPP_\n#define MODELGEN_KR150_HPP_\n"
            "#endif  // MODELGEN_KR150_HPP_\n");
}

TEST(Printer, EveryLineEndsInNewlineEvenWithoutFinalNewlineInTemplate) {
  const Template tmpl("t.tmpl", "a $x$\nb");
  EXPECT_EQ(Printer(tmpl).set("x", "1").render(), "a 1\nb\n");
}

TEST(Printer, EmptyTemplateLinesAreKept) {
  const Template tmpl("t.tmpl", "a\n\n\nb\n");
  EXPECT_EQ(Printer(tmpl).render(), "a\n\n\nb\n");
}

TEST(Printer, SetLongLong) {
  const Template tmpl("t.tmpl", "constexpr int kDof = $dof$;\nconst long long m = $m$;\n$n$\n");
  const std::string out = Printer(tmpl)
                              .set("dof", 6LL)
                              .set("m", LLONG_MIN)
                              .set("n", static_cast<long long>(0))
                              .render();
  EXPECT_EQ(out, "constexpr int kDof = 6;\nconst long long m = -9223372036854775808;\n0\n");
}

TEST(Printer, SetWithIntegerArgumentsOfOtherTypes) {
  // The model emitter passes sizes and ints; they must print as numbers.
  const Template tmpl("t.tmpl", "$a$ $b$ $c$\n");
  const std::size_t size = 42;
  EXPECT_EQ(Printer(tmpl).set("a", 7).set("b", size).set("c", -1).render(), "7 42 -1\n");
}

TEST(Printer, BlockIsIndentedToThePlaceholderColumn) {
  const Template tmpl("t.tmpl",
                      "void f() {\n"
                      "    $body$\n"
                      "}\n");
  const std::string out = Printer(tmpl)
                              .set_block("body",
                                         [](CodeWriter& w) {
                                           w.line("int a = 1;");
                                           w.blank();
                                           w.line("if (a) {");
                                           w.line("  a = 2;");
                                           w.line("}");
                                         })
                              .render();
  EXPECT_EQ(out,
            "void f() {\n"
            "    int a = 1;\n"
            "\n"
            "    if (a) {\n"
            "      a = 2;\n"
            "    }\n"
            "}\n");
}

TEST(Printer, BlockAtColumnOneIsNotIndented) {
  const Template tmpl("t.tmpl", "begin\n$body$\nend\n");
  const std::string out = Printer(tmpl)
                              .set_block("body",
                                         [](CodeWriter& w) {
                                           w.line("x");
                                           w.line("  y");
                                         })
                              .render();
  EXPECT_EQ(out, "begin\nx\n  y\nend\n");
}

TEST(Printer, MultiLineValueOnABlockLineIsIndentedLikeABlock) {
  const Template tmpl("t.tmpl", "{\n  $banner$\n}\n");
  EXPECT_EQ(Printer(tmpl).set("banner", "// one\n\n// two").render(),
            "{\n  // one\n\n  // two\n}\n");
}

TEST(Printer, EmptyBlockRemovesTheLine) {
  const Template tmpl("t.tmpl",
                      "a\n"
                      "    $body$\n"
                      "b\n");
  EXPECT_EQ(Printer(tmpl).set_block("body", [](CodeWriter&) {}).render(), "a\nb\n");
}

TEST(Printer, BlockOfOneEmptyLineKeepsAnEmptyLineWithoutIndent) {
  const Template tmpl("t.tmpl", "a\n    $body$\nb\n");
  EXPECT_EQ(Printer(tmpl).set_block("body", [](CodeWriter& w) { w.blank(); }).render(), "a\n\nb\n");
}

TEST(Printer, PlaceholderWithTextAroundIsInlineNotABlock) {
  // Not alone on its line: a value with a newline is inserted as is, no indentation added.
  const Template tmpl("t.tmpl", "  x = $v$;\n");
  EXPECT_EQ(Printer(tmpl).set("v", "1").render(), "  x = 1;\n");
}

TEST(Printer, DoubleDollarIsALiteralDollar) {
  const Template tmpl("t.tmpl", "cost: $$$n$ or $$5\n$$\n");
  EXPECT_EQ(Printer(tmpl).set("n", "3").render(), "cost: $3 or $5\n$\n");
}

TEST(Printer, DoubleDollarAloneIsNotABlockPlaceholder) {
  const Template tmpl("t.tmpl", "    $$\n");
  EXPECT_EQ(Printer(tmpl).render(), "    $\n");
}

TEST(Printer, CommentLinesAreDropped) {
  const Template tmpl("t.tmpl",
                      "$# This template says hello.\n"
                      "hello $name$\n"
                      "$# another comment with $unbalanced and $name$\n"
                      "bye\n");
  EXPECT_EQ(Printer(tmpl).set("name", "world").render(), "hello world\nbye\n");
}

TEST(Printer, UnknownPlaceholderNamesItsPosition) {
  const Template tmpl("t.tmpl",
                      "$# comment on line 1\n"
                      "line two\n"
                      "int $a$ = $missing$;\n");
  const std::string message = logic_error_message([&] { Printer(tmpl).set("a", "x").render(); });
  EXPECT_NE(message.find("t.tmpl:3:11"), std::string::npos) << message;
  EXPECT_NE(message.find("missing"), std::string::npos) << message;
}

TEST(Printer, UnknownBlockPlaceholderNamesItsPosition) {
  const Template tmpl("t.tmpl", "a\n\n      $body$\n");
  const std::string message = logic_error_message([&] { Printer(tmpl).render(); });
  EXPECT_NE(message.find("t.tmpl:3:7"), std::string::npos) << message;
  EXPECT_NE(message.find("body"), std::string::npos) << message;
}

TEST(Printer, ColumnCountsDoubleDollarsAsTwoCharacters) {
  const Template tmpl("t.tmpl", "$$$$ $x$\n");
  const std::string message = logic_error_message([&] { Printer(tmpl).render(); });
  EXPECT_NE(message.find("t.tmpl:1:6"), std::string::npos) << message;
}

TEST(Printer, BlockUsedInlineIsAnError) {
  const Template tmpl("t.tmpl", "x = $body$;\n");
  const std::string message = logic_error_message(
      [&] { Printer(tmpl).set_block("body", [](CodeWriter& w) { w.line("1"); }).render(); });
  EXPECT_NE(message.find("t.tmpl:1:5"), std::string::npos) << message;
}

TEST(Printer, UnusedValueThrows) {
  const Template tmpl("t.tmpl", "a $x$\n");
  const std::string message =
      logic_error_message([&] { Printer(tmpl).set("x", "1").set("stray", "2").render(); });
  EXPECT_NE(message.find("t.tmpl"), std::string::npos) << message;
  EXPECT_NE(message.find("stray"), std::string::npos) << message;
}

TEST(Printer, UnusedBlockThrows) {
  const Template tmpl("t.tmpl", "a\n");
  const std::string message = logic_error_message(
      [&] { Printer(tmpl).set_block("stray", [](CodeWriter& w) { w.line("x"); }).render(); });
  EXPECT_NE(message.find("stray"), std::string::npos) << message;
}

TEST(Printer, UnusedEmptyBlockThrowsToo) {
  const Template tmpl("t.tmpl", "a\n");
  EXPECT_THROW(Printer(tmpl).set_block("stray", [](CodeWriter&) {}).render(), std::logic_error);
}

TEST(Printer, ValueUsedOnlyInACommentLineIsUnused) {
  const Template tmpl("t.tmpl", "$# uses $x$\nplain\n");
  EXPECT_THROW(Printer(tmpl).set("x", "1").render(), std::logic_error);
}

TEST(Template, UnpairedDollarThrowsAtParseTimeWithPosition) {
  const std::string message =
      logic_error_message([] { Template("t.tmpl", "first\nsecond\nab $oops\n"); });
  EXPECT_NE(message.find("t.tmpl:3:4"), std::string::npos) << message;
}

TEST(Template, UnpairedDollarAfterAPlaceholder) {
  const std::string message = logic_error_message([] { Template("t.tmpl", "$a$ cost $\n"); });
  EXPECT_NE(message.find("t.tmpl:1:10"), std::string::npos) << message;
}

TEST(Template, LinesAfterCommentsKeepTheirFileLineNumbers) {
  const std::string message =
      logic_error_message([] { Template("t.tmpl", "$# c1\n$# c2\n\n  $\n"); });
  EXPECT_NE(message.find("t.tmpl:4:3"), std::string::npos) << message;
}

TEST(Printer, RenderCanBeCalledTwiceWithTheSameResult) {
  const Template tmpl("t.tmpl", "$a$\n  $b$\n");
  Printer printer(tmpl);
  printer.set("a", "x").set_block("b", [](CodeWriter& w) { w.line("y"); });
  EXPECT_EQ(printer.render(), "x\n  y\n");
  EXPECT_EQ(printer.render(), "x\n  y\n");
}

}  // namespace
}  // namespace modelgen::gen
