#pragma once
// Whole-file text I/O. Writes are atomic (temporary file in the same folder, then
// rename), so a failed run never leaves a partial output file.
#include <string>
#include <vector>

namespace anisomesh {

// Contents of the file at path; throws IoError naming the path when it cannot be read.
std::string readTextFile(const std::string& path);

// Writes contents to path through a temporary sibling file and a rename; throws IoError
// (and removes the temporary) on any failure, leaving path untouched.
void writeTextFileAtomic(const std::string& path, const std::string& contents);

// The same for contents given as consecutive pieces (no joined copy in memory).
void writeTextFileAtomic(const std::string& path, const std::vector<std::string>& pieces);

// Lower-case extension without the dot ("mesh" for "a/b.MESH"), empty when there is none.
std::string fileExtension(const std::string& path);

}  // namespace anisomesh
