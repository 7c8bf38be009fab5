#pragma once
// Private: whitespace tokenizer with line numbers for the text mesh formats, so every
// parse error can name the line and what was expected.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
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
#include "anisomesh/core/number_text.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/core/types.h"
#include "number_scan.h"

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
      // Plain digits ending the token: their value, as from_chars (1 to 7 digits, a
      // vertex number, read at once; or up to 17 one by one, so no overflow).
      if (kSwarDigits && end_ - p_ >= 8) {
        const uint64_t word = load8(p_);
        const int n = leadingDigits(word);
        if (n > 0 && n < 8 && isSpace(p_[n])) {
          *v = (long long)digitsValue(word, n);
          p_ += n;
          return true;
        }
      }
      unsigned long long x = 0;
      const char* q = p_;
      while (q < end_ && q - p_ < 18 && static_cast<unsigned char>(*q - '0') < 10) x = x * 10 + unsigned(*q++ - '0');
      if (q > p_ && q - p_ < 18 && endsHere(q)) {
        *v = static_cast<long long>(x);
        p_ = q;
        return true;
      }
      const char* b = p_;
      if (b < end_ && *b == '+' && b + 1 < end_ && b[1] != '-') ++b;  // as TokenStream::integer
      const std::from_chars_result r = std::from_chars(b, end_, *v);
      if (r.ptr == b || !endsHere(r.ptr) || r.ec == std::errc::result_out_of_range) return false;
      p_ = r.ptr;
      return true;
    }
    const char* position() const { return p_; }
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

  // n records, one per line (what every writer produces), read in parallel (parallel.h):
  // record(i, cursor) reads record i from its line and returns false when it refuses a
  // value. The values are the ones the token-by-token reading gives, for any thread count.
  // Returns false, consuming nothing, when a line holds anything else (a record split over
  // lines, two on one line, a comment, a refused value): the caller then reads the section
  // token by token, with its messages. Small sections: false.
  //
  // The text is cut into blocks (by size: the same for any thread count). A batch of
  // blocks has its newlines counted in parallel (so line i's block is known), then the
  // lines starting in each block (after its first newline; the first block: from the
  // start) are parsed by one task, while the next batch is counted. Each parsed batch is
  // handed to release_.
  template <class Record>
  bool lineRecords(long long n, const Record& record) {
    constexpr long long kMinRecords = 1 << 14;
    constexpr size_t kBlock = size_t(1) << 18;
    constexpr size_t kBatch = 16;  // blocks per batch (4 MiB)
    if (n < kMinRecords || atEnd()) return false;
    const size_t last = size_t(n) - 1;  // the last record's line
    const char* const begin = p_;
    const size_t size = size_t(end_ - begin);
    const size_t blocks = chunkCount(size, kBlock);
    auto blockBegin = [&](size_t k) { return begin + std::min(size, k * kBlock); };
    // newlines[k]: newlines before block k (counted up to the batch being parsed).
    std::vector<size_t> newlines(blocks + 1, 0);
    std::vector<char> ok(kBatch, 0);
    auto count = [&](size_t k) {
      newlines[k + 1] = countNewlines(blockBegin(k), size_t(blockBegin(k + 1) - blockBegin(k)));
    };
    const char* stop = nullptr;  // the end of the last record's line
    // Parses the lines of block k that hold records (block k's newlines end lines
    // newlines[k] .. newlines[k + 1] - 1; the lines after them start in it).
    auto parse = [&](size_t k) {
      const size_t lo = k == 0 ? 0 : newlines[k] + 1;
      const size_t hi = std::min(newlines[k + 1], last);
      if (lo > hi) return true;
      const char* q = begin;
      if (k > 0) q = static_cast<const char*>(std::memchr(blockBegin(k), '\n', size_t(end_ - blockBegin(k)))) + 1;
      LineCursor cursor(q, end_, comment_);
      for (size_t i = lo; i <= hi; ++i)
        if (!record(i, cursor) || !cursor.endLine()) return false;
      if (hi == last) stop = cursor.position();
      return true;
    };
    auto prefix = [&](size_t b0, size_t b1) {
      for (size_t k = b0; k < b1; ++k) newlines[k + 1] += newlines[k];
    };
    parallelChunks(std::min(kBatch, blocks), 1, [&](size_t k, size_t, size_t) { count(k); });
    prefix(0, std::min(kBatch, blocks));
    for (size_t b0 = 0; b0 < blocks; b0 += kBatch) {
      const size_t b1 = std::min(blocks, b0 + kBatch);
      // The batch holds the last record's line (or is the text's last): nothing more to count.
      const bool final = newlines[b1] >= last || b1 == blocks;
      const size_t counted = final ? 0 : std::min(kBatch, blocks - b1);
      std::fill(ok.begin(), ok.end(), char(0));
      parallelChunks(b1 - b0 + counted, 1, [&](size_t t, size_t, size_t) {
        if (t < b1 - b0)
          ok[t] = parse(b0 + t) ? 1 : 0;
        else
          count(b1 + (t - (b1 - b0)));
      });
      for (size_t t = 0; t < b1 - b0; ++t)
        if (!ok[t]) return false;
      if (final) break;
      prefix(b1, b1 + counted);
      if (release_) release_(blockBegin(b1));
    }
    if (!stop) return false;  // fewer lines than records
    if (release_) release_(stop);
    lastLine_ = line_ + int(n - 1);
    line_ += int(stop > p_ && stop[-1] == '\n' ? n : n - 1);
    p_ = stop;
    skipSpace();
    return true;
  }

  // The newlines in [p, p + n), eight bytes a word (SWAR): a byte of x = w ^ '\n'...'\n' is
  // zero where w holds a newline; ((x & 0x7f..) + 0x7f..) | x has its high bit set exactly in
  // x's nonzero bytes (no carry crosses a byte), so each byte of the sum counts its position's
  // newlines, flushed every 255 words. As fast as the former 32 byte lanes natively (which GCC
  // vectorised), 2.5-3x faster in wasm, whose scalar code kept the lanes in memory: 24-37 ms
  // for the 14 MB of a 1e5 remesh input there, now 9-12 ms.
  static size_t countNewlines(const char* p, size_t n) {
    constexpr std::uint64_t kOnes = 0x0101010101010101u, kLow7 = 0x7f7f7f7f7f7f7f7fu, kNewlines = kOnes * '\n';
    constexpr std::uint64_t kEvenBytes = 0x00ff00ff00ff00ffu;
    size_t c = 0;
    while (n >= 8) {
      const size_t words = std::min<size_t>(n / 8, 255);
      std::uint64_t counts = 0;  // per byte position, at most 255
      for (size_t k = 0; k < words; ++k, p += 8) {
        std::uint64_t w;
        std::memcpy(&w, p, 8);
        const std::uint64_t x = w ^ kNewlines;
        counts += (~(((x & kLow7) + kLow7) | x) >> 7) & kOnes;
      }
      n -= words * 8;
      const std::uint64_t pairs = (counts & kEvenBytes) + ((counts >> 8) & kEvenBytes);  // 4 sums of 2 bytes
      c += size_t((pairs * 0x0001000100010001u) >> 48);
    }
    for (size_t i = 0; i < n; ++i) c += p[i] == '\n';
    return c;
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
    // The plain forms first (number_scan.h: the same value).
    const char* q = scanDecimal(b, e, v);
    if (q && (q >= e || !isNumberChar(*q))) return q;
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

// Writes v at p with round-trip precision, the bytes of printf's %.17g (std::to_chars with
// precision 17 is specified to match it; formatG17 where the library lacks floating
// to_chars), and returns their end; p needs 32 chars of room.
inline char* putNumber(char* p, double v) {
#if defined(__cpp_lib_to_chars)
  return std::to_chars(p, p + 32, v, std::chars_format::general, 17).ptr;
#else
  return p + formatG17(v, p);
#endif
}

// Writes v at p in decimal and returns the end; p needs 24 chars of room.
inline char* putInt(char* p, long long v) { return std::to_chars(p, p + 24, v).ptr; }

// Appends v as putNumber writes it.
inline void appendNumber(std::string* out, double v) {
  char buf[32];
  out->append(buf, size_t(putNumber(buf, v) - buf));
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
