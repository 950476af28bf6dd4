// The program readers' tokenizer and token cursor.
#include "planner/program/program_tokens.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "models/core/error.h"

namespace waam::planner::internal {
namespace {

bool IsWordStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '$' || c == '#'; }
bool IsWordChar(char c) { return IsWordStart(c) || std::isdigit(static_cast<unsigned char>(c)) || c == '.'; }
bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The length of the number at text[i] (digits, fraction, exponent), 0 when none starts there.
std::size_t NumberLength(std::string_view text, std::size_t i) {
  std::size_t k = i;
  while (k < text.size() && IsDigit(text[k])) ++k;
  const bool int_digits = k > i;
  if (k < text.size() && text[k] == '.') {
    std::size_t f = k + 1;
    while (f < text.size() && IsDigit(text[f])) ++f;
    if (!int_digits && f == k + 1) return 0;  // a lone '.'
    k = f;
  } else if (!int_digits) {
    return 0;
  }
  if (k < text.size() && (text[k] == 'e' || text[k] == 'E')) {
    std::size_t e = k + 1;
    if (e < text.size() && (text[e] == '+' || text[e] == '-')) ++e;
    if (e < text.size() && IsDigit(text[e])) {
      while (e < text.size() && IsDigit(text[e])) ++e;
      k = e;
    }
  }
  return k - i;
}

}  // namespace

std::vector<Token> Tokenize(std::string_view text) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    Token t;
    const std::size_t start = i;
    if (const std::size_t n = NumberLength(text, i); n > 0) {
      t.kind = TokenKind::kNumber;
      t.text = std::string(text.substr(i, n));
      const auto [end, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), t.number);
      if (ec != std::errc() || !std::isfinite(t.number)) t.kind = TokenKind::kSymbol;  // 1e999: no number
      i += n;
    } else if (IsWordStart(c)) {
      std::size_t k = i;
      while (k < text.size() && IsWordChar(text[k])) ++k;
      t.kind = TokenKind::kWord;
      for (std::size_t j = i; j < k; ++j) t.text += static_cast<char>(std::toupper(static_cast<unsigned char>(text[j])));
      i = k;
    } else if (c == '\'' || c == '"') {
      std::size_t close = text.find(c, i + 1);
      if (close == std::string_view::npos) close = text.size();
      t.kind = TokenKind::kString;
      t.text = std::string(text.substr(i + 1, close - i - 1));
      i = close + 1;
    } else {
      t.kind = TokenKind::kSymbol;
      t.text = std::string(1, c);
      ++i;
    }
    t.raw = std::string(text.substr(start, i - start));
    out.push_back(std::move(t));
  }
  return out;
}

TokenCursor::TokenCursor(std::string_view text, const std::string& file, int line)
    : tokens_(Tokenize(text)), file_(file), line_(line) {}

const Token& TokenCursor::Peek(std::size_t ahead) const {
  static const Token kEndToken;
  return at_ + ahead < tokens_.size() ? tokens_[at_ + ahead] : kEndToken;
}

const Token& TokenCursor::Next() {
  const Token& t = Peek();
  if (at_ < tokens_.size()) ++at_;
  return t;
}

bool TokenCursor::Is(std::string_view text, std::size_t ahead) const {
  const Token& t = Peek(ahead);
  return (t.kind == TokenKind::kWord || t.kind == TokenKind::kSymbol) && t.text == text;
}

bool TokenCursor::Accept(std::string_view text) {
  if (!Is(text)) return false;
  ++at_;
  return true;
}

void TokenCursor::Expect(std::string_view text, std::string_view context) {
  if (!Accept(text)) Fail(std::string(context) + ": expected '" + std::string(text) + "' at '" + Rest() + "'");
}

bool TokenCursor::PeekNumber() const {
  if (Peek().kind == TokenKind::kNumber) return true;
  return (Is("-") || Is("+")) && Peek(1).kind == TokenKind::kNumber;
}

double TokenCursor::ExpectNumber(std::string_view what) {
  double sign = 1.0;
  if (Accept("-")) {
    sign = -1.0;
  } else {
    Accept("+");
  }
  if (Peek().kind != TokenKind::kNumber) Fail(std::string(what) + " '" + Peek().raw + "' is not a finite number");
  return sign * Next().number;
}

int TokenCursor::ExpectInteger(std::string_view what, int lo, int hi) {
  const double v = ExpectNumber(what);
  if (!(v >= lo && v <= hi && v == std::floor(v))) {
    std::string text = std::to_string(v);
    Fail(std::string(what) + " " + text.substr(0, 20) + " must be a whole number in [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  }
  return static_cast<int>(v);
}

std::string TokenCursor::ExpectWord(std::string_view what) {
  if (Peek().kind != TokenKind::kWord) Fail("expected " + std::string(what) + " at '" + Rest() + "'");
  return Next().text;
}

bool TokenCursor::SkipGroup() {
  const std::string open = Peek().kind == TokenKind::kSymbol ? Peek().text : "";
  if (open != "[" && open != "(" && open != "{") return false;
  const std::string close = open == "[" ? "]" : (open == "(" ? ")" : "}");
  int depth = 0;
  while (!AtEnd()) {
    const Token& t = Next();
    if (t.kind != TokenKind::kSymbol) continue;
    if (t.text == open) ++depth;
    if (t.text == close && --depth == 0) return true;
  }
  Fail("'" + open + "' without its '" + close + "'");
}

std::string TokenCursor::Rest() const {
  std::string out;
  for (std::size_t k = at_; k < tokens_.size() && out.size() < 40; ++k) {
    if (!out.empty() && tokens_[k].kind != TokenKind::kSymbol) out += ' ';
    out += tokens_[k].raw;
  }
  return out.substr(0, 40);
}

void TokenCursor::Fail(const std::string& message) const { WAAM_THROW(file_ << ":" << line_ << ": " << message); }

}  // namespace waam::planner::internal
