#include "anisomesh/io/json_text.h"

#include <nlohmann/json.hpp>
#include <vector>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

using json = nlohmann::json;

// SAX events tracking the path of the current value; stops at the first overflow.
class PathTracker : public nlohmann::json_sax<json> {
 public:
  std::string overflowPath;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    value();  // the object is the parent's next element
    frames_.push_back({false, -1, ""});
    return true;
  }
  bool key(string_t& k) override {
    frames_.back().key = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override {
    value();
    frames_.push_back({true, -1, ""});
    return true;
  }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& ex) override {
    if (ex.id == 406) {  // out_of_range: number overflow, at the value being read
      if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
      overflowPath = path();
    }
    return false;
  }

 private:
  struct Frame {
    bool array;
    int index;
    std::string key;
  };

  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array)
        p += "[" + std::to_string(f.index) + "]";
      else
        p += (p.empty() ? "" : ".") + f.key;
    }
    return p.empty() ? "(root)" : p;
  }

  std::vector<Frame> frames_;
};

}  // namespace

std::string jsonOverflowPath(const std::string& text) {
  PathTracker t;
  (void)json::sax_parse(text, &t, json::input_format_t::json, false);
  return t.overflowPath;
}

void requireNoNulByte(const std::string& text) {
  const size_t at = text.find('\0');
  require(at == std::string::npos, ErrorCode::ParseError,
          "(root): malformed JSON: a NUL byte at offset " + std::to_string(at) +
              " (the JSON parser would take it for the end of the text and ignore what follows)");
}

void requireNoJsonNumberOverflow(const std::string& text) {
  const std::string path = jsonOverflowPath(text);
  require(path.empty(), ErrorCode::ParseError, path + ": number overflow: the value does not fit a double");
}

}  // namespace anisomesh
