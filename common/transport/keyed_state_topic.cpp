#include "common/transport/keyed_state_topic.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <map>
#include <mutex>

#include "common/core/sample_queue.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/internal/state_conversions.hpp"
#include "common/transport/internal/writer_id.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::transport {
namespace {

namespace dds = eprosima::fastdds::dds;

// What differs between the topics: the wire type, the topic, which fields are the key, and whether
// a server serves it (served_state.hpp: exclusive ownership).
template <typename Message>
struct TopicTraits;

template <>
struct TopicTraits<EntityMessage> {
  using Sample = fleetmap_msgs::msg::dds_::Entity_;
  static constexpr const char* kTopic = kEntitiesTopic;
  static constexpr bool kServed = false;
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return EntityTypeSupport(); }
  static EntityMessage KeyOf(const EntityMessage& message) {
    scene::DoorEntity key_only;  // any alternative carries the id
    key_only.id = message.entity_id();
    EntityMessage key;
    key.robot = message.robot;
    key.entity = std::move(key_only);
    return key;
  }
  // Names the sender of a refused sample when its key fields are readable.
  static std::string Sender(const Sample& sample) {
    return sample.robot_id().substr(0, 64) + "/" + sample.entity_id().substr(0, 64);
  }
};

template <>
struct TopicTraits<SubmapMessage> {
  using Sample = fleetmap_msgs::msg::dds_::Submap_;
  static constexpr const char* kTopic = kSubmapGraphTopic;
  static constexpr bool kServed = true;
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return SubmapTypeSupport(); }
  static SubmapMessage KeyOf(const SubmapMessage& message) {
    SubmapMessage key;
    key.submap.id = message.submap.id;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "sub-map " + std::to_string(sample.submap_id());
  }
};

template <>
struct TopicTraits<ObjectTemplateMessage> {
  using Sample = fleetmap_msgs::msg::dds_::ObjectTemplate_;
  static constexpr const char* kTopic = kObjectTemplatesTopic;
  static constexpr bool kServed = true;
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return ObjectTemplateTypeSupport(); }
  static ObjectTemplateMessage KeyOf(const ObjectTemplateMessage& message) {
    ObjectTemplateMessage key;
    key.template_id = message.template_id;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "template " + std::to_string(sample.template_id());
  }
};

template <>
struct TopicTraits<RouteGraphMessage> {
  using Sample = fleetmap_msgs::msg::dds_::RouteGraph_;
  static constexpr const char* kTopic = kRouteGraphTopic;
  static constexpr bool kServed = true;
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return RouteGraphTypeSupport(); }
  static RouteGraphMessage KeyOf(const RouteGraphMessage& message) {
    RouteGraphMessage key;
    key.graph_id = message.graph_id;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "route graph " + sample.graph_id().substr(0, 64);
  }
};

template <>
struct TopicTraits<ObjectModelMessage> {
  using Sample = fleetmap_msgs::msg::dds_::ObjectModel_;
  static constexpr const char* kTopic = kObjectsTopic;
  static constexpr bool kServed = true;
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return ObjectModelTypeSupport(); }
  static ObjectModelMessage KeyOf(const ObjectModelMessage& message) {
    ObjectModelMessage key;
    key.object_id = message.object_id;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "object " + std::to_string(sample.object_id());
  }
};

template <>
struct TopicTraits<RobotFrameMessage> {
  using Sample = fleetmap_msgs::msg::dds_::RobotFrame_;
  static constexpr const char* kTopic = kRobotFramesTopic;
  static constexpr bool kServed = true;
  static constexpr bool kKeyedByRobotFirst = true;  // @key string robot_id, first
  static dds::TypeSupport Type() { return RobotFrameTypeSupport(); }
  static RobotFrameMessage KeyOf(const RobotFrameMessage& message) {
    RobotFrameMessage key;
    key.robot = message.robot;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "robot frame " + sample.robot_id().substr(0, 64);
  }
};

template <>
struct TopicTraits<FleetServerMessage> {
  using Sample = fleetmap_msgs::msg::dds_::FleetServer_;
  static constexpr const char* kTopic = kServersTopic;
  static constexpr bool kServed = false;  // every server writes its own instance
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return FleetServerTypeSupport(); }
  static FleetServerMessage KeyOf(const FleetServerMessage& message) {
    FleetServerMessage key;
    key.server_id = message.server_id;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "server " + sample.server_id().substr(0, 64);
  }
};

template <typename Message>
EndpointQos QosOf(const Participant& participant) {
  if constexpr (TopicTraits<Message>::kServed) {
    return ServedStateQos(participant.ownership_strength());
  } else {
    return KeyedStateQos();
  }
}

template <>
struct TopicTraits<RobotAdmissionMessage> {
  using Sample = fleetmap_msgs::msg::dds_::RobotAdmission_;
  static constexpr const char* kTopic = kAdmissionsTopic;
  static constexpr bool kServed = false;
  static constexpr bool kKeyedByRobotFirst = false;
  static dds::TypeSupport Type() { return RobotAdmissionTypeSupport(); }
  static RobotAdmissionMessage KeyOf(const RobotAdmissionMessage& message) {
    RobotAdmissionMessage key;
    key.robot = message.robot;
    return key;
  }
  static std::string Sender(const Sample& sample) {
    return "admission of " + sample.robot_id().substr(0, 64);
  }
};

}  // namespace

template <typename Message>
StatusOr<std::unique_ptr<KeyedStateWriter<Message>>> KeyedStateWriter<Message>::Create(
    Participant& participant) {
  using Traits = TopicTraits<Message>;
  std::unique_ptr<KeyedStateWriter> self(new KeyedStateWriter());
  FLEETMAP_ASSIGN_OR_RETURN(self->endpoint_,
                            WriterEndpoint::Create(participant, Traits::kTopic, Traits::Type(),
                                                   QosOf<Message>(participant).writer));
  return self;
}

template <typename Message>
KeyedStateWriter<Message>::~KeyedStateWriter() = default;

template <typename Message>
StatusOr<size_t> KeyedStateWriter<Message>::Write(const Message& message) {
  using Sample = typename TopicTraits<Message>::Sample;
  FLEETMAP_ASSIGN_OR_RETURN(Sample sample, ToIdl(message));
  if (!endpoint_->Write(&sample)) {
    return UnavailableError("could not write on " + endpoint_->topic_name());
  }
  return Sample::getCdrSerializedSize(sample) + 4;
}

template <typename Message>
Status KeyedStateWriter<Message>::Dispose(const Message& key) {
  using Traits = TopicTraits<Message>;
  FLEETMAP_ASSIGN_OR_RETURN(typename Traits::Sample sample, ToIdl(Traits::KeyOf(key)));
  if (!endpoint_->Dispose(&sample)) {
    return UnavailableError("could not dispose an instance on " + endpoint_->topic_name());
  }
  return Status::Ok();
}

template <typename Message>
int KeyedStateWriter<Message>::matched_readers() const {
  dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.current_count;
}

// Runs on DDS threads: checks, decodes and queues, nothing more.
template <typename Message>
class KeyedStateReader<Message>::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  using Traits = TopicTraits<Message>;
  using Sample = typename Traits::Sample;
  using Event = KeyedEvent<Message>;

  explicit Listener(std::shared_ptr<WakeUp> wake_up) : wake_up_(std::move(wake_up)) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<Sample>(reader, this, [this](const Sample& sample, const dds::SampleInfo& info) {
      Event event;
      event.writer = WriterId(info.publication_handle);
      if (info.valid_data) {
        OnSample(sample, info, std::move(event));
      } else {
        OnInstanceGone(info, std::move(event));
      }
    });
    if (wake_up_) wake_up_->Notify();
  }

  std::vector<Event> Drain() { return events_.Drain(); }
  size_t dropped() const { return events_.dropped(); }

 protected:
  void OnMalformed(const Status& error) override {
    Event event;
    event.kind = Event::Kind::kRejected;
    event.error = error.WithContext(std::string(Traits::kTopic) + ": malformed payload");
    events_.Push(std::move(event));
  }

 private:
  void OnSample(const Sample& sample, const dds::SampleInfo& info, Event event) {
    StatusOr<Message> message = FromIdl(sample);
    if (!message.ok()) {
      event.kind = Event::Kind::kRejected;
      event.error =
          message.status().WithContext(std::string(Traits::kTopic) + ": " + Traits::Sender(sample));
      events_.Push(std::move(event));
      return;
    }
    {
      std::lock_guard lock(mutex_);
      key_by_instance_[info.instance_handle] = Traits::KeyOf(*message);
    }
    event.message = *std::move(message);
    events_.Push(std::move(event));
  }

  // Only a disposal withdraws an instance; a writer that vanished leaves its state in place.
  void OnInstanceGone(const dds::SampleInfo& info, Event event) {
    if (info.instance_state != dds::NOT_ALIVE_DISPOSED_INSTANCE_STATE) return;
    std::lock_guard lock(mutex_);
    // get_key_value is not supported by Fast DDS 2.9: remember each instance's key.
    const auto it = key_by_instance_.find(info.instance_handle);
    if (it == key_by_instance_.end()) return;
    event.kind = Event::Kind::kRemoved;
    event.message = it->second;
    events_.Push(std::move(event));
  }

  std::shared_ptr<WakeUp> wake_up_;
  SampleQueue<Event> events_;
  std::mutex mutex_;
  std::map<dds::InstanceHandle_t, Message> key_by_instance_;  // guarded by mutex_
};

template <typename Message>
StatusOr<std::unique_ptr<KeyedStateReader<Message>>> KeyedStateReader<Message>::Create(
    Participant& participant, std::shared_ptr<WakeUp> wake_up) {
  using Traits = TopicTraits<Message>;
  std::unique_ptr<KeyedStateReader> self(new KeyedStateReader());
  self->listener_ = std::make_unique<Listener>(std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      ReaderEndpoint::Create(participant, Traits::kTopic, Traits::Type(),
                             QosOf<Message>(participant).reader, self->listener_.get()));
  return self;
}

template <typename Message>
StatusOr<std::unique_ptr<KeyedStateReader<Message>>> KeyedStateReader<Message>::CreateForRobot(
    Participant& participant, const RobotId& robot, std::shared_ptr<WakeUp> wake_up) {
  using Traits = TopicTraits<Message>;
  if constexpr (!Traits::kKeyedByRobotFirst) {
    // The filter reads the sample's first field as the robot id; these topics start otherwise.
    return InternalError(std::string(Traits::kTopic) + " is not keyed by a robot id first");
  }
  std::unique_ptr<KeyedStateReader> self(new KeyedStateReader());
  self->listener_ = std::make_unique<Listener>(std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      ReaderEndpoint::Create(participant, Traits::kTopic, Traits::Type(),
                             QosOf<Message>(participant).reader, self->listener_.get(),
                             ContentFilter::OnlyRobot(robot.value)));
  return self;
}

template <typename Message>
KeyedStateReader<Message>::~KeyedStateReader() {
  endpoint_.reset();
}

template <typename Message>
std::vector<KeyedEvent<Message>> KeyedStateReader<Message>::Drain() {
  return listener_->Drain();
}

template <typename Message>
size_t KeyedStateReader<Message>::dropped() const {
  return listener_->dropped();
}

template class KeyedStateWriter<EntityMessage>;
template class KeyedStateReader<EntityMessage>;
template class KeyedStateWriter<SubmapMessage>;
template class KeyedStateReader<SubmapMessage>;
template class KeyedStateWriter<ObjectTemplateMessage>;
template class KeyedStateReader<ObjectTemplateMessage>;
template class KeyedStateWriter<ObjectModelMessage>;
template class KeyedStateReader<ObjectModelMessage>;
template class KeyedStateWriter<RouteGraphMessage>;
template class KeyedStateReader<RouteGraphMessage>;
template class KeyedStateWriter<RobotFrameMessage>;
template class KeyedStateReader<RobotFrameMessage>;
template class KeyedStateWriter<RobotAdmissionMessage>;
template class KeyedStateReader<RobotAdmissionMessage>;
template class KeyedStateWriter<FleetServerMessage>;
template class KeyedStateReader<FleetServerMessage>;

}  // namespace fleetmap::transport
