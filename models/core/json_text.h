#ifndef WAAM_MODELS_CORE_JSON_TEXT_H_
#define WAAM_MODELS_CORE_JSON_TEXT_H_

// The text of a JSON document the project writes (output files, pages, the Python API's documents).
#include <string>

#include <nlohmann/json.hpp>

namespace waam {

// `document` as JSON text (indented by `indent` spaces; -1: on one line). Text that is not UTF-8 (a Latin-1 comment
// or name from a controller's export, a scenario's bytes) is written with U+FFFD in place of each invalid sequence,
// not refused: nlohmann's default throws (type_error 316) and the command would end in an internal error.
inline std::string JsonText(const nlohmann::json& document, int indent = 2) {
  return document.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace waam

#endif  // WAAM_MODELS_CORE_JSON_TEXT_H_
