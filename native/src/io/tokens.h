#pragma once
// Private: whitespace tokenizer with line numbers for the text mesh formats, so every
// parse error can name the line and what was expected.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace io_detail {

struct Token {
  const char* begin;
  size_t size;
  int line;
  std::string str() const { return std::string(begin, size); }
};

class TokenStream {
 public:
  // Splits text into tokens; everything from commentChar (when nonzero) to the end of a line is dropped.
  TokenStream(const std::string& text, std::string format, char commentChar, int firstLine = 1)
      : format_(std::move(format)), text_(text) {
    int line = firstLine;
    const char* p = text_.data();
    const char* end = p + text_.size();
    while (p < end) {
      const char ch = *p;
      if (ch == '\n') { ++line; ++p; continue; }
      if (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v') { ++p; continue; }
      if (commentChar && ch == commentChar) {
        while (p < end && *p != '\n') ++p;
        continue;
      }
      const char* b = p;
      while (p < end && !(*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '\f' || *p == '\v') &&
             !(commentChar && *p == commentChar))
        ++p;
      tokens_.push_back({b, size_t(p - b), line});
    }
    lastLine_ = line;
  }

  TokenStream(const TokenStream&) = delete;
  TokenStream& operator=(const TokenStream&) = delete;

  bool atEnd() const { return pos_ >= tokens_.size(); }
  const Token& peek() const { return tokens_[pos_]; }
  const Token& next() {
    if (atEnd()) fail("more data");
    return tokens_[pos_++];
  }
  int line() const { return atEnd() ? lastLine_ : tokens_[pos_].line; }

  [[noreturn]] void fail(const std::string& expected) const {
    const std::string got = atEnd() ? std::string("end of file") : "'" + tokens_[pos_].str() + "'";
    throw Error(ErrorCode::ParseError, format_ + " line " + std::to_string(line()) + ": expected " + expected +
                                           ", got " + got);
  }
  [[noreturn]] void failAt(int line, const std::string& message) const {
    throw Error(ErrorCode::ParseError, format_ + " line " + std::to_string(line) + ": " + message);
  }

  // The next token as a double; fails naming what was expected.
  double number(const std::string& what) {
    if (atEnd()) fail(what);
    const Token& t = tokens_[pos_];
    const std::string s = t.str();
    char* stop = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &stop);
    if (stop != s.c_str() + s.size() || s.empty()) fail(what);
    ++pos_;
    return v;
  }
  // The next token as an integer; fails naming what was expected.
  long long integer(const std::string& what) {
    if (atEnd()) fail(what);
    const std::string s = tokens_[pos_].str();
    char* stop = nullptr;
    errno = 0;
    const long long v = std::strtoll(s.c_str(), &stop, 10);
    if (stop != s.c_str() + s.size() || s.empty() || errno == ERANGE) fail(what);
    ++pos_;
    return v;
  }
  // A count: a nonnegative integer no larger than the tokens left (guards huge allocations).
  long long count(const std::string& what, int tokensPerItem) {
    const int ln = line();
    const long long n = integer(what);
    if (n < 0) failAt(ln, "expected " + what + " (a nonnegative integer), got " + std::to_string(n));
    if (tokensPerItem > 0 && n > (long long)((tokens_.size() - pos_) / tokensPerItem + 1))
      failAt(ln, what + " " + std::to_string(n) + " is larger than the data that follows");
    return n;
  }
  const std::string& format() const { return format_; }

 private:
  std::string format_;
  std::string text_;  // owned: tokens point into it
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  int lastLine_ = 1;
};

// Appends v with round-trip precision.
inline void appendNumber(std::string* out, double v) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", v);
  out->append(buf, size_t(n));
}

inline void appendInt(std::string* out, long long v) { out->append(std::to_string(v)); }

}  // namespace io_detail
}  // namespace anisomesh
