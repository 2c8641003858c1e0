// Token and line helpers shared by the text mesh readers (OFF, OBJ, PLY, STL). Numbers are parsed with
// std::from_chars into double, so coordinates keep every digit the file has.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <glm/glm.hpp>

#include "util/error.h"

namespace voxr::text {

// Lines of a text, '\n'-terminated ('\r' before it counts as whitespace), numbered from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : rest_(text) {}
  // The text after the last line returned (empty after the last line).
  std::string_view rest() const { return done_ ? std::string_view() : rest_; }
  size_t number() const { return line_; }
  // Next line with its 1-based number; false at the end.
  bool next(std::string_view& line, size_t& number) {
    if (done_) return false;
    const size_t eol = rest_.find('\n');
    line = rest_.substr(0, eol);
    if (eol == std::string_view::npos) {
      done_ = true;
    } else {
      rest_.remove_prefix(eol + 1);
    }
    number = ++line_;
    return true;
  }

 private:
  std::string_view rest_;
  size_t line_ = 0;
  bool done_ = false;
};

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Splits `line` at whitespace, dropping everything from `comment` on (when comment != 0).
inline void split(std::string_view line, char comment, std::vector<std::string_view>& tokens) {
  tokens.clear();
  if (comment != 0) line = line.substr(0, line.find(comment));
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

// `token` as it may be quoted in a message: at most 24 characters, bytes that are not printable ASCII as '?'.
inline std::string printable(std::string_view token) {
  std::string s(token.substr(0, 24));
  for (char& c : s)
    if (c < 0x20 || c > 0x7e) c = '?';
  return token.size() > 24 ? s + "..." : s;
}

// Largest coordinate magnitude voxr accepts: the soup stores positions as floats relative to an anchor, and
// a mesh must fit float range after that (anything larger is a broken file, not a survey).
inline constexpr double kMaxCoordinate = 1e30;

// Parses a whole token as a finite number of at most kMaxCoordinate; false otherwise.
inline bool parse_number(std::string_view token, double& out) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !(std::abs(value) <= kMaxCoordinate))
    return false;
  out = value;
  return true;
}

// The coordinates of a vertex line "<keyword> x y z ...": tokens[1..3] as numbers; fails naming the line.
inline glm::dvec3 parse_vertex(const std::string& name, size_t line,
                               const std::vector<std::string_view>& tokens) {
  if (tokens.size() < 4) fail("{}: line {}: a vertex needs three coordinates", name, line);
  glm::dvec3 p;
  for (int c = 0; c < 3; ++c)
    if (!parse_number(tokens[c + 1], p[c]))
      fail("{}: line {}: vertex coordinate '{}' is not a finite number (of magnitude at most {:g})", name,
           line, printable(tokens[c + 1]), kMaxCoordinate);
  return p;
}

// A whole token as a non-negative integer that fits T; false otherwise.
template <typename T>
bool parse_uint(std::string_view token, T& out) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size() && !token.empty() && token[0] != '-';
}

// A count in a header; fails naming the file, line and what is counted.
inline size_t parse_count(const std::string& name, size_t line, std::string_view token, const char* what) {
  size_t value = 0;
  if (!parse_uint(token, value))
    fail("{}: line {}: the {} count '{}' is not a non-negative integer", name, line, what, printable(token));
  return value;
}

}  // namespace voxr::text
