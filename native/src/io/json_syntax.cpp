// JSON syntax errors without the parser's internals (see json_syntax.h).
#include "anisomesh/io/json_syntax.h"

#include <nlohmann/json.hpp>

#include "anisomesh/core/error.h"

namespace anisomesh {

void checkJsonSyntax(const std::string& text) {
  if (nlohmann::json::accept(text)) return;
  std::string what = "not JSON";
  try {
    const nlohmann::json unused = nlohmann::json::parse(text);
    (void)unused;
  } catch (const nlohmann::json::parse_error& e) {
    what = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax error while
    // parsing value - invalid literal; last read: 'tru,'" -> "line 1, column 5: invalid literal; ..."
    const size_t bracket = what.find("] ");
    if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) what = what.substr(bracket + 2);
    if (what.rfind("parse error at ", 0) == 0) what = what.substr(15);
    const size_t dash = what.find(" - ");
    const size_t colon = what.find(": ");
    if (colon != std::string::npos && dash != std::string::npos && dash > colon)
      what = what.substr(0, colon + 2) + what.substr(dash + 3);
  }
  throw Error(ErrorCode::ParseError, "(root): malformed JSON at " + what);
}

}  // namespace anisomesh
