#include "common/transport/internal/robot_id_filter.hpp"

#include <cstdint>
#include <cstring>

namespace fleetmap::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

// Accepts the samples whose leading robot id is `robot`.
class RobotIdFilter final : public dds::IContentFilter {
 public:
  explicit RobotIdFilter(std::string robot) : robot_(std::move(robot)) {}

  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo& /*sample_info*/,
                const GUID_t& /*reader_guid*/) const override {
    const std::optional<std::string_view> robot = LeadingCdrString(payload);
    return !robot || *robot == robot_;
  }

  void set_robot(std::string robot) { robot_ = std::move(robot); }

 private:
  std::string robot_;
};

// The robot a filter parameter names: the DDS SQL string literal 'alpha', or alpha as it is.
std::string Unquoted(const char* parameter) {
  std::string text = parameter == nullptr ? std::string() : std::string(parameter);
  if (text.size() >= 2 && text.front() == '\'' && text.back() == '\'') {
    text = text.substr(1, text.size() - 2);
  }
  return text;
}

class Factory final : public dds::IContentFilterFactory {
 public:
  ReturnCode_t create_content_filter(const char* /*filter_class_name*/, const char* /*type_name*/,
                                     const dds::TopicDataType* /*data_type*/,
                                     const char* filter_expression,
                                     const ParameterSeq& filter_parameters,
                                     dds::IContentFilter*& filter_instance) override {
    // filter_expression is null when only the parameters of an existing filter change.
    if (filter_expression != nullptr &&
        std::strcmp(filter_expression, kRobotIdFilterExpression) != 0) {
      return ReturnCode_t::RETCODE_BAD_PARAMETER;
    }
    if (filter_parameters.length() != 1) return ReturnCode_t::RETCODE_BAD_PARAMETER;
    std::string robot = Unquoted(filter_parameters[0]);
    if (filter_instance != nullptr) {
      static_cast<RobotIdFilter*>(filter_instance)->set_robot(std::move(robot));
    } else {
      filter_instance = new RobotIdFilter(std::move(robot));
    }
    return ReturnCode_t::RETCODE_OK;
  }

  ReturnCode_t delete_content_filter(const char* /*filter_class_name*/,
                                     dds::IContentFilter* filter_instance) override {
    delete static_cast<RobotIdFilter*>(filter_instance);
    return ReturnCode_t::RETCODE_OK;
  }
};

}  // namespace

dds::IContentFilterFactory& RobotIdFilterFactory() {
  static Factory* const factory = new Factory();  // outlives every participant
  return *factory;
}

std::optional<std::string_view> LeadingCdrString(
    const eprosima::fastrtps::rtps::SerializedPayload_t& payload) {
  constexpr uint32_t kHeader = 4;  // encapsulation id and options
  if (payload.data == nullptr || payload.length < kHeader + 4) return std::nullopt;
  const bool little_endian = payload.data[1] == 0x01;  // CDR_LE (0x0001), PL_CDR_LE (0x0003)
  const uint8_t* size_bytes = payload.data + kHeader;
  const uint32_t size = little_endian
                            ? (uint32_t{size_bytes[0]} | uint32_t{size_bytes[1]} << 8 |
                               uint32_t{size_bytes[2]} << 16 | uint32_t{size_bytes[3]} << 24)
                            : (uint32_t{size_bytes[3]} | uint32_t{size_bytes[2]} << 8 |
                               uint32_t{size_bytes[1]} << 16 | uint32_t{size_bytes[0]} << 24);
  // A CDR string's length counts its terminating NUL.
  if (size == 0 || size > payload.length - kHeader - 4) return std::nullopt;
  const char* text = reinterpret_cast<const char*>(size_bytes + 4);
  if (text[size - 1] != '\0') return std::nullopt;
  return std::string_view(text, size - 1);
}

}  // namespace fleetmap::transport
