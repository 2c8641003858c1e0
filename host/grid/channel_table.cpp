#include "grid/channel_table.h"

#include "util/error.h"

namespace voxr {

const ChannelInfo& channel_info(Channel c) {
  for (const ChannelInfo& info : kChannelTable)
    if (info.channel == c) return info;
  throw InternalError(fmt::format("channel bit {} is not in the channel table", uint32_t(c)));
}

const ChannelInfo* find_channel_array(std::string_view array_name) {
  for (const ChannelInfo& info : kChannelTable)
    if (array_name == info.array_name) return &info;
  return nullptr;
}

Defines channel_defines() {
  Defines defines;
  for (const ChannelInfo& info : kChannelTable)
    defines.push_back({info.define, std::to_string(uint32_t(info.channel))});
  return defines;
}

bool ChannelSet::sparse() const {
  for (const ChannelInfo& info : kChannelTable)
    if (info.layout == ChannelLayout::kSparse && has(info.channel)) return true;
  return false;
}

ChannelSet ChannelSet::parse(std::string_view list) {
  ChannelSet set;
  while (!list.empty()) {
    const size_t comma = list.find(',');
    const std::string_view name = list.substr(0, comma);
    const ChannelInfo* found = nullptr;
    for (const ChannelInfo& info : kChannelTable)
      if (name == info.name) found = &info;
    if (!found) {
      std::string known;
      for (const ChannelInfo& info : kChannelTable)
        known += fmt::format("{}{}", known.empty() ? "" : ", ", info.name);
      fail("unknown channel '{}' (channels: {})", name, known);
    }
    set.add(found->channel);
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return set;
}

std::string ChannelSet::to_string() const {
  std::string s;
  for (const ChannelInfo& info : kChannelTable)
    if (has(info.channel)) s += fmt::format("{}{}", s.empty() ? "" : ",", info.name);
  return s;
}

}  // namespace voxr
