#include "common/security/fleet_security.hpp"

#include <fmt/format.h>
#include <openssl/x509v3.h>

#include <algorithm>
#include <filesystem>

#include "common/core/ids.hpp"
#include "common/security/pem_files.hpp"
#include "common/security/security_folder.hpp"

namespace fleetmap::security {
namespace fs = std::filesystem;
namespace {

Status MakeDirectory(const fs::path& path) {
  std::error_code error;
  fs::create_directories(path, error);
  if (error) return UnavailableError(path.string() + ": cannot create: " + error.message());
  return Status::Ok();
}

StatusOr<std::unique_ptr<CertificateAuthority>> LoadCa(const SecurityFolder& folder) {
  if (!fs::exists(folder.ca_cert())) {
    return NotFoundError(folder.root().string() + ": no fleet CA (" + folder.ca_cert().string() +
                         " is missing); run `fleetmap security init --dir " +
                         folder.root().string() + "` first");
  }
  return CertificateAuthority::Load(folder.ca_cert(), folder.ca_key());
}

// Writes `name`'s permissions, signed.
Status WritePermissions(const SecurityFolder& folder, const CertificateAuthority& ca,
                        const PermissionsRequest& request) {
  const std::string xml = PermissionsXml(request);
  FLEETMAP_ASSIGN_OR_RETURN(const std::string signed_xml, ca.SignDocument(xml));
  FLEETMAP_RETURN_IF_ERROR(
      WriteSecurityFile(folder.permissions_xml(request.name), xml, /*private_key=*/false));
  return WriteSecurityFile(folder.permissions(request.name), signed_xml, /*private_key=*/false);
}

Status IssueIdentity(const SecurityFolder& folder, const CertificateAuthority& ca,
                     const std::string& name, Role role, Validity validity) {
  FLEETMAP_ASSIGN_OR_RETURN(const IssuedIdentity issued, ca.Issue(name, RoleName(role), validity));
  FLEETMAP_RETURN_IF_ERROR(MakeDirectory(folder.identity(name)));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.key(name), issued.key_pem, true));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.cert(name), issued.cert_pem, false));
  return WritePermissions(folder, ca,
                          PermissionsRequest{name, role, issued.subject, validity.not_before,
                                             validity.not_after, /*revoked=*/false});
}

StatusOr<EnrolledIdentity> ReadEnrolled(const SecurityFolder& folder, const std::string& name,
                                        const std::vector<std::string>& revoked_serials) {
  FLEETMAP_ASSIGN_OR_RETURN(const CertPtr cert, ReadCertificate(folder.cert(name)));
  EnrolledIdentity identity;
  identity.name = name;
  identity.role = SubjectField(cert.get(), NID_organizationalUnitName);
  identity.serial = SerialHex(cert.get());
  identity.not_before = ToTime(X509_get0_notBefore(cert.get()));
  identity.not_after = ToTime(X509_get0_notAfter(cert.get()));
  identity.revoked = std::find(revoked_serials.begin(), revoked_serials.end(), identity.serial) !=
                     revoked_serials.end();
  return identity;
}

StatusOr<std::vector<std::string>> CurrentRevocations(const SecurityFolder& folder) {
  FLEETMAP_ASSIGN_OR_RETURN(const CrlPtr crl, ReadRevocationList(folder.crl()));
  return RevokedSerials(crl.get());
}

}  // namespace

Status InitFleet(const std::string& dir, const FleetSecurityOptions& options) {
  const SecurityFolder folder(dir);
  if (fs::exists(folder.ca_cert()) || fs::exists(folder.ca_key())) {
    return InvalidArgumentError(dir + ": already holds a fleet CA (" + folder.ca_cert().string() +
                                "); enroll into it, or choose a new folder");
  }
  FLEETMAP_RETURN_IF_ERROR(MakeDirectory(folder.ca_cert().parent_path()));
  FLEETMAP_ASSIGN_OR_RETURN(
      const auto ca,
      CertificateAuthority::Create("fleetmap fleet CA", Validity::FromNow(options.ca_days)));
  // The key first: a folder with a certificate but no key could never enroll anyone.
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.ca_key(), ca->key_pem(), true));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.ca_cert(), ca->cert_pem(), false));
  const std::string governance = GovernanceXml();
  FLEETMAP_ASSIGN_OR_RETURN(const std::string signed_governance, ca->SignDocument(governance));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.governance_xml(), governance, false));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.governance(), signed_governance, false));
  FLEETMAP_ASSIGN_OR_RETURN(const std::string crl, ca->RevocationList({}));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.crl(), crl, false));
  return IssueIdentity(folder, *ca, kServerIdentity, Role::kServer,
                       Validity::FromNow(options.identity_days));
}

Status Enroll(const std::string& dir, const std::string& name, Role role, Validity validity) {
  if (!IsValidRobotName(name)) {
    return InvalidArgumentError(fmt::format(
        "\"{}\" is not a valid name: [A-Za-z][A-Za-z0-9_]*, at most 64 characters (a robot's "
        "id, as in its ROS 2 namespace)",
        name));
  }
  if ((name == kServerIdentity) != (role == Role::kServer)) {
    return InvalidArgumentError(
        fmt::format("\"{}\" is the server's identity and only the server's", kServerIdentity));
  }
  if (validity.not_after <= validity.not_before) {
    return InvalidArgumentError("an identity must be valid for some time");
  }
  const SecurityFolder folder(dir);
  FLEETMAP_ASSIGN_OR_RETURN(const auto ca, LoadCa(folder));
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<std::string> revoked, CurrentRevocations(folder));
  if (fs::exists(folder.cert(name))) {
    FLEETMAP_ASSIGN_OR_RETURN(const EnrolledIdentity existing, ReadEnrolled(folder, name, revoked));
    if (!existing.revoked && role != Role::kServer) {
      return InvalidArgumentError(name + " is already enrolled in " + dir + " (as " +
                                  existing.role + ", until " + UtcText(existing.not_after) +
                                  "); revoke it first to enroll it again");
    }
  }
  return IssueIdentity(folder, *ca, name, role, validity);
}

Status Revoke(const std::string& dir, const std::string& name) {
  const SecurityFolder folder(dir);
  FLEETMAP_ASSIGN_OR_RETURN(const auto ca, LoadCa(folder));
  if (!fs::exists(folder.cert(name))) {
    return NotFoundError(name + " is not enrolled in " + dir + " (no " +
                         folder.cert(name).string() + ")");
  }
  FLEETMAP_ASSIGN_OR_RETURN(std::vector<std::string> revoked, CurrentRevocations(folder));
  FLEETMAP_ASSIGN_OR_RETURN(const CertPtr cert, ReadCertificate(folder.cert(name)));
  const std::string serial = SerialHex(cert.get());
  if (std::find(revoked.begin(), revoked.end(), serial) == revoked.end()) {
    revoked.push_back(serial);
  }
  FLEETMAP_ASSIGN_OR_RETURN(const std::string crl, ca->RevocationList(revoked));
  FLEETMAP_RETURN_IF_ERROR(WriteSecurityFile(folder.crl(), crl, false));
  const Role role =
      ParseRole(SubjectField(cert.get(), NID_organizationalUnitName)).value_or(Role::kRobot);
  return WritePermissions(folder, *ca,
                          PermissionsRequest{name, role, SubjectRfc2253(cert.get()),
                                             ToTime(X509_get0_notBefore(cert.get())),
                                             ToTime(X509_get0_notAfter(cert.get())),
                                             /*revoked=*/true});
}

StatusOr<std::vector<EnrolledIdentity>> ListIdentities(const std::string& dir) {
  const SecurityFolder folder(dir);
  if (!fs::exists(folder.ca_cert())) {
    return NotFoundError(dir + ": not a fleet security folder (no " + folder.ca_cert().string() +
                         ")");
  }
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<std::string> revoked, CurrentRevocations(folder));
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder.identities(), error)) {
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  std::vector<EnrolledIdentity> identities;
  for (const std::string& name : names) {
    FLEETMAP_ASSIGN_OR_RETURN(EnrolledIdentity identity, ReadEnrolled(folder, name, revoked));
    identities.push_back(std::move(identity));
  }
  return identities;
}

}  // namespace fleetmap::security
