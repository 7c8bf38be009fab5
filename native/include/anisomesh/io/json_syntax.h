#pragma once
// JSON syntax errors in the user's words: ParseError "(root): malformed JSON at line L,
// column C: <what the lexer saw>", without nlohmann's "[json.exception.parse_error.101]".
#include <string>

namespace anisomesh {

// Throws ParseError when text is not well-formed JSON; returns otherwise.
void checkJsonSyntax(const std::string& text);

}  // namespace anisomesh
