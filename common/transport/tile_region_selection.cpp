#include "common/transport/tile_region_selection.hpp"

#include <algorithm>
#include <charconv>
#include <optional>

namespace fleetmap::transport {
namespace {

constexpr std::string_view kBoxTag = "box:";

std::optional<int32_t> ParseInt(std::string_view text) {
  int32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// Four comma-separated integers: A,B,C,D.
std::optional<TileBox> ParseBox(std::string_view text) {
  int32_t numbers[4];
  for (size_t i = 0; i < 4; ++i) {
    const size_t comma = i < 3 ? text.find(',') : text.size();
    if (comma == std::string_view::npos) return std::nullopt;
    const std::optional<int32_t> number = ParseInt(text.substr(0, comma));
    if (!number) return std::nullopt;
    numbers[i] = *number;
    text.remove_prefix(std::min(text.size(), comma + 1));
  }
  return TileBox{numbers[0], numbers[2], numbers[1], numbers[3]};
}

}  // namespace

bool TileRegionSelection::Passes(const TileId& tile) const {
  if (own.Contains(tile)) return true;
  for (const TileBox& other : others) {
    if (other.Contains(tile)) return false;  // that shard's
  }
  return !others.empty();  // on no shard's region (only known when the others are)
}

std::vector<std::string> TileRegionSelection::ToParameters() const {
  std::vector<std::string> parameters = {std::to_string(own.min_x), std::to_string(own.max_x),
                                         std::to_string(own.min_y), std::to_string(own.max_y)};
  for (const TileBox& other : others) {
    parameters.push_back(std::string(kBoxTag) + std::to_string(other.min_x) + "," +
                         std::to_string(other.max_x) + "," + std::to_string(other.min_y) + "," +
                         std::to_string(other.max_y));
  }
  return parameters;
}

StatusOr<TileRegionSelection> TileRegionSelection::FromParameters(
    const std::vector<std::string>& parameters) {
  if (parameters.size() < 4) {
    return InvalidArgumentError("a tile region filter needs four tile bounds");
  }
  TileRegionSelection selection;
  int32_t bounds[4];
  for (size_t i = 0; i < 4; ++i) {
    const std::optional<int32_t> bound = ParseInt(parameters[i]);
    if (!bound) return InvalidArgumentError("tile bound \"" + parameters[i] + "\" is no integer");
    bounds[i] = *bound;
  }
  selection.own = TileBox{bounds[0], bounds[2], bounds[1], bounds[3]};
  for (size_t i = 4; i < parameters.size(); ++i) {
    const std::string_view parameter = parameters[i];
    if (parameter.substr(0, kBoxTag.size()) == kBoxTag) {
      const std::optional<TileBox> box = ParseBox(parameter.substr(kBoxTag.size()));
      if (!box) return InvalidArgumentError("\"" + parameters[i] + "\" is not box:A,B,C,D");
      selection.others.push_back(*box);
    } else {
      return InvalidArgumentError("unknown tile region filter parameter \"" + parameters[i] + "\"");
    }
  }
  return selection;
}

}  // namespace fleetmap::transport
