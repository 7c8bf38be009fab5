#pragma once
// JSON text checks shared by the case readers: failures nlohmann's parser reports without
// a place (a number overflowing a double, such as 1e999) get the JSON path of the value.
#include <string>

namespace anisomesh {

// The JSON path ("controlSpace.hmax", "sources[2].radius", "(root)") of the first number
// in text that does not fit a double, or "" when there is none (or the text is malformed
// before reaching one).
std::string jsonOverflowPath(const std::string& text);

// Throws ParseError "PATH: number overflow: the value does not fit a double" when text
// holds such a number (call it when nlohmann's parser reports out_of_range 406).
void requireNoJsonNumberOverflow(const std::string& text);

// ParseError when the text holds a NUL byte (nlohmann's parser stops there: a valid case
// followed by a NUL and garbage was read as the case alone).
void requireNoNulByte(const std::string& text);

}  // namespace anisomesh
