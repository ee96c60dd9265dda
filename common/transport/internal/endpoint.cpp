#include "common/transport/internal/endpoint.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <atomic>

#include "common/transport/internal/last_samples.hpp"
#include "common/transport/internal/robot_id_filter.hpp"
#include "common/transport/internal/served_writers.hpp"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

StatusOr<std::unique_ptr<WriterEndpoint>> WriterEndpoint::Create(Participant& participant,
                                                                 const std::string& topic_name,
                                                                 dds::TypeSupport type,
                                                                 const dds::DataWriterQos& qos) {
  std::unique_ptr<WriterEndpoint> self(new WriterEndpoint(participant, topic_name));
  FLEETMAP_ASSIGN_OR_RETURN(self->topic_, participant.AcquireTopic(topic_name, type));
  self->writer_ = participant.publisher()->create_datawriter(self->topic_, qos);
  if (self->writer_ == nullptr) {
    return UnavailableError("could not create a DDS writer on " + topic_name);
  }
  if (qos.ownership().kind == dds::EXCLUSIVE_OWNERSHIP_QOS) {
    self->last_samples_ = std::make_unique<LastSamples>(type);
    participant.served_writers().Add(self.get());
  }
  return self;
}

WriterEndpoint::WriterEndpoint(Participant& participant, std::string topic_name)
    : participant_(participant), topic_name_(std::move(topic_name)) {}

WriterEndpoint::~WriterEndpoint() {
  if (last_samples_) participant_.served_writers().Remove(this);
  if (writer_ != nullptr) participant_.publisher()->delete_datawriter(writer_);
  if (topic_ != nullptr) participant_.ReleaseTopic(topic_);
}

bool WriterEndpoint::Write(void* sample) {
  return last_samples_ ? last_samples_->Write(writer_, sample) : writer_->write(sample);
}

bool WriterEndpoint::Dispose(void* key) {
  if (last_samples_) return last_samples_->Dispose(writer_, key);
  // HANDLE_NIL: the instance is found from the key (Fast DDS 2.9 lacks lookup_instance).
  return writer_->dispose(key, dds::HANDLE_NIL) == ReturnCode_t::RETCODE_OK;
}

size_t WriterEndpoint::WriteAgain() {
  return last_samples_ ? last_samples_->WriteAgain(writer_) : 0;
}

StatusOr<std::unique_ptr<ReaderEndpoint>> ReaderEndpoint::Create(
    Participant& participant, const std::string& topic_name, dds::TypeSupport type,
    const dds::DataReaderQos& qos, dds::DataReaderListener* listener,
    const std::optional<ContentFilter>& filter) {
  std::unique_ptr<ReaderEndpoint> self(new ReaderEndpoint(participant, topic_name));
  FLEETMAP_ASSIGN_OR_RETURN(self->topic_, participant.AcquireTopic(topic_name, type));
  dds::TopicDescription* read_from = self->topic_;
  if (filter) {
    // A content-filtered topic's name is the participant's own business, unique within it.
    static std::atomic<uint64_t> filtered_topics{0};
    std::string name = topic_name + "/filtered_" + std::to_string(filtered_topics.fetch_add(1));
    self->filtered_topic_ = participant.dds_participant()->create_contentfilteredtopic(
        name, self->topic_, filter->expression, filter->parameters, filter->class_name.c_str());
    if (self->filtered_topic_ == nullptr) {
      return UnavailableError("could not filter " + topic_name + " to " + filter->label);
    }
    read_from = self->filtered_topic_;
  }
  self->reader_ =
      participant.subscriber()->create_datareader(read_from, qos, listener, dds::StatusMask::all());
  if (self->reader_ == nullptr) {
    return UnavailableError("could not create a DDS reader on " + topic_name);
  }
  return self;
}

Status ReaderEndpoint::SetFilterParameters(const std::vector<std::string>& parameters) {
  if (filtered_topic_ == nullptr) return InternalError(topic_name_ + " is read without a filter");
  if (filtered_topic_->set_expression_parameters(parameters) != ReturnCode_t::RETCODE_OK) {
    return UnavailableError("could not change the filter of " + topic_name_);
  }
  return Status::Ok();
}

ContentFilter ContentFilter::OnlyRobot(const std::string& robot) {
  return ContentFilter{
      kRobotIdFilterClass, kRobotIdFilterExpression, {"'" + robot + "'"}, "robot " + robot};
}

ReaderEndpoint::~ReaderEndpoint() {
  if (reader_ != nullptr) {
    reader_->set_listener(nullptr);
    participant_.subscriber()->delete_datareader(reader_);
  }
  if (filtered_topic_ != nullptr) {
    participant_.dds_participant()->delete_contentfilteredtopic(filtered_topic_);
  }
  if (topic_ != nullptr) participant_.ReleaseTopic(topic_);
}

}  // namespace fleetmap::transport
