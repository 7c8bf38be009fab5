#include "anisomesh/io/file_io.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"

namespace anisomesh {
namespace {

std::atomic<std::int64_t> gMaxInputBytes{std::int64_t(512) << 20};

// The folder and the file name of path ("." for a bare name).
void splitPath(const std::string& path, std::string* dir, std::string* name) {
  const size_t slash = path.find_last_of('/');
  *dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  *name = slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

std::int64_t defaultMaxInputBytes() { return gMaxInputBytes.load(); }

void setDefaultMaxInputBytes(std::int64_t bytes) {
  require(bytes > 0, ErrorCode::InvalidArgument, "the input size limit must be positive");
  gMaxInputBytes.store(bytes);
}

std::string readTextFile(const std::string& path, const ReadFileOptions& options) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  require(f != nullptr, ErrorCode::IoError, "cannot open '" + path + "' for reading: " + std::strerror(errno));
  struct stat st {};
  const bool known = fstat(fileno(f), &st) == 0;
  if (known) {
    std::string refused;
    if (S_ISDIR(st.st_mode))
      refused = "'" + path + "' is a directory";
    else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))
      refused = "'" + path + "' is a device, not a file";
    else if (S_ISREG(st.st_mode) && std::int64_t(st.st_size) > options.maxBytes)
      refused = "'" + path + "' holds " + std::to_string(std::int64_t(st.st_size)) +
                " bytes, above the input limit of " + std::to_string(options.maxBytes) + " bytes";
    if (!refused.empty()) {
      std::fclose(f);
      throw Error(ErrorCode::IoError, refused);
    }
  }
  std::string out;
  // A regular file: one read into a string of its size. Anything else (a pipe, a device)
  // or a file that grows meanwhile: the rest in 64 KiB steps.
  const long long size = known && S_ISREG(st.st_mode) ? (long long)st.st_size : -1;
  if (size > 0) {
    out.resize(size_t(size));
    out.resize(std::fread(&out[0], 1, size_t(size), f));
  }
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {
    out.append(buf, n);
    if (std::int64_t(out.size()) > options.maxBytes) {  // a pipe, or a file that grew
      std::fclose(f);
      throw Error(ErrorCode::IoError,
                  "'" + path + "' holds more than the input limit of " + std::to_string(options.maxBytes) + " bytes");
    }
  }
  // ferror also catches a directory opened as a file (EISDIR on the first read).
  const bool failed = std::ferror(f) != 0;
  const std::string why = failed ? std::strerror(errno) : "";
  std::fclose(f);
  require(!failed, ErrorCode::IoError, "error while reading '" + path + "': " + why);
  return out;
}

TextFileView::TextFileView(const std::string& path, const ReadFileOptions& options) {
  const long page = sysconf(_SC_PAGESIZE);
  struct stat st {};
  // A map only for a regular file within the limit whose size is not a whole number of
  // pages: the rest of its last page reads as zeros (the NUL after the text). Anything
  // else, and any failure, goes through readTextFile (and its errors).
  if (page > 0 && stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
      std::int64_t(st.st_size) <= options.maxBytes && st.st_size % page != 0) {
    const int fd = open(path.c_str(), O_RDONLY);
    if (fd >= 0) {
      struct stat fst {};
      if (fstat(fd, &fst) == 0 && fst.st_size == st.st_size) {
        void* m = mmap(nullptr, size_t(fst.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
        if (m != MAP_FAILED) {
          map_ = m;
          mapSize_ = size_t(fst.st_size);
        }
      }
      close(fd);
    }
  }
  if (map_) {
    begin_ = released_ = static_cast<const char*>(map_);
    end_ = begin_ + mapSize_;
    madvise(map_, mapSize_, MADV_SEQUENTIAL);
    return;
  }
  text_ = readTextFile(path, options);
  begin_ = released_ = text_.data();
  end_ = begin_ + text_.size();
}

TextFileView::~TextFileView() {
  if (map_) munmap(map_, mapSize_);
}

void TextFileView::release(const char* p) {
  if (!map_ || p <= released_) return;
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  const size_t upTo = size_t(std::min(p, end_) - begin_) / page * page;  // whole pages before p
  const size_t from = size_t(released_ - begin_);
  if (upTo <= from) return;
  madvise(const_cast<char*>(begin_) + from, upTo - from, MADV_DONTNEED);
  released_ = begin_ + upTo;
}

int removeStaleTemporaries(const std::string& path) {
  std::string dir, name;
  splitPath(path, &dir, &name);
  const std::string prefix = name + ".tmp-";
  DIR* d = opendir(dir.c_str());
  if (!d) return 0;
  int removed = 0;
  while (const dirent* e = readdir(d)) {
    const std::string entry = e->d_name;
    if (entry.compare(0, prefix.size(), prefix) != 0) continue;
    // path.tmp-PID-...: the writer's process id comes first.
    char* end = nullptr;
    const long pid = std::strtol(entry.c_str() + prefix.size(), &end, 10);
    if (end == entry.c_str() + prefix.size() || *end != '-' || pid <= 0 || pid == long(getpid())) continue;
    if (kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // still running (or unknown): keep it
    std::string path = dir;
    path += '/';
    path += entry;
    if (std::remove(path.c_str()) == 0) ++removed;
  }
  closedir(d);
  return removed;
}

namespace {

// Bytes at most per pwrite: the slices are written in parallel chunks, so the kernel's copy
// into the page cache (half of a 1e6-triangle output's write time here) runs on every thread.
constexpr size_t kWriteSlice = size_t(1) << 20;

// The text [data, data + size) of each view, one after another, to path (see writeTextFileAtomic).
void writeViewsAtomic(const std::string& path, const std::vector<std::pair<const char*, size_t>>& views) {
  require(!path.empty(), ErrorCode::IoError, "empty output path");
  removeStaleTemporaries(path);
  // A unique sibling name, so the rename stays on one file system; the process id first,
  // so a later write can tell a dead writer's leftover from a running one's file.
  std::random_device rd;
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::string tmp =
      path + ".tmp-" + std::to_string(long(getpid())) + "-" + std::to_string(rd()) + "-" + std::to_string(stamp);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  require(fd >= 0, ErrorCode::IoError, "cannot create '" + tmp + "' to write '" + path + "': " + std::strerror(errno));
  // Slices of at most kWriteSlice bytes at their file offsets, written in parallel chunks.
  struct Slice {
    const char* data;
    size_t size;
    off_t offset;
  };
  std::vector<Slice> slices;
  off_t offset = 0;
  for (const auto& [data, size] : views)
    for (size_t at = 0; at < size; at += kWriteSlice) {
      const size_t n = std::min(kWriteSlice, size - at);
      slices.push_back({data + at, n, offset});
      offset += off_t(n);
    }
  std::atomic<bool> written{true};
  parallelChunks(slices.size(), 1, [&](size_t, size_t b, size_t e) {
    for (size_t k = b; k < e && written.load(std::memory_order_relaxed); ++k) {
      const Slice& sl = slices[k];
      for (size_t done = 0; done < sl.size;) {
        const ssize_t w = ::pwrite(fd, sl.data + done, sl.size - done, sl.offset + off_t(done));
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
          written = false;
          return;
        }
        done += size_t(w);
      }
    }
  });
  const bool closed = ::close(fd) == 0;
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

}  // namespace

void writeTextFileAtomic(const std::string& path, const std::string& contents) {
  writeViewsAtomic(path, {{contents.data(), contents.size()}});
}

void writeTextFileAtomic(const std::string& path, const std::vector<std::string>& pieces) {
  std::vector<std::pair<const char*, size_t>> views;
  views.reserve(pieces.size());
  for (const std::string& p : pieces) views.emplace_back(p.data(), p.size());
  writeViewsAtomic(path, views);
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
