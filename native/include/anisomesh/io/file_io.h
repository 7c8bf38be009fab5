#pragma once
// Whole-file text I/O. Reads are bounded (a size limit checked before reading, character
// devices and directories refused), so /dev/zero or a huge file cannot exhaust memory.
// Writes are atomic (temporary file in the same folder, then rename), so a failed run
// never leaves a partial output file; the temporary of a run killed while writing is
// removed by the next write to the same target.
#include <cstdint>
#include <string>
#include <vector>

namespace anisomesh {

// The input size limit readTextFile applies by default (initially 512 MiB).
std::int64_t defaultMaxInputBytes();
// Changes that default (e.g. the CLI's --max-input-bytes); throws InvalidArgument unless > 0.
void setDefaultMaxInputBytes(std::int64_t bytes);

struct ReadFileOptions {
  std::int64_t maxBytes = defaultMaxInputBytes();  // larger inputs are refused (IoError) before reading
};

// Contents of the file at path; throws IoError naming the path when it cannot be read,
// is a directory or a character device (such as /dev/zero), or holds more than
// options.maxBytes bytes (checked up front for regular files, while reading for pipes).
std::string readTextFile(const std::string& path, const ReadFileOptions& options = {});

// The text of the file at path for a parser that reads it once from front to back: a
// read-only memory map of a regular file where the system has one, so the parsed pages
// can be given back while the parse goes on (a large input is then not held in full
// beside what it is parsed into); otherwise the text read as readTextFile does. The same
// checks and errors as readTextFile. The text is followed by a NUL byte.
class TextFileView {
 public:
  explicit TextFileView(const std::string& path, const ReadFileOptions& options = {});
  ~TextFileView();
  TextFileView(const TextFileView&) = delete;
  TextFileView& operator=(const TextFileView&) = delete;
  const char* begin() const { return begin_; }
  const char* end() const { return end_; }
  // Gives the whole pages before p back to the system (a map only; read again from the
  // file when touched later).
  void release(const char* p);

 private:
  std::string text_;  // when not mapped
  void* map_ = nullptr;
  size_t mapSize_ = 0;
  const char* begin_ = nullptr;
  const char* end_ = nullptr;
  const char* released_ = nullptr;
};

// Writes contents to path through a temporary sibling file (path.tmp-PID-...) and a
// rename; throws IoError (and removes the temporary) on any failure, leaving path
// untouched. Temporaries of path left by processes that no longer run are removed first.
void writeTextFileAtomic(const std::string& path, const std::string& contents);

// The same for contents given as consecutive pieces (no joined copy in memory).
void writeTextFileAtomic(const std::string& path, const std::vector<std::string>& pieces);
// Removes the temporaries path.tmp-PID-* whose process PID no longer runs (what a kill
// during writeTextFileAtomic leaves); returns how many were removed.
int removeStaleTemporaries(const std::string& path);

// Lower-case extension without the dot ("mesh" for "a/b.MESH"), empty when there is none.
std::string fileExtension(const std::string& path);

}  // namespace anisomesh
