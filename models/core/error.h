// Error types shared by every module: InputError for anything a user can cause.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace waam {

// Thrown for bad input a user can fix: a broken mesh, a malformed scenario, a CSV with text in a number.
// The message is one line that names the file (or key) and the place, and says what rule was broken.
// The CLI prints it and exits with code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

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
