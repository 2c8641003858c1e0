#include "cl/program_cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

namespace voxr {

namespace {

constexpr char kMagic[8] = {'V', 'O', 'X', 'R', 'P', 'R', 'G', '2'};
// magic, key length (uint64), binary length (uint64), key text, binary
constexpr size_t kHeader = sizeof kMagic + 2 * sizeof(uint64_t);

uint64_t fnv1a(const std::string& text) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::optional<std::filesystem::path> folder_from_environment() {
  if (const char* dir = std::getenv("VOXR_CACHE_DIR"); dir && *dir) return std::filesystem::path(dir);
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "voxr";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "voxr";
  return std::nullopt;
}

}  // namespace

ProgramCache::ProgramCache() : folder_(folder_from_environment()) {}

std::filesystem::path ProgramCache::entry(const std::string& key) const {
  return *folder_ / fmt::format("{:016x}.bin", fnv1a(key));
}

std::optional<std::vector<unsigned char>> ProgramCache::load(const std::string& key) const {
  if (!folder_) return std::nullopt;
  std::ifstream in(entry(key), std::ios::binary);
  if (!in) return std::nullopt;
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Keys are compared as bytes (the sources hold UTF-8); a short or overlong file is a torn write.
  if (bytes.size() < kHeader || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return std::nullopt;
  uint64_t key_size = 0, binary_size = 0;
  std::memcpy(&key_size, bytes.data() + sizeof kMagic, sizeof key_size);
  std::memcpy(&binary_size, bytes.data() + sizeof kMagic + sizeof key_size, sizeof binary_size);
  if (key_size != key.size() || binary_size == 0 || bytes.size() != kHeader + key_size + binary_size ||
      std::memcmp(bytes.data() + kHeader, key.data(), key.size()) != 0)
    return std::nullopt;
  return std::vector<unsigned char>(bytes.begin() + long(kHeader + key_size), bytes.end());
}

void ProgramCache::store(const std::string& key, const std::vector<unsigned char>& binary) const {
  if (!folder_ || binary.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(*folder_, ec);
  const std::filesystem::path target = entry(key);
  static std::atomic<int> counter{0};
  const std::filesystem::path temp =
      target.string() + fmt::format(".{}.{}.tmp", getpid(), counter.fetch_add(1));
  {
    std::ofstream out(temp, std::ios::binary);
    const uint64_t key_size = key.size(), binary_size = binary.size();
    out.write(kMagic, sizeof kMagic);
    out.write(reinterpret_cast<const char*>(&key_size), sizeof key_size);
    out.write(reinterpret_cast<const char*>(&binary_size), sizeof binary_size);
    out.write(key.data(), std::streamsize(key.size()));
    out.write(reinterpret_cast<const char*>(binary.data()), std::streamsize(binary.size()));
    out.close();  // flushes: a full disk shows here
    if (!out) {
      std::filesystem::remove(temp, ec);
      return;
    }
  }
  std::filesystem::rename(temp, target, ec);
  if (ec) std::filesystem::remove(temp, ec);
}

}  // namespace voxr
