#include "anisomesh/io/file_io.h"

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>

#include <sys/stat.h>

#include "anisomesh/core/error.h"

namespace anisomesh {

std::string readTextFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  require(f != nullptr, ErrorCode::IoError, "cannot open '" + path + "' for reading: " + std::strerror(errno));
  std::string out;
  // A regular file: one read into a string of its size. Anything else (a pipe, a device)
  // or a file that grows meanwhile: the rest in 64 KiB steps.
  struct stat st;
  const long long size = ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) ? (long long)st.st_size : -1;
  if (size > 0) {
    out.resize(size_t(size));
    out.resize(std::fread(&out[0], 1, size_t(size), f));
  }
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  // ferror also catches a directory opened as a file (EISDIR on the first read).
  const bool failed = std::ferror(f) != 0;
  const std::string why = failed ? std::strerror(errno) : "";
  std::fclose(f);
  require(!failed, ErrorCode::IoError, "error while reading '" + path + "': " + why);
  return out;
}

void writeTextFileAtomic(const std::string& path, const std::string& contents) {
  writeTextFileAtomic(path, std::vector<std::string>{contents});
}

void writeTextFileAtomic(const std::string& path, const std::vector<std::string>& pieces) {
  require(!path.empty(), ErrorCode::IoError, "empty output path");
  // A unique sibling name, so the rename stays on one file system.
  std::random_device rd;
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::string tmp = path + ".tmp-" + std::to_string(rd()) + "-" + std::to_string(stamp);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  require(f != nullptr, ErrorCode::IoError,
          "cannot create '" + tmp + "' to write '" + path + "': " + std::strerror(errno));
  bool written = true;
  for (const std::string& p : pieces) written = written && std::fwrite(p.data(), 1, p.size(), f) == p.size();
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    std::remove(tmp.c_str());
    throw Error(ErrorCode::IoError, "cannot write '" + path + "' (disk full or I/O error)");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw Error(ErrorCode::IoError, "cannot move the output into '" + path + "': " + why);
  }
}

std::string fileExtension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

}  // namespace anisomesh
