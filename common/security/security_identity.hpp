#pragma once

// One participant's DDS Security identity, taken from a fleet security folder and checked before
// DDS sees it, so that a bad file is an error naming the file (Fast DDS only logs that a
// participant could not be made).

#include <ctime>
#include <string>

#include "common/core/status.hpp"
#include "common/security/access_documents.hpp"

namespace fleetmap::security {

struct SecurityIdentity {
  std::string name;  // the subject's CN: a robot id, "server", or a viewer's name
  Role role = Role::kRobot;
  // Absolute paths of the files Fast DDS loads.
  std::string ca_cert;
  std::string cert;
  std::string key;
  std::string governance;
  std::string permissions;
  std::string crl;
  std::time_t not_after = 0;
};

// `name`'s identity in the folder `dir` (security_folder.hpp), checked: every file present and
// readable; the certificate issued by the folder's CA, in its validity period, not on the
// revocation list, for CN=`name`; the key its key and readable by its owner only; the governance
// and the permissions signed by the CA; the revocation list signed by the CA and current.
// InvalidArgument, naming the file and what is wrong, otherwise.
StatusOr<SecurityIdentity> LoadIdentity(const std::string& dir, const std::string& name);

// The CN of a subject as OpenSSL's one-line form writes it ("/O=fleetmap/OU=robot/CN=robot1"), as
// DDS identity tokens carry it (dds.cert.sn); "" if there is none.
std::string CommonNameOfSubject(const std::string& one_line_subject);

}  // namespace fleetmap::security
