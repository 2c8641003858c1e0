#include "util/json_reader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace voxr {

using nlohmann::json;

namespace {

// Appends compact JSON of `value` to `out`, containers below `depth` levels as [...] / {...}, and stops once
// `out` is longer than `limit` (the caller cuts it): bounded work and stack however large or deep the value
// (json::dump recurses once per level and overflowed the stack on a 100 000-deep array).
void append_shown(const json& value, int depth, size_t limit, std::string& out) {
  if (out.size() > limit) return;
  if (!value.is_structured()) {
    out += value.dump();
    return;
  }
  const bool array = value.is_array();
  if (depth == 0 && !value.empty()) {
    out += array ? "[...]" : "{...}";
    return;
  }
  out += array ? '[' : '{';
  bool first = true;
  for (auto it = value.begin(); it != value.end() && out.size() <= limit; ++it) {
    if (!first) out += ',';
    first = false;
    if (!array) out += json(it.key()).dump() + ':';
    append_shown(*it, depth - 1, limit, out);
  }
  out += array ? ']' : '}';
}

}  // namespace

// Compact JSON of a value for messages, cut to a readable length and depth.
std::string shown(const json& value) {
  constexpr size_t kLength = 40;
  constexpr int kDepth = 4;
  std::string s;
  append_shown(value, kDepth, kLength, s);
  return s.size() > kLength ? s.substr(0, kLength - 3) + "..." : s;
}

namespace {
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const bool same = std::tolower((unsigned char)a[i - 1]) == std::tolower((unsigned char)b[j - 1]);
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}
}  // namespace

std::string join(const std::vector<std::string_view>& items) {
  std::string s;
  for (std::string_view item : items) s += (s.empty() ? "" : ", ") + std::string(item);
  return s;
}

std::string quoted_text(std::string_view text) {
  return shown(json(std::string(text)));
}

std::string printable_key(std::string_view key) {
  const bool plain = key.size() <= 40 && std::none_of(key.begin(), key.end(), [](char c) {
                       return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
                     });
  return plain ? std::string(key) : quoted_text(key);
}

std::string join_path(const std::string& base, std::string_view key) {
  return base.empty() ? printable_key(key) : base + "." + printable_key(key);
}

void fail_json_value(const std::string& where, const std::string& path, std::string_view what) {
  fail("{}: '{}' {}", where, path, what);
}

namespace {

// Why `d` (a JSON number, so finite: nlohmann refuses overflowing text) cannot be a float, or nullptr.
const char* float_problem(double d) {
  if (!std::isfinite(d)) return "must be finite";
  if (std::abs(d) > double(std::numeric_limits<float>::max()))
    return "is out of float range (the magnitude must be at most 3.4e38)";
  return nullptr;
}

}  // namespace

glm::dvec3 json_dvec3(const json& value, const std::string& where, const std::string& path) {
  if (!value.is_array() || value.size() != 3 ||
      !std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); }))
    fail_json_value(where, path, fmt::format("must be an array of 3 numbers (got {})", shown(value)));
  glm::dvec3 v;
  for (int c = 0; c < 3; ++c) {
    v[c] = value[c].get<double>();
    if (const char* problem = float_problem(v[c]))
      fail_json_value(where, path, fmt::format("{} (got {})", problem, shown(value)));
  }
  return v;
}

glm::vec3 json_vec3(const json& value, const std::string& where, const std::string& path) {
  return glm::vec3(json_dvec3(value, where, path));
}

JsonObjectReader::JsonObjectReader(const json& value, std::string where, std::string path,
                                   std::initializer_list<std::string_view> allowed)
    : value_(value), where_(std::move(where)), path_(std::move(path)), allowed_(allowed) {
  if (!value_.is_object())
    fail("{}: '{}' must be an object (got {})", where_, path_.empty() ? "the top level" : path_,
         shown(value_));
  for (const auto& item : value_.items()) {
    const std::string& key = item.key();
    if (std::find(allowed_.begin(), allowed_.end(), key) != allowed_.end()) continue;
    // Suggest an allowed key that extends the unknown one ("rotate" -> "rotate_deg"), or else the closest
    // by edit distance when it is close enough to be a typo.
    std::string_view best;
    size_t best_distance = std::numeric_limits<size_t>::max();
    for (std::string_view a : allowed_) {
      if (key.size() >= 3 && (a.starts_with(key) || std::string_view(key).starts_with(a))) {
        best = a;
        best_distance = 0;
        break;
      }
      if (const size_t d = edit_distance(key, a); d < best_distance) best_distance = d, best = a;
    }
    if (!best.empty() && best_distance <= std::max<size_t>(2, best.size() / 3))
      fail("{}: unknown key '{}' (did you mean '{}'?)", where_, join_path(path_, key),
           join_path(path_, best));
    fail("{}: unknown key '{}' (allowed here: {})", where_, join_path(path_, key), join(allowed_));
  }
}

std::string JsonObjectReader::path(std::string_view key) const {
  return join_path(path_, key);
}

void JsonObjectReader::check_allowed(std::string_view key) const {
  // Asking for a key the constructor did not allow is a bug in the reader, not in the scene.
  VOXR_CHECK(std::find(allowed_.begin(), allowed_.end(), key) != allowed_.end());
}

bool JsonObjectReader::has(std::string_view key) const {
  check_allowed(key);
  return value_.contains(key);
}

const json* JsonObjectReader::get(std::string_view key) const {
  check_allowed(key);
  const auto it = value_.find(key);
  return it == value_.end() ? nullptr : &*it;
}

const json& JsonObjectReader::required(std::string_view key) const {
  const json* v = get(key);
  if (!v) fail("{}: missing required key '{}'", where_, path(key));
  return *v;
}

void JsonObjectReader::fail_key(std::string_view key, std::string_view what) const {
  fail("{}: '{}' {}", where_, path(key), what);
}

void JsonObjectReader::require(bool ok, std::string_view key, std::string_view what) const {
  if (ok) return;
  const json* v = get(key);
  if (v) fail_key(key, fmt::format("{} (got {})", what, shown(*v)));
  fail_key(key, what);
}

void JsonObjectReader::forbid(std::string_view key, std::string_view why) const {
  if (has(key)) fail_key(key, why);
}

float JsonObjectReader::number(std::string_view key, std::optional<float> fallback) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  const json& value = v ? *v : required(key);
  if (!value.is_number()) fail_key(key, fmt::format("must be a number (got {})", shown(value)));
  const double d = value.get<double>();
  if (const char* problem = float_problem(d))
    fail_key(key, fmt::format("{} (got {})", problem, shown(value)));
  return float(d);
}

int64_t JsonObjectReader::integer(std::string_view key, std::optional<int64_t> fallback, int64_t lo,
                                  int64_t hi) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  const json& value = v ? *v : required(key);
  const bool in_range =
      value.is_number_integer() &&
      (value.is_number_unsigned()
           ? value.get<uint64_t>() <= uint64_t(hi) && hi >= 0 && int64_t(value.get<uint64_t>()) >= lo
           : value.get<int64_t>() >= lo && value.get<int64_t>() <= hi);
  if (!in_range) fail_key(key, fmt::format("must be an integer in [{}, {}] (got {})", lo, hi, shown(value)));
  return value.is_number_unsigned() ? int64_t(value.get<uint64_t>()) : value.get<int64_t>();
}

std::string JsonObjectReader::string(std::string_view key, std::optional<std::string> fallback) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  const json& value = v ? *v : required(key);
  if (!value.is_string()) fail_key(key, fmt::format("must be a string (got {})", shown(value)));
  return value.get<std::string>();
}

glm::vec3 JsonObjectReader::vec3(std::string_view key, std::optional<glm::vec3> fallback) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  return json_vec3(v ? *v : required(key), where_, path(key));
}

glm::dvec3 JsonObjectReader::dvec3(std::string_view key) const {
  return json_dvec3(required(key), where_, path(key));
}

glm::vec2 JsonObjectReader::vec2(std::string_view key, std::optional<glm::vec2> fallback) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  const std::vector<float> n = numbers(key);
  if (n.size() != 2) fail_key(key, fmt::format("must be an array of 2 numbers (got {})", shown(*v)));
  return glm::vec2(n[0], n[1]);
}

glm::vec3 JsonObjectReader::scale(std::string_view key, std::optional<glm::vec3> fallback) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  const json& value = v ? *v : required(key);
  glm::vec3 s;
  if (value.is_number()) {
    s = glm::vec3(number(key));
  } else {
    if (!value.is_array())
      fail_key(key, fmt::format("must be a number or an array of 3 numbers (got {})", shown(value)));
    s = vec3(key);
  }
  require(s.x != 0.0f && s.y != 0.0f && s.z != 0.0f, key, "must not be 0 along any axis");
  return s;
}

std::vector<float> JsonObjectReader::numbers(std::string_view key,
                                             std::optional<std::vector<float>> fallback) const {
  const json* v = get(key);
  if (!v && fallback) return *fallback;
  const json& value = v ? *v : required(key);
  if (!value.is_array()) fail_key(key, fmt::format("must be an array of numbers (got {})", shown(value)));
  std::vector<float> out;
  for (const json& e : value) {
    if (!e.is_number()) fail_key(key, fmt::format("must be an array of numbers (got {})", shown(value)));
    if (const char* problem = float_problem(e.get<double>()))
      fail_key(key, fmt::format("{} (got {})", problem, shown(value)));
    out.push_back(float(e.get<double>()));
  }
  return out;
}

}  // namespace voxr
