#pragma once

// The fleet's certificate authority: one self-signed CA that is both the identity CA (it issues
// every participant's certificate and the revocation list) and the permissions CA (it signs the
// governance and the permissions documents). OpenSSL, ECDSA on P-256 with SHA-256 (what Fast DDS's
// PKI-DH calls ECDSA-SHA256).

#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::security {

// A validity period, seconds since the epoch (UTC).
struct Validity {
  std::time_t not_before = 0;
  std::time_t not_after = 0;

  // From now (less a minute, for clocks a little behind) for `days` days.
  static Validity FromNow(int days);
};

// A key and its certificate, both PEM.
struct IssuedIdentity {
  std::string key_pem;
  std::string cert_pem;
  std::string serial;   // hex
  std::string subject;  // RFC 2253, as DDS permissions name it
};

class CertificateAuthority {
 public:
  // A new CA named `common_name` (subject O=fleetmap, CN=common_name).
  static StatusOr<std::unique_ptr<CertificateAuthority>> Create(const std::string& common_name,
                                                                Validity validity);
  // The CA of a fleet folder: its certificate and key (PEM files); errors name the file.
  static StatusOr<std::unique_ptr<CertificateAuthority>> Load(const std::string& cert_path,
                                                              const std::string& key_path);
  ~CertificateAuthority();
  CertificateAuthority(const CertificateAuthority&) = delete;
  CertificateAuthority& operator=(const CertificateAuthority&) = delete;

  std::string cert_pem() const;
  std::string key_pem() const;

  // A new key and a certificate for subject O=fleetmap, OU=`organizational_unit`, CN=`name`.
  StatusOr<IssuedIdentity> Issue(const std::string& name, const std::string& organizational_unit,
                                 Validity validity) const;

  // `text` signed as S/MIME (multipart/signed, the signature detached, the content as text/plain):
  // the form DDS Security reads governance and permissions in.
  StatusOr<std::string> SignDocument(const std::string& text) const;

  // A revocation list of this CA naming `revoked_serials` (hex), valid as long as the CA (a list
  // past its next update fails every check, so it must not expire before the certificates).
  StatusOr<std::string> RevocationList(const std::vector<std::string>& revoked_serials) const;

 private:
  struct Keys;
  explicit CertificateAuthority(std::unique_ptr<Keys> keys);
  std::unique_ptr<Keys> keys_;
};

}  // namespace fleetmap::security
