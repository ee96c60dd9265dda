#include "common/security/pem_files.hpp"

#include <fcntl.h>
#include <openssl/bn.h>
#include <openssl/pem.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "common/security/utc_time.hpp"

namespace fleetmap::security {
namespace {

// Reads one PEM object of type `Pointer` from `path` with OpenSSL's `read` (PEM_read_bio_X509...);
// an error names the file and whether it is missing, unreadable or not a PEM `what`.
template <typename Pointer, typename Object>
StatusOr<Pointer> ReadPem(const std::string& path,
                          Object* (*read)(BIO*, Object**, pem_password_cb*, void*),
                          const char* what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return InvalidArgumentError(path + ": missing (no such file)");
  }
  BioPtr file(BIO_new_file(path.c_str(), "r"));
  if (!file) return InvalidArgumentError(path + ": cannot be read (" + TakeOpenSslError() + ")");
  Pointer object(read(file.get(), nullptr, nullptr, nullptr));
  if (!object) {
    return InvalidArgumentError(path + ": not a PEM " + what + " (" + TakeOpenSslError() + ")");
  }
  return object;
}

}  // namespace

StatusOr<CertPtr> ReadCertificate(const std::string& path) {
  return ReadPem<CertPtr>(path, PEM_read_bio_X509, "certificate");
}

StatusOr<KeyPtr> ReadPrivateKey(const std::string& path) {
  return ReadPem<KeyPtr>(path, PEM_read_bio_PrivateKey, "private key");
}

StatusOr<CrlPtr> ReadRevocationList(const std::string& path) {
  return ReadPem<CrlPtr>(path, PEM_read_bio_X509_CRL, "revocation list");
}

std::vector<std::string> RevokedSerials(X509_CRL* crl) {
  std::vector<std::string> serials;
  STACK_OF(X509_REVOKED)* revoked = X509_CRL_get_REVOKED(crl);
  for (int i = 0; i < sk_X509_REVOKED_num(revoked); ++i) {
    const ASN1_INTEGER* serial = X509_REVOKED_get0_serialNumber(sk_X509_REVOKED_value(revoked, i));
    std::unique_ptr<BIGNUM, decltype(&BN_free)> number(ASN1_INTEGER_to_BN(serial, nullptr),
                                                       BN_free);
    char* hex = number ? BN_bn2hex(number.get()) : nullptr;
    if (hex != nullptr) serials.emplace_back(hex);
    OPENSSL_free(hex);
  }
  return serials;
}

std::string SubjectField(X509* cert, int nid) {
  char text[256] = {0};
  if (X509_NAME_get_text_by_NID(X509_get_subject_name(cert), nid, text, sizeof(text)) < 0) {
    return "";
  }
  return text;
}

std::time_t ToTime(const ASN1_TIME* time) {
  std::tm tm{};
  if (ASN1_TIME_to_tm(time, &tm) != 1) return 0;
  return timegm(&tm);
}

std::string UtcText(std::time_t time) { return FormatUtc(time, "%Y-%m-%d %H:%M:%S UTC"); }

Status WriteSecurityFile(const std::string& path, const std::string& contents, bool private_key) {
  // Not common/core's WriteFileAtomically: a key must never exist, even for a moment, with a mode
  // wider than 0600, so the temporary file is made with that mode.
  const std::string temporary = path + ".tmp." + std::to_string(getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC,
                        private_key ? 0600 : 0644);
  if (fd < 0) return UnavailableError(path + ": cannot write: " + std::strerror(errno));
  size_t written = 0;
  while (written < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + written, contents.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<size_t>(n);
  }
  const bool ok = written == contents.size() && ::fchmod(fd, private_key ? 0600 : 0644) == 0 &&
                  ::fsync(fd) == 0;
  const int saved_errno = errno;
  ::close(fd);
  if (!ok || std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(ok ? errno : saved_errno);
    std::remove(temporary.c_str());
    return UnavailableError(path + ": cannot write: " + reason);
  }
  return Status::Ok();
}

}  // namespace fleetmap::security
