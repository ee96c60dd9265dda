#pragma once

// Internal to transport: who each discovered participant is. Its host: the IPv4 address of its
// first unicast locator (a budget per host bounds what many participants of one machine can make
// the server hold). On a secured participant also its name: DDS Security authenticates a peer's
// certificate in its handshake and checks its permissions against that certificate's subject; the
// subject's CN also travels in the peer's identity token (dds.cert.sn), which this listener keeps
// per participant (GUID prefix), so the server can check a sample's robot id against the name of
// the participant that wrote it. Thread-safe: Fast DDS calls the listener on its discovery thread.

#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>

namespace fleetmap::transport {

class ParticipantIdentities : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  // The name (certificate CN) of the participant whose GUID prefix (24 hex digits) starts
  // `writer_id`, or nullopt when that participant is unknown or gave none.
  std::optional<std::string> NameOf(const std::string& writer_id) const;
  // The IPv4 address (dotted) of the participant that owns `writer_id`, or nullopt when that
  // participant is unknown or announced no IPv4 unicast locator (shared memory only).
  std::optional<std::string> HostOf(const std::string& writer_id) const;
  // Seconds from this listener's creation (its participant's) until the first participant named
  // `name` was authenticated (the DDS Security handshake done), or nullopt if none was yet.
  std::optional<double> SecondsUntilAuthenticated(const std::string& name) const;
  // How many writers of the topic `topic_name` other participants have now, as discovered.
  size_t RemoteWritersOf(const std::string& topic_name) const;

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  void onParticipantAuthentication(
      eprosima::fastdds::dds::DomainParticipant* participant,
      eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override;
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;

 private:
  const std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();
  mutable std::mutex mutex_;
  std::map<std::string, std::string> name_by_prefix_;
  std::map<std::string, std::string> host_by_prefix_;
  std::map<std::string, double> authenticated_after_by_prefix_;    // seconds since created_
  std::map<std::string, std::set<std::string>> writers_by_topic_;  // writer GUIDs, as text
};

}  // namespace fleetmap::transport
