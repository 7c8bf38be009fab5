#pragma once
// Numbers in messages as the user wrote them: the shortest text that reads back as the same
// double (5 -> "5", 0.1 -> "0.1", 1e-300 -> "1e-300"), not std::to_string's "5.000000".
#include <string>

namespace anisomesh {

// The shortest %g text (1 to 17 significant digits) that parses back to v; "nan", "inf", "-inf".
std::string numberText(double v);

// Writes v into buf (32 chars or more) as printf's "%.17g" does, byte for byte, and returns
// the length: exact integer arithmetic for |v| in [1e-5, 1e17) (coordinates, metrics),
// snprintf otherwise (and for 0, subnormals, inf, NaN). The writers use it where the library
// has no floating std::to_chars (libc++ 13 in the wasm build), whose snprintf took 0.67 s of
// a 1e6-triangle writeMesh against 0.09 s natively.
int formatG17(double v, char* buf);

// Appends the 64 bits of x in hex and a space: distinct for distinct doubles (and for +0 / -0),
// for exact cache keys.
void appendDoubleBits(std::string& out, double x);

}  // namespace anisomesh
