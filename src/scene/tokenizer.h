// Tokens of the scene description format (design §2) and the C-like number syntax it shares
// with OFF files.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "core/error.h"

namespace rad {

enum class TokenKind {
  Word,    // a run of characters up to whitespace, ';', '"', '{', '}', '<' or '>'
  String,  // "..." on one line; text holds the characters between the quotes
  Symbol,  // one of { } < >
  End,     // end of the text
};

struct Token {
  TokenKind kind = TokenKind::End;
  std::string text;
  SourceLoc loc;  // first character (the opening quote for strings)
};

/// How a word reads as a number.
struct NumberParse {
  enum Status { Ok, NotANumber, NonFinite } status = NotANumber;
  double value = 0.0;
};

/// Reads a whole word as a C-like real number: "1", "-0.5", "+3", "2.", ".5", "1e-3".
/// Words that are numbers but not finite ("inf", "nan", "1e999") give NonFinite.
NumberParse parse_number(std::string_view word);

/// Reads a whole word as a decimal integer (optional sign). False if it is not one.
bool parse_integer(std::string_view word, long long& value);

/// Describes a token for messages: 'Object', '}', string "name", end of file.
std::string describe(const Token& token);

/// Splits description text into tokens. ';' starts a comment to the end of the line; spaces,
/// tabs, CR and LF separate tokens; a UTF-8 byte-order mark is skipped. Columns count bytes
/// from 1. Not thread-safe; the text must outlive the tokenizer.
class Tokenizer {
 public:
  Tokenizer(std::string_view text, std::string path);

  /// The next token, without consuming it. Throws rad::Error on an unterminated string.
  const Token& peek();
  /// The next token, consumed. Returns End forever once the text is exhausted.
  Token next();

 private:
  Token scan();
  void skip_blanks_and_comments();
  SourceLoc here() const { return {path_, line_, static_cast<int>(pos_ - line_start_) + 1}; }

  std::string_view text_;
  std::string path_;
  size_t pos_ = 0;
  size_t line_start_ = 0;
  int line_ = 1;
  Token peeked_;
  bool has_peeked_ = false;
};

}  // namespace rad
