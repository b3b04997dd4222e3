// Tokens and numbers of the description format.
#include "scene/tokenizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rad {
namespace {

std::vector<Token> all_tokens(std::string_view text) {
  Tokenizer t(text, "t.des");
  std::vector<Token> out;
  while (true) {
    Token tok = t.next();
    out.push_back(tok);
    if (tok.kind == TokenKind::End) return out;
  }
}

TEST(Tokenizer, SplitsWordsStringsAndSymbols) {
  auto t = all_tokens("Object \"a b\" Pure {<1 2 3>}");
  ASSERT_EQ(t.size(), 11u);
  EXPECT_EQ(t[0].kind, TokenKind::Word);
  EXPECT_EQ(t[0].text, "Object");
  EXPECT_EQ(t[1].kind, TokenKind::String);
  EXPECT_EQ(t[1].text, "a b");
  EXPECT_EQ(t[3].kind, TokenKind::Symbol);
  EXPECT_EQ(t[3].text, "{");
  EXPECT_EQ(t[4].text, "<");
  EXPECT_EQ(t[5].text, "1");
  EXPECT_EQ(t[7].text, "3");
  EXPECT_EQ(t[8].text, ">");
  EXPECT_EQ(t[9].text, "}");
  EXPECT_EQ(t[10].kind, TokenKind::End);
}

TEST(Tokenizer, ReportsLineAndColumnOfEachToken) {
  auto t = all_tokens("\"s\"\n  Object\t\"x\"\n<");
  EXPECT_EQ(t[0].loc.line, 1);
  EXPECT_EQ(t[0].loc.column, 1);
  EXPECT_EQ(t[1].loc.line, 2);
  EXPECT_EQ(t[1].loc.column, 3);
  EXPECT_EQ(t[2].loc.column, 10);  // a tab counts as one column
  EXPECT_EQ(t[3].loc.line, 3);
  EXPECT_EQ(t[3].loc.column, 1);
  EXPECT_EQ(t[3].loc.file, "t.des");
}

TEST(Tokenizer, SkipsCommentsToEndOfLine) {
  auto t = all_tokens("; a comment { \"\nA ; B C\n;last");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].text, "A");
  EXPECT_EQ(t[0].loc.line, 2);
}

TEST(Tokenizer, TreatsCrLfAsLineEnd) {
  auto t = all_tokens("A\r\nB\r\n  C");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[1].text, "B");
  EXPECT_EQ(t[1].loc.line, 2);
  EXPECT_EQ(t[1].loc.column, 1);
  EXPECT_EQ(t[2].loc.line, 3);
  EXPECT_EQ(t[2].loc.column, 3);
}

TEST(Tokenizer, SkipsByteOrderMark) {
  auto t = all_tokens("\xEF\xBB\xBF\"s\"");
  EXPECT_EQ(t[0].kind, TokenKind::String);
  EXPECT_EQ(t[0].loc.column, 1);
}

TEST(Tokenizer, EndsWordsAtSymbolsQuotesAndComments) {
  auto t = all_tokens("off/a.off}x\"s\"y;z");
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t[0].text, "off/a.off");
  EXPECT_EQ(t[1].text, "}");
  EXPECT_EQ(t[2].text, "x");
  EXPECT_EQ(t[3].text, "s");
  EXPECT_EQ(t[4].text, "y");
}

TEST(Tokenizer, ReportsUnterminatedStringAtItsQuote) {
  Tokenizer t("A  \"open\nB\"", "t.des");
  t.next();
  try {
    t.next();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 1);
    EXPECT_EQ(e.loc().column, 4);
    EXPECT_NE(std::string(e.what()).find("unterminated string"), std::string::npos);
  }
}

TEST(Tokenizer, PeekDoesNotConsume) {
  Tokenizer t("A B", "t.des");
  EXPECT_EQ(t.peek().text, "A");
  EXPECT_EQ(t.peek().text, "A");
  EXPECT_EQ(t.next().text, "A");
  EXPECT_EQ(t.next().text, "B");
  EXPECT_EQ(t.next().kind, TokenKind::End);
  EXPECT_EQ(t.next().kind, TokenKind::End);
}

TEST(Numbers, ReadsEveryCLikeForm) {
  struct Case {
    const char* text;
    double value;
  };
  for (Case c : {Case{"1", 1.0},
                 {"-0.5", -0.5},
                 {"2.", 2.0},
                 {".5", 0.5},
                 {"1e-3", 1e-3},
                 {"+3", 3.0},
                 {"-.25", -0.25},
                 {"6.02E23", 6.02e23},
                 {"1e+2", 100.0},
                 {"0", 0.0},
                 {"-0", 0.0},
                 {"1e-400", 0.0}}) {
    NumberParse n = parse_number(c.text);
    EXPECT_EQ(n.status, NumberParse::Ok) << c.text;
    EXPECT_NEAR(n.value, c.value, std::abs(c.value) * 1e-12) << c.text;
  }
}

TEST(Numbers, RejectsWordsThatAreNotWholeNumbers) {
  for (const char* w : {"", "+", "-", ".", "e3", "1e", "1.2.3", "1,", "abc", "+-1", "++1", "0x10",
                        "1 ", "Object"}) {
    EXPECT_EQ(parse_number(w).status, NumberParse::NotANumber) << "'" << w << "'";
  }
}

TEST(Numbers, FlagsNonFiniteNumbers) {
  for (const char* w : {"1e999", "-1e999", "inf", "-inf", "nan", "NaN", "infinity", "+inf"}) {
    EXPECT_EQ(parse_number(w).status, NumberParse::NonFinite) << w;
  }
}

TEST(Numbers, ReadsIntegers) {
  long long v = 0;
  EXPECT_TRUE(parse_integer("42", v));
  EXPECT_EQ(v, 42);
  EXPECT_TRUE(parse_integer("+7", v));
  EXPECT_EQ(v, 7);
  EXPECT_TRUE(parse_integer("-3", v));
  EXPECT_EQ(v, -3);
  EXPECT_FALSE(parse_integer("1.0", v));
  EXPECT_FALSE(parse_integer("x", v));
  EXPECT_FALSE(parse_integer("", v));
  EXPECT_FALSE(parse_integer("+-1", v));
}

}  // namespace
}  // namespace rad
