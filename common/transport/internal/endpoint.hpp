#pragma once

// Internal to transport: the DDS entities behind one typed reader or writer, created in one
// checked step and deleted in reverse order.

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class LastSamples;

// A writer with EXCLUSIVE ownership serves state (served_state.hpp): it remembers the last sample
// of each instance and joins its participant's ServedWriters.
class WriterEndpoint {
 public:
  static StatusOr<std::unique_ptr<WriterEndpoint>> Create(
      Participant& participant, const std::string& topic_name,
      eprosima::fastdds::dds::TypeSupport type, const eprosima::fastdds::dds::DataWriterQos& qos);
  ~WriterEndpoint();
  WriterEndpoint(const WriterEndpoint&) = delete;
  WriterEndpoint& operator=(const WriterEndpoint&) = delete;

  eprosima::fastdds::dds::DataWriter* writer() const { return writer_; }
  const std::string& topic_name() const { return topic_name_; }

  // Writes `sample`, of the endpoint's type; false when DDS refused it.
  bool Write(void* sample);
  // Disposes the instance `key` (a sample with its key fields set) names.
  bool Dispose(void* key);
  // A writer that serves state: its instances written again (disposals too); the count. Others: 0.
  size_t WriteAgain();

 private:
  WriterEndpoint(Participant& participant, std::string topic_name);

  Participant& participant_;
  std::string topic_name_;
  eprosima::fastdds::dds::Topic* topic_ = nullptr;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  std::unique_ptr<LastSamples> last_samples_;  // writers that serve state only
};

// A DDS content filter of one of the classes every Participant registers.
struct ContentFilter {
  std::string class_name;
  std::string expression;
  std::vector<std::string> parameters;
  std::string label;  // for the filtered topic's name and errors: "robot alpha", "region west"

  // The instances of one robot only (robot_id_filter.hpp; topics whose first field is the robot
  // id).
  static ContentFilter OnlyRobot(const std::string& robot);
};

class ReaderEndpoint {
 public:
  // `listener` must outlive the endpoint; it is detached before the reader is deleted. With a
  // `filter`, the reader takes what it passes (the writers evaluate it where they know the class).
  static StatusOr<std::unique_ptr<ReaderEndpoint>> Create(
      Participant& participant, const std::string& topic_name,
      eprosima::fastdds::dds::TypeSupport type, const eprosima::fastdds::dds::DataReaderQos& qos,
      eprosima::fastdds::dds::DataReaderListener* listener,
      const std::optional<ContentFilter>& filter = std::nullopt);
  ~ReaderEndpoint();
  ReaderEndpoint(const ReaderEndpoint&) = delete;
  ReaderEndpoint& operator=(const ReaderEndpoint&) = delete;

  eprosima::fastdds::dds::DataReader* reader() const { return reader_; }
  const std::string& topic_name() const { return topic_name_; }
  // New parameters for the reader's filter (the writers learn them through discovery).
  Status SetFilterParameters(const std::vector<std::string>& parameters);

 private:
  ReaderEndpoint(Participant& participant, std::string topic_name)
      : participant_(participant), topic_name_(std::move(topic_name)) {}

  Participant& participant_;
  std::string topic_name_;
  eprosima::fastdds::dds::Topic* topic_ = nullptr;
  eprosima::fastdds::dds::ContentFilteredTopic* filtered_topic_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace fleetmap::transport
