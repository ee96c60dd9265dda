#pragma once

// `fleetmap security`'s operations on a fleet security folder (security_folder.hpp): make the
// fleet CA, the governance and the server's identity; enroll a robot or a viewer; revoke one;
// list who is enrolled. Keys are written 0600, everything else 0644, each file whole or not at
// all.

#include <ctime>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/security/access_documents.hpp"
#include "common/security/certificate_authority.hpp"

namespace fleetmap::security {

struct FleetSecurityOptions {
  int ca_days = 3650;       // the CA and its revocation list
  int identity_days = 365;  // each identity's certificate and permissions
};

// Makes the folder `dir` (new, or empty): the CA, the governance (signed), an empty revocation
// list and the server's identity. InvalidArgument if `dir` already holds a CA.
Status InitFleet(const std::string& dir, const FleetSecurityOptions& options);

// Enrolls `name` (a robot id, or a viewer's name) with `role`, valid for `validity`: a new key, a
// certificate of the fleet CA, and signed permissions. A name already enrolled and not revoked is
// InvalidArgument; a revoked one is enrolled afresh (new key, new serial).
Status Enroll(const std::string& dir, const std::string& name, Role role, Validity validity);

// Revokes `name`: its certificate's serial goes on the revocation list (re-signed; every
// participant that loads it refuses the identity from its next start), and its permissions are
// re-signed to allow nothing.
Status Revoke(const std::string& dir, const std::string& name);

struct EnrolledIdentity {
  std::string name;
  std::string role;
  std::string serial;
  std::time_t not_before = 0;
  std::time_t not_after = 0;
  bool revoked = false;
};

// Everyone enrolled in `dir`, by name.
StatusOr<std::vector<EnrolledIdentity>> ListIdentities(const std::string& dir);

}  // namespace fleetmap::security
