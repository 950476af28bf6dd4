// The tokenizer the program readers share: a statement's words, numbers, quoted strings and symbols, and a cursor
// over them with the checks every reader needs ("file:line: expected ...").
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace waam::planner::internal {

enum class TokenKind { kWord, kNumber, kString, kSymbol, kEnd };

struct Token {
  TokenKind kind = TokenKind::kEnd;
  std::string text;     // words upper-cased; strings without their quotes; a symbol's one character
  double number = 0.0;  // kNumber: the value (always finite, never signed: a sign is a symbol)
  std::string raw;      // the text as written, for messages
};

// Splits `text` into tokens. Words start with a letter, '_', '$' or '#' and go on with letters, digits, '_', '$',
// '#' and '.' ($VEL.CP, CNT100); numbers are digits with an optional fraction and exponent (a number followed by
// letters, as 40cm, is a number and a word); strings are quoted with ' or " (an unclosed one runs to the end); every
// other character that is not blank is a symbol of its own.
std::vector<Token> Tokenize(std::string_view text);

// A cursor over one statement's tokens; failures are InputError "file:line: ...".
class TokenCursor {
 public:
  TokenCursor(std::string_view text, const std::string& file, int line);

  bool AtEnd() const { return at_ >= tokens_.size(); }
  // The token `ahead` places on (an kEnd token past the end).
  const Token& Peek(std::size_t ahead = 0) const;
  const Token& Next();
  // True when the next token is this word (upper case) or symbol.
  bool Is(std::string_view text, std::size_t ahead = 0) const;
  // Consumes the next token when it is this word or symbol.
  bool Accept(std::string_view text);
  // Consumes this word or symbol, or throws "file:line: <context>: expected 'text'".
  void Expect(std::string_view text, std::string_view context);
  // A number with an optional sign; throws naming `what` when there is none.
  double ExpectNumber(std::string_view what);
  bool PeekNumber() const;  // a number (with an optional sign) comes next
  // A whole number in [lo, hi]; throws naming `what`.
  int ExpectInteger(std::string_view what, int lo, int hi);
  // A word; throws naming `what`.
  std::string ExpectWord(std::string_view what);
  // Skips a bracketed group starting at the next token ('[', '(' or '{' up to its match); false when none starts.
  bool SkipGroup();
  // The rest of the statement as text, for messages (at most 40 characters).
  std::string Rest() const;
  [[noreturn]] void Fail(const std::string& message) const;
  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  std::vector<Token> tokens_;
  std::size_t at_ = 0;
  std::string file_;
  int line_ = 0;
};

}  // namespace waam::planner::internal
