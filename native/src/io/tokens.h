#pragma once
// Private: whitespace tokenizer with line numbers for the text mesh formats, so every
// parse error can name the line and what was expected.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "anisomesh/core/error.h"
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
      : format_(std::move(format)), text_(text), comment_(commentChar), line_(firstLine), lastLine_(firstLine) {
    p_ = text_.data();
    end_ = p_ + text_.size();
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

  // The next token as a double; fails naming what was expected.
  // what is a string or a callable returning one (built only on failure: hot loops).
  template <class What>
  double number(const What& what) {
    if (atEnd()) fail(describe(what));
    // strtod directly on the text (it is NUL-terminated) stops at the token's end.
    const Token t = peek();
    char* stop = nullptr;
    const double v = std::strtod(t.begin, &stop);
    if (t.size == 0 || stop != t.begin + t.size) fail(describe(what));
    next();
    return v;
  }
  // The next token as an integer; fails naming what was expected.
  template <class What>
  long long integer(const What& what) {
    if (atEnd()) fail(describe(what));
    const Token t = peek();
    char* stop = nullptr;
    errno = 0;
    const long long v = std::strtoll(t.begin, &stop, 10);
    if (t.size == 0 || stop != t.begin + t.size || errno == ERANGE) fail(describe(what));
    next();
    return v;
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

 private:
  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
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
  const std::string& text_;  // the caller's text, alive for the whole parse
  char comment_;
  int line_;
  int lastLine_ = 1;
  const char* p_ = nullptr;
  const char* end_ = nullptr;
};

// Appends v with round-trip precision.
inline void appendNumber(std::string* out, double v) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", v);
  out->append(buf, size_t(n));
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

inline void appendInt(std::string* out, long long v) { out->append(std::to_string(v)); }

}  // namespace io_detail
}  // namespace anisomesh
