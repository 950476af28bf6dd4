// The two kinds of failure (as in Drake): InputError for anything a user can cause (OutputError, one of them, for an
// output that cannot be written), InternalError (WAAM_DEMAND) for the code's own mistakes.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace waam {

namespace internal {
// `message` with every control character (a byte below 0x20, or 0x7f) written as \n, \r, \t or \xNN, so the user's
// bytes a message quotes (a token, a cell, a key) cannot break it over lines or rewrite the terminal.
inline std::string OneLine(const std::string& message) {
  static const char kHex[] = "0123456789abcdef";
  std::string line;
  line.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      line.push_back(c);
    } else if (c == '\n') {
      line += "\\n";
    } else if (c == '\r') {
      line += "\\r";
    } else if (c == '\t') {
      line += "\\t";
    } else {
      line += "\\x";
      line.push_back(kHex[byte >> 4]);
      line.push_back(kHex[byte & 0xf]);
    }
  }
  return line;
}
}  // namespace internal

// Thrown for bad input a user can fix: a broken mesh, a malformed scenario, a CSV with text in a number.
// The message is one line that names the file (or key) and the place, and says what rule was broken; control
// characters in it (a newline, carriage return or NUL in a quoted token of the user's file) are escaped as \n, \r,
// \t, \xNN (internal::OneLine). The CLI prints it and exits with code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(internal::OneLine(message)) {}
};

// Thrown when an output cannot be written (disk full, no permission, a path that is a file): the message is one line
// "cannot write <path>: <reason>". A user can fix it, so it is an InputError: the CLI prints it and exits with code 2.
class OutputError : public InputError {
 public:
  explicit OutputError(const std::string& message) : InputError(message) {}
};

// Thrown by WAAM_DEMAND when an invariant of the code itself fails: a bug, not bad input. The message names the
// file, line and condition; the CLI prints it as an internal error and exits with code 1.
class InternalError : public std::logic_error {
 public:
  explicit InternalError(const std::string& message) : std::logic_error(message) {}
};

namespace internal {
[[noreturn]] inline void DemandFailed(const char* condition, const char* file, int line) {
  std::ostringstream message;
  message << file << ":" << line << ": internal check failed: " << condition << " (please report this)";
  throw InternalError(message.str());
}
}  // namespace internal

// Thrown when a long run is interrupted (SIGINT); the CLI removes partial outputs and exits with code 130.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace waam

// Throws waam::InputError with a streamed message unless `condition` holds, e.g.
//   WAAM_THROW_UNLESS(h > 0, "scenario slicing.layer_height_mm = " << h << ": must be > 0");
#define WAAM_THROW_UNLESS(condition, message)        \
  do {                                               \
    if (!(condition)) {                              \
      std::ostringstream waam_throw_stream_;         \
      waam_throw_stream_ << message;                 \
      throw ::waam::InputError(waam_throw_stream_.str()); \
    }                                                \
  } while (false)

// Throws waam::InputError with a streamed message (a throw expression, so the compiler knows it does not return).
#define WAAM_THROW(message)    \
  throw ::waam::InputError([&] { \
    std::ostringstream waam_throw_stream_; \
    waam_throw_stream_ << message; \
    return waam_throw_stream_.str(); \
  }())

// Checks an invariant of the code itself (Drake's DRAKE_DEMAND), never a user's input (use WAAM_THROW_UNLESS for
// that): throws waam::InternalError naming the file, line and condition unless `condition` holds.
#define WAAM_DEMAND(condition)                                                        \
  do {                                                                                \
    if (!(condition)) ::waam::internal::DemandFailed(#condition, __FILE__, __LINE__); \
  } while (false)
