#pragma once
// Private: whitespace tokenizer with line numbers for the text mesh formats, so every
// parse error can name the line and what was expected.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <fast_float/fast_float.h>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/core/types.h"

namespace anisomesh {
namespace io_detail {

struct Token {
  const char* begin;
  size_t size;
  int line;
  std::string str() const { return std::string(begin, size); }
};

// A message given as text, or as a callable building it on demand.
inline std::string describe(const std::string& s) { return s; }
inline std::string describe(const char* s) { return s; }
template <class F, class = decltype(std::declval<const F&>()())>
std::string describe(const F& f) {
  return f();
}

class TokenStream {
 public:
  // Scans text lazily (constant memory, also for huge meshes); everything from
  // commentChar (when nonzero) to the end of a line is dropped.
  TokenStream(const std::string& text, std::string format, char commentChar, int firstLine = 1)
      : TokenStream(text.data(), text.data() + text.size(), std::move(format), commentChar, firstLine) {}
  // The text [begin, end), which must be followed by a NUL byte (as a std::string's) and
  // stay alive for the whole parse.
  TokenStream(const char* begin, const char* end, std::string format, char commentChar, int firstLine = 1)
      : format_(std::move(format)), comment_(commentChar), line_(firstLine), lastLine_(firstLine) {
    p_ = begin;
    end_ = end;
    skipSpace();
  }
  TokenStream(const TokenStream&) = delete;
  TokenStream& operator=(const TokenStream&) = delete;

  bool atEnd() const { return p_ >= end_; }
  // The next token without consuming it (atEnd() must be false).
  Token peek() const {
    const char* b = p_;
    const char* e = b;
    while (e < end_ && !isSpace(*e) && !(comment_ && *e == comment_)) ++e;
    return {b, size_t(e - b), line_};
  }
  // Consumes the next token; fails at the end of the text.
  Token next() {
    if (atEnd()) fail("more data");
    const Token t = peek();
    lastLine_ = t.line;
    p_ += t.size;
    skipSpace();
    return t;
  }
  // The line of the next token, or at the end the line of the last one.
  int line() const { return atEnd() ? lastLine_ : line_; }

  [[noreturn]] void fail(const std::string& expected) const {
    const std::string got = atEnd() ? std::string("end of file") : "'" + peek().str() + "'";
    throw Error(ErrorCode::ParseError,
                format_ + " line " + std::to_string(line()) + ": expected " + expected + ", got " + got);
  }
  [[noreturn]] void failAt(int line, const std::string& message) const {
    throw Error(ErrorCode::ParseError, format_ + " line " + std::to_string(line) + ": " + message);
  }

  // The next token as a double; fails naming what was expected, or when the value
  // overflows a double (underflow gives the nearest representable value, as strtod).
  // what is a string or a callable returning one (built only on failure: hot loops).
  template <class What>
  double number(const What& what) {
    if (atEnd()) fail(describe(what));
    double v = 0.0;
    bool overflow = false;
    const char* stop = parseDouble(p_, end_, &v, &overflow);
    if (stop == p_ || !endsToken(stop)) fail(describe(what));
    if (overflow) failAt(line_, describe(what) + " '" + peek().str() + "' overflows a double");
    advance(stop);
    return v;
  }
  // The next token as an integer; fails naming what was expected (also on overflow).
  template <class What>
  long long integer(const What& what) {
    if (atEnd()) fail(describe(what));
    long long v = 0;
    const char* b = p_;
    if (b < end_ && *b == '+' && b + 1 < end_ && b[1] != '-') ++b;  // strtoll's sign, kept
    const std::from_chars_result r = std::from_chars(b, end_, v);
    if (r.ptr == b || !endsToken(r.ptr)) fail(describe(what));
    if (r.ec == std::errc::result_out_of_range)
      failAt(line_, describe(what) + " '" + peek().str() + "' does not fit in a 64-bit integer");
    advance(r.ptr);
    return v;
  }
  // The next token as an integer that fits in int32 (element and vertex references):
  // larger values are refused, never truncated.
  template <class What>
  int int32(const What& what) {
    const int ln = line();
    const long long v = integer(what);
    if (v < INT_MIN || v > INT_MAX)
      failAt(ln, describe(what) + " " + std::to_string(v) + " does not fit in a 32-bit integer");
    return int(v);
  }
  // A count: a nonnegative integer that the remaining text can hold (every token takes
  // at least two characters with its separator), which guards huge allocations.
  long long count(const std::string& what, int tokensPerItem) {
    const int ln = line();
    const long long n = integer(what);
    if (n < 0) failAt(ln, "expected " + what + " (a nonnegative integer), got " + std::to_string(n));
    const long long room = (long long)(end_ - p_) / 2 + 1;
    if (tokensPerItem > 0 && n > room / tokensPerItem + 1)
      failAt(ln, what + " " + std::to_string(n) + " is larger than the data that follows");
    return n;
  }
  const std::string& format() const { return format_; }
  // Called by lineRecords with the end of each batch of lines it has parsed (the text
  // before it is not read again unless the section falls back to token-by-token reading).
  void setRelease(std::function<void(const char*)> release) { release_ = std::move(release); }

  // Reads the tokens of one line (LineRecords below); every read is false when the token
  // is missing, would end the line early or is refused by the token-by-token reading.
  class LineCursor {
   public:
    LineCursor(const char* p, const char* end, char comment) : p_(p), end_(end), comment_(comment) {}
    bool number(double* v) {
      if (!startToken()) return false;
      bool overflow = false;
      const char* stop = parseDouble(p_, end_, v, &overflow);
      if (stop == p_ || !endsHere(stop) || overflow) return false;
      p_ = stop;
      return true;
    }
    bool integer(long long* v) {
      if (!startToken()) return false;
      const char* b = p_;
      if (b < end_ && *b == '+' && b + 1 < end_ && b[1] != '-') ++b;  // as TokenStream::integer
      const std::from_chars_result r = std::from_chars(b, end_, *v);
      if (r.ptr == b || !endsHere(r.ptr) || r.ec == std::errc::result_out_of_range) return false;
      p_ = r.ptr;
      return true;
    }
    // Only blanks up to the end of the line: consumes it, true.
    bool endLine() {
      while (p_ < end_ && isBlank(*p_)) ++p_;
      if (p_ >= end_) return true;
      if (*p_ != '\n') return false;
      ++p_;
      return true;
    }

   private:
    static bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
    bool startToken() {
      while (p_ < end_ && isBlank(*p_)) ++p_;
      return p_ < end_ && *p_ != '\n' && *p_ != comment_;
    }
    bool endsHere(const char* q) const { return q >= end_ || isSpace(*q); }
    const char* p_;
    const char* end_;
    char comment_;
  };

  // n records, one per line (what every writer produces), read in parallel chunks of lines
  // (parallel.h): record(i, cursor) reads record i from its line and returns false when it
  // refuses a value. The values are the ones the token-by-token reading gives, for any
  // thread count. Returns false, consuming nothing, when a line holds anything else (a
  // record split over lines, two on one line, a comment, a refused value): the caller
  // then reads the section token by token, with its messages. Small sections: false.
  template <class Record>
  bool lineRecords(long long n, const Record& record) {
    constexpr long long kMinRecords = 1 << 14;
    constexpr size_t kChunkLines = 1 << 14;
    // Chunks found and parsed per batch (a few MB of text): the text is scanned once, batch
    // by batch, and each parsed batch is handed to release_.
    constexpr size_t kBatchChunks = 16;
    if (n < kMinRecords || atEnd()) return false;
    const size_t records = size_t(n);
    const size_t chunks = chunkCount(records, kChunkLines);
    std::vector<const char*> start(kBatchChunks + 1);
    std::vector<char> ok(kBatchChunks, 0);
    const char* q = p_;
    for (size_t first = 0; first < chunks; first += kBatchChunks) {
      const size_t batch = std::min(kBatchChunks, chunks - first);
      for (size_t c = 0; c < batch; ++c) {
        start[c] = q;
        const size_t lines = std::min(kChunkLines, records - (first + c) * kChunkLines);
        for (size_t l = 0; l < lines; ++l) {
          if (q >= end_) return false;  // fewer lines than records
          const void* nl = std::memchr(q, '\n', size_t(end_ - q));
          q = nl ? static_cast<const char*>(nl) + 1 : end_;
        }
      }
      start[batch] = q;
      std::fill(ok.begin(), ok.end(), char(0));
      parallelChunks(batch, 1, [&](size_t c, size_t, size_t) {
        LineCursor cursor(start[c], end_, comment_);
        const size_t last = std::min(records, (first + c + 1) * kChunkLines);
        for (size_t i = (first + c) * kChunkLines; i < last; ++i)
          if (!record(i, cursor) || !cursor.endLine()) return;
        ok[c] = 1;
      });
      for (size_t c = 0; c < batch; ++c)
        if (!ok[c]) return false;
      if (release_) release_(q);
    }
    lastLine_ = line_ + int(n - 1);
    line_ += int(q > p_ && q[-1] == '\n' ? n : n - 1);
    p_ = q;
    skipSpace();
    return true;
  }

 private:
  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
  // True when a token may end at q (end of text, a blank or a comment).
  bool endsToken(const char* q) const { return q >= end_ || isSpace(*q) || (comment_ && *q == comment_); }
  // Consumes the token ending at stop.
  void advance(const char* stop) {
    lastLine_ = line_;
    p_ = stop;
    skipSpace();
  }
  // Parses a double at b: fast_float's from_chars (correctly rounded, as strtod, natively
  // and in wasm), strtod for what it refuses (a '+' sign, hexadecimal) and for infinities
  // (strtod tells an overflow from a written "inf"): the same value either way. Returns the
  // end of the number (b if none).
  static const char* parseDouble(const char* b, const char* e, double* v, bool* overflow) {
    const fast_float::from_chars_result r = fast_float::from_chars(b, e, *v);
    if (r.ec == std::errc() && r.ptr > b && (r.ptr >= e || !isNumberChar(*r.ptr)) && !std::isinf(*v)) return r.ptr;
    // The text is NUL-terminated (a std::string) and b starts a token: strtod stops in it.
    char* stop = nullptr;
    errno = 0;
    *v = std::strtod(b, &stop);
    *overflow = errno == ERANGE && std::isinf(*v);
    return stop;
  }
  // Characters that may continue a number strtod would read further (hexadecimal, exponent).
  static bool isNumberChar(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '.' || c == '+' ||
           c == '-';
  }
  // Moves past blanks, newlines (counting them) and comments.
  void skipSpace() {
    while (p_ < end_) {
      if (*p_ == '\n') {
        ++line_;
        ++p_;
      } else if (isSpace(*p_)) {
        ++p_;
      } else if (comment_ && *p_ == comment_) {
        while (p_ < end_ && *p_ != '\n') ++p_;
      } else {
        break;
      }
    }
  }
  std::string format_;
  std::function<void(const char*)> release_;  // setRelease
  char comment_;
  int line_;
  int lastLine_ = 1;
  const char* p_ = nullptr;
  const char* end_ = nullptr;
};

// Appends v with round-trip precision: the bytes of printf's %.17g (std::to_chars with
// precision 17 is specified to match it; snprintf where the library lacks floating to_chars).
inline void appendNumber(std::string* out, double v) {
  char buf[32];
#if defined(__cpp_lib_to_chars)
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17);
  out->append(buf, size_t(r.ptr - buf));
#else
  const int n = std::snprintf(buf, sizeof buf, "%.17g", v);
  out->append(buf, size_t(n));
#endif
}

// Appends "x y z\n" (each as appendNumber writes it).
inline void appendXyzLine(std::string* out, const Vec3& p) {
  appendNumber(out, p.x());
  out->push_back(' ');
  appendNumber(out, p.y());
  out->push_back(' ');
  appendNumber(out, p.z());
  out->push_back('\n');
}

inline void appendInt(std::string* out, long long v) {
  char buf[24];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  out->append(buf, size_t(r.ptr - buf));
}

}  // namespace io_detail
}  // namespace anisomesh
