#include "scene/tokenizer.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

namespace rad {

NumberParse parse_number(std::string_view word) {
  NumberParse out;
  std::string_view s = word;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars refuses a '+'
  if (s.empty() || s.front() == '+' || (s.front() == '-' && word.front() == '+')) return out;
  double value = 0.0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size()) return out;
  if (ec == std::errc::result_out_of_range) {
    // Overflow is not finite; underflow is a tiny finite number. strtod tells them apart.
    value = std::strtod(std::string(s).c_str(), nullptr);
  } else if (ec != std::errc()) {
    return out;
  }
  out.value = value;
  out.status = std::isfinite(value) ? NumberParse::Ok : NumberParse::NonFinite;
  return out;
}

bool parse_integer(std::string_view word, long long& value) {
  std::string_view s = word;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty() || s.front() == '+' || (s.front() == '-' && word.front() == '+')) return false;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size();
}

std::string describe(const Token& token) {
  switch (token.kind) {
    case TokenKind::Word:
    case TokenKind::Symbol:
      return "'" + token.text + "'";
    case TokenKind::String:
      return "string \"" + token.text + "\"";
    case TokenKind::End:
      return "end of file";
  }
  return "?";
}

namespace {
bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}
bool is_symbol(char c) { return c == '{' || c == '}' || c == '<' || c == '>'; }
bool ends_word(char c) { return is_blank(c) || is_symbol(c) || c == ';' || c == '"'; }
}  // namespace

Tokenizer::Tokenizer(std::string_view text, std::string path)
    : text_(text), path_(std::move(path)) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") {
    pos_ = 3;
    line_start_ = 3;
  }
}

const Token& Tokenizer::peek() {
  if (!has_peeked_) {
    peeked_ = scan();
    has_peeked_ = true;
  }
  return peeked_;
}

Token Tokenizer::next() {
  if (has_peeked_) {
    has_peeked_ = false;
    return std::move(peeked_);
  }
  return scan();
}

void Tokenizer::skip_blanks_and_comments() {
  while (pos_ < text_.size()) {
    char c = text_[pos_];
    if (c == '\n') {
      ++pos_;
      ++line_;
      line_start_ = pos_;
    } else if (is_blank(c)) {
      ++pos_;
    } else if (c == ';') {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      return;
    }
  }
}

Token Tokenizer::scan() {
  skip_blanks_and_comments();
  Token t;
  t.loc = here();
  if (pos_ >= text_.size()) return t;  // End
  char c = text_[pos_];
  if (is_symbol(c)) {
    t.kind = TokenKind::Symbol;
    t.text = std::string(1, c);
    ++pos_;
  } else if (c == '"') {
    size_t close = pos_ + 1;
    while (close < text_.size() && text_[close] != '"' && text_[close] != '\n') ++close;
    if (close >= text_.size() || text_[close] != '"') {
      throw Error(t.loc, "unterminated string: no closing '\"' on this line");
    }
    t.kind = TokenKind::String;
    t.text = std::string(text_.substr(pos_ + 1, close - pos_ - 1));
    pos_ = close + 1;
  } else {
    size_t end = pos_;
    while (end < text_.size() && !ends_word(text_[end])) ++end;
    t.kind = TokenKind::Word;
    t.text = std::string(text_.substr(pos_, end - pos_));
    pos_ = end;
  }
  return t;
}

}  // namespace rad
