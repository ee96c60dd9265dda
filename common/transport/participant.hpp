#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/security/security_identity.hpp"

namespace eprosima::fastdds::dds {
class DomainParticipant;
class Publisher;
class Subscriber;
class Topic;
class TypeSupport;
}  // namespace eprosima::fastdds::dds

namespace fleetmap::transport {

class ParticipantIdentities;
class ServedWriters;

struct ParticipantOptions {
  // Unset: the FLEETMAP_DOMAIN environment variable, else 0. Valid DDS domains are 0..232.
  std::optional<int> domain_id;
  std::string name = "fleetmap";
  // Unset: true when FLEETMAP_LOCALHOST_ONLY or ROS_LOCALHOST_ONLY is "1". Localhost-only uses UDP
  // on 127.0.0.1 with unicast discovery and sends nothing to any other interface.
  std::optional<bool> localhost_only;
  // Fast DDS hands samples between entities of one process without the wire by default. Tests
  // that must exercise serialization and UDP turn it off; the setting is process-wide.
  bool intraprocess_delivery = true;
  // Fast DDS discovery servers to discover through instead of simple (multicast or initial-peer)
  // discovery, in ROS 2's ROS_DISCOVERY_SERVER syntax: "IP:PORT", or "IP:PORT;IP:PORT" for the
  // servers of ids 0 and 1 (`fastdds discovery -i 0 -l IP -p PORT` starts server 0). Unset:
  // $ROS_DISCOVERY_SERVER, else simple discovery.
  std::optional<std::string> discovery_server;
  // How long a silent participant is kept before its endpoints are dropped.
  std::chrono::milliseconds participant_lease{6000};
  // DDS Security (docs/security.md): this participant authenticates as `security->name`, checks
  // every peer against the fleet CA, and keeps to its signed permissions. A robot's publisher
  // then writes in the DDS partition named after the robot (its permissions allow no other), and
  // the subscriber reads every partition. Unset: no security (anyone on the domain may join).
  std::optional<security::SecurityIdentity> security;
  // The strength of this participant's writers on the exclusive topics (served_state.hpp): of the
  // live servers, readers take the strongest's samples. A standby gets a lower one.
  int32_t ownership_strength = 0;

  // Sets `security` to `identity`'s identity in the fleet security folder `dir`, checked
  // (security::LoadIdentity): an error names the file and what is wrong with it.
  Status UseSecurityFolder(const std::string& dir, const std::string& identity);

  void Describe(OptionsPrinter& out) const;
};

// Resolves the domain id from the options and the environment; an error names the bad value.
StatusOr<int> ResolveDomainId(const std::optional<int>& requested);
bool ResolveLocalhostOnly(const std::optional<bool>& requested);
// The discovery servers from the options and the environment ("" for simple discovery); an error
// names the bad value and where it came from.
StatusOr<std::string> ResolveDiscoveryServer(const std::optional<std::string>& requested);

// One DDS domain participant with one publisher and one subscriber, and the topics its readers
// and writers share. Not thread-safe: create readers and writers from one thread (the node's).
// Readers and writers must be destroyed before their participant.
class Participant {
 public:
  static StatusOr<std::unique_ptr<Participant>> Create(const ParticipantOptions& options);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  int domain_id() const { return domain_id_; }
  bool localhost_only() const { return localhost_only_; }
  // The discovery servers it discovers through; empty for simple discovery.
  const std::string& discovery_server() const { return discovery_server_; }
  // The participant's GUID prefix in hex (24 digits): the first digits of every WriterId of its
  // writers (see writer_id.hpp), so a node can tell its own samples from another participant's.
  std::string id() const;

  bool secured() const { return secured_; }
  // On a secured participant: the authenticated name (certificate CN) of the participant that
  // owns `writer_id` (a WriterId), or nullopt if it gave none. Always nullopt when not secured.
  std::optional<std::string> AuthenticatedName(const std::string& writer_id) const;
  // On a secured participant: seconds from its creation until it authenticated a participant
  // named `name` (DDS Security's handshake with it done), or nullopt if not (yet).
  std::optional<double> SecondsToAuthenticate(const std::string& name) const;
  // The host (IPv4 address) of the participant that owns `writer_id`, as its discovery announced
  // it, or nullopt if not known (yet) or it announced shared memory only.
  std::optional<std::string> HostOf(const std::string& writer_id) const;
  // How many writers of the topic `topic_name` (e.g. kFusedTilesTopic) other participants have,
  // as discovery reports them: a peer's presence without reading its samples.
  size_t RemoteWritersOf(const std::string& topic_name) const;

  // For transport's own readers and writers: the topic `name` of `type` (registering the type
  // on first use); each AcquireTopic is paired with one ReleaseTopic.
  StatusOr<eprosima::fastdds::dds::Topic*> AcquireTopic(const std::string& name,
                                                        eprosima::fastdds::dds::TypeSupport type);
  void ReleaseTopic(eprosima::fastdds::dds::Topic* topic);

  // Writes the last sample of every instance of this participant's writers on the exclusive
  // topics again (served_state.hpp): what a server does when it starts serving, since readers
  // refused what it wrote while another server was their owner. The number of instances.
  size_t RepublishServedState();
  int32_t ownership_strength() const { return ownership_strength_; }
  std::chrono::milliseconds participant_lease() const { return participant_lease_; }
  // For transport's own writers on the exclusive topics.
  ServedWriters& served_writers() { return *served_writers_; }

  eprosima::fastdds::dds::Publisher* publisher() const { return publisher_; }
  eprosima::fastdds::dds::Subscriber* subscriber() const { return subscriber_; }
  eprosima::fastdds::dds::DomainParticipant* dds_participant() const { return participant_; }

 private:
  Participant();

  struct TopicEntry {
    eprosima::fastdds::dds::Topic* topic = nullptr;
    int users = 0;
  };

  int domain_id_ = 0;
  bool localhost_only_ = false;
  std::string discovery_server_;
  bool secured_ = false;
  int32_t ownership_strength_ = 0;
  std::chrono::milliseconds participant_lease_{0};
  // Declared before the participant: its writers are deleted first.
  std::unique_ptr<ServedWriters> served_writers_;
  // Declared before the participant: Fast DDS calls it until the participant is deleted.
  std::unique_ptr<ParticipantIdentities> identities_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, TopicEntry> topics_;
};

}  // namespace fleetmap::transport
