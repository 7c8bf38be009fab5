#pragma once
// Numbers in messages as the user wrote them: the shortest text that reads back as the same
// double (5 -> "5", 0.1 -> "0.1", 1e-300 -> "1e-300"), not std::to_string's "5.000000".
#include <string>

namespace anisomesh {

// The shortest %g text (1 to 17 significant digits) that parses back to v; "nan", "inf", "-inf".
std::string numberText(double v);

// Appends the 64 bits of x in hex and a space: distinct for distinct doubles (and for +0 / -0),
// for exact cache keys.
void appendDoubleBits(std::string& out, double x);

}  // namespace anisomesh
