#pragma once

// The layout of a fleet security folder (docs/security.md):
//
//   D/ca/ca.pem                      the fleet CA's certificate (identity and permissions CA)
//   D/ca/ca.key                      its private key (0600): needed only where robots are enrolled
//   D/governance.xml, governance.p7s the governance, and the same signed by the CA (S/MIME)
//   D/crl.pem                        the CA's revocation list
//   D/identities/<name>/cert.pem     an identity's certificate (subject CN=<name>, OU=<role>)
//                       key.pem      its private key (0600)
//                       permissions.xml, permissions.p7s   its permissions, and signed
//
// A robot's machine needs ca/ca.pem, governance.p7s, crl.pem and its own identities/<name>.

#include <filesystem>
#include <string>

namespace fleetmap::security {

class SecurityFolder {
 public:
  explicit SecurityFolder(std::filesystem::path root) : root_(std::move(root)) {}

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path ca_cert() const { return root_ / "ca" / "ca.pem"; }
  std::filesystem::path ca_key() const { return root_ / "ca" / "ca.key"; }
  std::filesystem::path governance_xml() const { return root_ / "governance.xml"; }
  std::filesystem::path governance() const { return root_ / "governance.p7s"; }
  std::filesystem::path crl() const { return root_ / "crl.pem"; }
  std::filesystem::path identities() const { return root_ / "identities"; }
  std::filesystem::path identity(const std::string& name) const { return identities() / name; }
  std::filesystem::path cert(const std::string& name) const { return identity(name) / "cert.pem"; }
  std::filesystem::path key(const std::string& name) const { return identity(name) / "key.pem"; }
  std::filesystem::path permissions_xml(const std::string& name) const {
    return identity(name) / "permissions.xml";
  }
  std::filesystem::path permissions(const std::string& name) const {
    return identity(name) / "permissions.p7s";
  }

 private:
  std::filesystem::path root_;
};

// The identity fleetmap-server takes.
inline constexpr char kServerIdentity[] = "server";

}  // namespace fleetmap::security
