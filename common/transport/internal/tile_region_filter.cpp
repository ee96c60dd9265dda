#include "common/transport/internal/tile_region_filter.hpp"

#include <cstring>

#include "common/transport/internal/robot_id_filter.hpp"

namespace fleetmap::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

class TileRegionFilter final : public dds::IContentFilter {
 public:
  explicit TileRegionFilter(TileRegionSelection selection) : selection_(std::move(selection)) {}

  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo& /*sample_info*/,
                const GUID_t& /*reader_guid*/) const override {
    const std::optional<TileSampleKey> key = ReadTileSampleKey(payload);
    return !key || selection_.Passes(key->tile);
  }

  void set_selection(TileRegionSelection selection) { selection_ = std::move(selection); }

 private:
  TileRegionSelection selection_;
};

class Factory final : public dds::IContentFilterFactory {
 public:
  ReturnCode_t create_content_filter(const char* /*filter_class_name*/, const char* /*type_name*/,
                                     const dds::TopicDataType* /*data_type*/,
                                     const char* filter_expression,
                                     const ParameterSeq& filter_parameters,
                                     dds::IContentFilter*& filter_instance) override {
    // filter_expression is null when only the parameters of an existing filter change.
    if (filter_expression != nullptr &&
        std::strcmp(filter_expression, kTileRegionFilterExpression) != 0) {
      return ReturnCode_t::RETCODE_BAD_PARAMETER;
    }
    std::vector<std::string> parameters;
    parameters.reserve(filter_parameters.length());
    for (ParameterSeq::size_type i = 0; i < filter_parameters.length(); ++i) {
      parameters.emplace_back(filter_parameters[i]);
    }
    StatusOr<TileRegionSelection> selection = TileRegionSelection::FromParameters(parameters);
    if (!selection.ok()) return ReturnCode_t::RETCODE_BAD_PARAMETER;
    if (filter_instance != nullptr) {
      static_cast<TileRegionFilter*>(filter_instance)->set_selection(std::move(selection).value());
    } else {
      filter_instance = new TileRegionFilter(std::move(selection).value());
    }
    return ReturnCode_t::RETCODE_OK;
  }

  ReturnCode_t delete_content_filter(const char* /*filter_class_name*/,
                                     dds::IContentFilter* filter_instance) override {
    delete static_cast<TileRegionFilter*>(filter_instance);
    return ReturnCode_t::RETCODE_OK;
  }
};

}  // namespace

dds::IContentFilterFactory& TileRegionFilterFactory() {
  static Factory* const factory = new Factory();  // outlives every participant
  return *factory;
}

std::optional<TileSampleKey> ReadTileSampleKey(
    const eprosima::fastrtps::rtps::SerializedPayload_t& payload) {
  const std::optional<std::string_view> robot = LeadingCdrString(payload);
  if (!robot) return std::nullopt;
  constexpr uint32_t kHeader = 4;  // encapsulation id and options
  // CDR aligns each int32 to 4 bytes from the start of the body (after the header).
  const uint32_t string_end = 4 + static_cast<uint32_t>(robot->size()) + 1;
  const uint32_t tile_x_at = kHeader + ((string_end + 3) & ~uint32_t{3});
  if (payload.length < tile_x_at + 8) return std::nullopt;
  const bool little_endian = payload.data[1] == 0x01;
  const auto read_int32 = [&](uint32_t at) {
    const uint8_t* b = payload.data + at;
    const uint32_t bits =
        little_endian
            ? (uint32_t{b[0]} | uint32_t{b[1]} << 8 | uint32_t{b[2]} << 16 | uint32_t{b[3]} << 24)
            : (uint32_t{b[3]} | uint32_t{b[2]} << 8 | uint32_t{b[1]} << 16 | uint32_t{b[0]} << 24);
    return static_cast<int32_t>(bits);
  };
  return TileSampleKey{*robot, TileId{read_int32(tile_x_at), read_int32(tile_x_at + 4)}};
}

}  // namespace fleetmap::transport
