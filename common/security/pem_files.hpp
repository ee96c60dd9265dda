#pragma once

// Reading and writing the PEM files of a security folder. Private to common/security. Every error
// names the file.

#include <ctime>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/security/openssl_handles.hpp"

namespace fleetmap::security {

StatusOr<CertPtr> ReadCertificate(const std::string& path);
StatusOr<KeyPtr> ReadPrivateKey(const std::string& path);
StatusOr<CrlPtr> ReadRevocationList(const std::string& path);

// The serials (hex) a revocation list names.
std::vector<std::string> RevokedSerials(X509_CRL* crl);

// A certificate field of its subject (NID_commonName, NID_organizationalUnitName), or "".
std::string SubjectField(X509* cert, int nid);

std::time_t ToTime(const ASN1_TIME* time);
// "2027-12-02 14:00:00 UTC"
std::string UtcText(std::time_t time);

// Writes `contents` to `path` whole or not at all, with file mode 0600 (a private key) or 0644.
Status WriteSecurityFile(const std::string& path, const std::string& contents, bool private_key);

}  // namespace fleetmap::security
