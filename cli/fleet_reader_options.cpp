#include "cli/fleet_reader_options.hpp"

namespace fleetmap::cli {

StatusOr<transport::ParticipantOptions> FleetReaderOptions::Participant(
    const std::string& name) const {
  transport::ParticipantOptions dds;
  dds.domain_id = domain;
  dds.name = name;
  if (localhost_only) dds.localhost_only = true;
  dds.discovery_server = discovery_server;
  if (!security_dir.empty()) {
    if (const Status secured = dds.UseSecurityFolder(security_dir, security_identity);
        !secured.ok()) {
      return secured.WithContext("--security");
    }
  }
  return dds;
}

FleetReaderFlags::FleetReaderFlags(CLI::App* command, FleetReaderOptions* options)
    : options_(options) {
  command->add_option("--domain", *domain_, "DDS domain id (default: $FLEETMAP_DOMAIN, else 0)")
      ->default_str("0");  // what -1, "not given", ends as
  command->add_flag("--localhost-only", options->localhost_only,
                    "use UDP on 127.0.0.1 only (also $FLEETMAP_LOCALHOST_ONLY=1)");
  command->add_option("--discovery-server", options->discovery_server,
                      "Fast DDS discovery servers to discover through, IP:PORT[;IP:PORT] (also "
                      "$ROS_DISCOVERY_SERVER)");
  command->add_option("--security", options->security_dir,
                      "DDS Security folder (fleetmap security): join the secured fleet as "
                      "--identity");
  command
      ->add_option("--identity", options->security_identity,
                   "the enrolled viewer to join as (fleetmap security enroll --viewer NAME)")
      ->capture_default_str();
}

void FleetReaderFlags::ApplyDomain() const {
  if (*domain_ >= 0) options_->domain = *domain_;
}

}  // namespace fleetmap::cli
