// Strict reading of JSON objects for scene files and generator parameters: unknown keys, wrong types and
// out-of-range values are errors naming the key path ("scene.json: 'meshes[1].transform.scale' must ...").
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace voxr {

// Reads one JSON object of the scene format. The constructor fails on any key outside `allowed` (suggesting
// an allowed key spelled alike), so a typo is reported before a missing required key. Errors read
// "<where>: '<path>.<key>' must be ...", "<where>: missing required key '<path>.<key>'" and
// "<where>: unknown key '<path>.<key>'".
class JsonObjectReader {
 public:
  // Fails unless `value` is an object whose keys are all in `allowed`. `path` is the object's key path
  // ("" for the root).
  JsonObjectReader(const nlohmann::json& value, std::string where, std::string path,
                   std::initializer_list<std::string_view> allowed);

  const std::string& where() const { return where_; }
  // "path.key", or "key" at the root.
  std::string path(std::string_view key) const;
  bool has(std::string_view key) const;
  // The value, or nullptr when the key is absent.
  const nlohmann::json* get(std::string_view key) const;

  // Required (no fallback) or optional values. Numbers must be finite; integers must lie in [lo, hi].
  float number(std::string_view key, std::optional<float> fallback = std::nullopt) const;
  int64_t integer(std::string_view key, std::optional<int64_t> fallback, int64_t lo, int64_t hi) const;
  std::string string(std::string_view key, std::optional<std::string> fallback = std::nullopt) const;
  glm::vec3 vec3(std::string_view key, std::optional<glm::vec3> fallback = std::nullopt) const;
  // A position in double (world coordinates keep every digit the file has), each component within float
  // range as vec3's.
  glm::dvec3 dvec3(std::string_view key) const;
  glm::vec2 vec2(std::string_view key, std::optional<glm::vec2> fallback = std::nullopt) const;
  // A scale: one number (uniform) or an array of 3 numbers, none of them 0.
  glm::vec3 scale(std::string_view key, std::optional<glm::vec3> fallback = std::nullopt) const;
  std::vector<float> numbers(std::string_view key,
                             std::optional<std::vector<float>> fallback = std::nullopt) const;

  // Throws "<where>: '<path>.<key>' <what> (got <value>)" unless `ok`.
  void require(bool ok, std::string_view key, std::string_view what) const;
  [[noreturn]] void fail_key(std::string_view key, std::string_view what) const;
  // Fails when `key` is present: it is allowed in general but not here (`why`, e.g. "is not used by kind
  // 'opaque'").
  void forbid(std::string_view key, std::string_view why) const;

 private:
  const nlohmann::json& required(std::string_view key) const;
  void check_allowed(std::string_view key) const;

  const nlohmann::json& value_;
  std::string where_;
  std::string path_;
  std::vector<std::string_view> allowed_;
};

// "where: 'path' <what>" for a value that is not inside an object (an array element, say).
[[noreturn]] void fail_json_value(const std::string& where, const std::string& path, std::string_view what);
// The value at `path` as a 3-vector of numbers of float range (|x| <= 3.4e38), in double or rounded to float.
glm::dvec3 json_dvec3(const nlohmann::json& value, const std::string& where, const std::string& path);
glm::vec3 json_vec3(const nlohmann::json& value, const std::string& where, const std::string& path);

// Compact JSON of a value for messages: at most 40 characters and 4 levels (deeper containers as [...] /
// {...}), in work and stack bounded however large or deep the value is.
std::string shown(const nlohmann::json& value);
// A string from a scene as a message quotes it: in double quotes, JSON-escaped (a newline as \n), at most 40
// characters (shown), so the message stays one line however the string was written.
std::string quoted_text(std::string_view text);
// A key or name shown bare in a message: as it is when it has at most 40 characters and no control
// character, else quoted_text().
std::string printable_key(std::string_view key);
// "a, b, c".
std::string join(const std::vector<std::string_view>& items);
// "base.key", or "key" when base is empty; the key as printable_key shows it.
std::string join_path(const std::string& base, std::string_view key);

}  // namespace voxr
