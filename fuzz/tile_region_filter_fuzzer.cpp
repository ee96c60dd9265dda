// Fuzz target: the tile-region content filter of shards (common/transport/internal/
// tile_region_filter.hpp, docs/shards.md). Its two inputs come from other participants: the
// samples it evaluates (a reader's participant runs it on every sample of another vendor's
// writer), and its parameters (a writer's participant makes the filter from what a remote
// reader announced in discovery). The first byte picks which: below 128 the rest is a sample's
// serialized payload, else the rest is parameters, one per line.
//
// Besides crashes, the properties: a sample key it reads lies inside the payload; parameters it
// accepts give back the same selection when written out and read again.

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/core/StackAllocatedSequence.hpp>
#include <fastdds/dds/topic/IContentFilter.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/core/check.hpp"
#include "common/transport/internal/tile_region_filter.hpp"

namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SerializedPayload_t;
using fleetmap::transport::TileRegionSelection;

void FuzzSample(const uint8_t* data, size_t size) {
  SerializedPayload_t payload(static_cast<uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<uint32_t>(size);
  const auto key = fleetmap::transport::ReadTileSampleKey(payload);
  if (key) {
    const auto* first = reinterpret_cast<const uint8_t*>(key->robot.data());
    FLEETMAP_CHECK(first == payload.data + 8, "the robot id starts after header and length");
    FLEETMAP_CHECK(key->robot.size() + 9 <= payload.length, "the robot id ends in the payload");
  }
  // The filter a shard of tiles (0..2, 0..5) beside another of (3..5, 0..5) would announce.
  dds::IContentFilterFactory& factory = fleetmap::transport::TileRegionFilterFactory();
  dds::StackAllocatedSequence<const char*, 5> parameters;
  parameters.length(5);
  const char* values[] = {"0", "2", "0", "5", "box:3,5,0,5"};
  for (int i = 0; i < 5; ++i) parameters[i] = values[i];
  dds::IContentFilter* filter = nullptr;
  const auto created = factory.create_content_filter(
      fleetmap::transport::kTileRegionFilterClass, "fleetmap_msgs::msg::dds_::VectorTile_", nullptr,
      fleetmap::transport::kTileRegionFilterExpression, parameters, filter);
  FLEETMAP_CHECK(created == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK,
                 "the filter is made for good parameters");
  const bool passed = filter->evaluate(payload, dds::IContentFilter::FilterSampleInfo(),
                                       eprosima::fastrtps::rtps::GUID_t());
  FLEETMAP_CHECK(
      !key || passed == (key->tile.x <= 2 || key->tile.x > 5 || key->tile.y < 0 || key->tile.y > 5),
      "the filter passes its own tiles and those on no region, and no other");
  factory.delete_content_filter(fleetmap::transport::kTileRegionFilterClass, filter);
}

void FuzzParameters(const uint8_t* data, size_t size) {
  std::vector<std::string> parameters(1);
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      parameters.emplace_back();
    } else {
      parameters.back().push_back(static_cast<char>(data[i]));
    }
  }
  const auto selection = TileRegionSelection::FromParameters(parameters);
  if (!selection.ok()) return;
  const auto again = TileRegionSelection::FromParameters(selection->ToParameters());
  FLEETMAP_CHECK(again.ok(), "written parameters are read again");
  FLEETMAP_CHECK(again->own == selection->own && again->others == selection->others,
                 "the selection survives its parameters");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  if (data[0] < 128) {
    FuzzSample(data + 1, size - 1);
  } else {
    FuzzParameters(data + 1, size - 1);
  }
  return 0;
}
