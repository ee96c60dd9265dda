#include "common/transport/internal/qos.hpp"

#include <type_traits>

#include <algorithm>

namespace fleetmap::transport {
namespace {

namespace dds = eprosima::fastdds::dds;

using std::chrono::milliseconds;

eprosima::fastrtps::Duration_t ToDuration(milliseconds ms) {
  return eprosima::fastrtps::Duration_t(static_cast<double>(ms.count()) / 1000.0);
}

// Reliability timings for lossy Wi-Fi; docs/fleet.md (Reliability on lossy networks) gives the
// reasons and the measurements. A reader learns that the last sample of a burst was lost only
// from the writer's next heartbeat, so the heartbeat period bounds how late a lost sample is
// repaired: Fast DDS's 3 s default made p99 2.5 s at 5 % loss. Periodic heartbeats stop while
// every reader has acknowledged everything, so a short period costs nothing on an idle topic.
constexpr milliseconds kHeartbeatPeriod{100};
// How long a writer waits to gather ACKNACKs before it repairs, and a reader before it answers a
// heartbeat: short, since with unicast every wait adds straight to the repair time.
constexpr milliseconds kNackResponseDelay{5};
constexpr milliseconds kHeartbeatResponseDelay{5};

// Both ends of a topic get the same timings, whatever the topic's other QoS.
EndpointQos WithLossyNetworkTimings(EndpointQos qos) {
  auto& writer = qos.writer.reliable_writer_qos().times;
  writer.heartbeatPeriod = ToDuration(kHeartbeatPeriod);
  writer.nackResponseDelay = ToDuration(kNackResponseDelay);
  writer.nackSupressionDuration = ToDuration(milliseconds(0));
  qos.reader.reliable_reader_qos().times.heartbeatResponseDelay =
      ToDuration(kHeartbeatResponseDelay);
  return qos;
}

// Reliable, transient local, keep last 1 per instance and as many instances as there are: the
// 10-instance default silently drops robot 11.
template <typename Qos>
void StateTopic(Qos& qos) {
  qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
  qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 1;
  qos.resource_limits().max_instances = 0;  // <= 0: unlimited
  qos.resource_limits().max_samples = 0;
  qos.resource_limits().max_samples_per_instance = 1;
  qos.resource_limits().allocated_samples = 16;
  if constexpr (std::is_same_v<Qos, dds::DataWriterQos>) {
    // One content filter per filtered reader (an agent's, robot_id_filter.hpp), evaluated here on
    // the writer's side: Fast DDS keeps 32 by default and sends unfiltered past them.
    qos.writer_resource_limits().reader_filters_allocation =
        eprosima::fastrtps::ResourceLimitedContainerConfig(0, 4096, 1);
  }
}

}  // namespace

EndpointQos RobotStatusQos() {
  EndpointQos qos;
  StateTopic(qos.writer);
  StateTopic(qos.reader);
  // MANUAL_BY_TOPIC: each status sample asserts its writer's liveliness. With AUTOMATIC, Fast DDS
  // 2.9 lets one live participant's heartbeats keep a dead one's writers alive (measured: a killed
  // agent went unnoticed until the other agent left), and a hung agent would look alive too.
  qos.writer.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
  qos.writer.liveliness().lease_duration = ToDuration(kRobotLivelinessLease);
  qos.writer.liveliness().announcement_period = ToDuration(kRobotLivelinessLease / 3);
  qos.reader.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
  qos.reader.liveliness().lease_duration = ToDuration(kRobotLivelinessLease);
  // Keep the instance registered when a robot's writer vanishes, so the reader sees the
  // NOT_ALIVE_NO_WRITERS transition instead of a silent removal.
  qos.writer.writer_data_lifecycle().autodispose_unregistered_instances = false;
  return WithLossyNetworkTimings(qos);
}

EndpointQos OccupancyGridQos() {
  EndpointQos qos;
  StateTopic(qos.writer);
  StateTopic(qos.reader);
  qos.writer.publish_mode().kind = dds::ASYNCHRONOUS_PUBLISH_MODE;
  qos.writer.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  qos.reader.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  return WithLossyNetworkTimings(qos);
}

EndpointQos OccupancyGridUpdateQos() {
  EndpointQos qos;
  for (auto* history : {&qos.writer.history(), &qos.reader.history()}) {
    history->kind = dds::KEEP_LAST_HISTORY_QOS;
    history->depth = 16;
  }
  qos.writer.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.reader.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.writer.durability().kind = dds::VOLATILE_DURABILITY_QOS;
  qos.reader.durability().kind = dds::VOLATILE_DURABILITY_QOS;
  return WithLossyNetworkTimings(qos);
}

EndpointQos KeyedStateQos() {
  EndpointQos qos;
  StateTopic(qos.writer);
  StateTopic(qos.reader);
  qos.writer.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  qos.reader.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  return WithLossyNetworkTimings(qos);
}

EndpointQos VectorTileQos() { return KeyedStateQos(); }

EndpointQos ServedStateQos(int32_t strength) {
  EndpointQos qos = KeyedStateQos();
  qos.writer.ownership().kind = dds::EXCLUSIVE_OWNERSHIP_QOS;
  qos.reader.ownership().kind = dds::EXCLUSIVE_OWNERSHIP_QOS;
  qos.writer.ownership_strength().value = static_cast<uint32_t>(std::max(0, strength));
  // MANUAL_BY_TOPIC at both ends. Fast DDS 2.9 watches a remote writer under the *reader's* kind
  // and lease (and only when the lease is finite), and one assertion of an AUTOMATIC or
  // MANUAL_BY_PARTICIPANT writer renews every writer the reader watches under that kind, whoever
  // owns it (LivelinessManager::assert_liveliness). A reader requesting AUTOMATIC would let the
  // standby's assertions keep the dead server alive until its participant lease ran out
  // (measured: 6 s, not 1 s); under MANUAL_BY_TOPIC each writer renews only itself.
  qos.writer.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
  qos.writer.liveliness().lease_duration = ToDuration(kServedLivelinessLease);
  qos.writer.liveliness().announcement_period = ToDuration(kServedLivelinessLease / 4);
  qos.reader.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
  qos.reader.liveliness().lease_duration = ToDuration(kServedLivelinessLease);
  return qos;
}

EndpointQos TfQos() {
  EndpointQos qos;
  for (auto* history : {&qos.writer.history(), &qos.reader.history()}) {
    history->kind = dds::KEEP_LAST_HISTORY_QOS;
    history->depth = 100;
  }
  qos.writer.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.reader.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.writer.durability().kind = dds::VOLATILE_DURABILITY_QOS;
  qos.reader.durability().kind = dds::VOLATILE_DURABILITY_QOS;
  return WithLossyNetworkTimings(qos);
}

}  // namespace fleetmap::transport
