#include "common/security/security_identity.hpp"

#include <openssl/err.h>
#include <openssl/x509v3.h>
#include <sys/stat.h>

#include <fmt/format.h>

#include <filesystem>

#include "common/security/pem_files.hpp"
#include "common/security/security_folder.hpp"

namespace fleetmap::security {
namespace fs = std::filesystem;
namespace {

std::string Absolute(const fs::path& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  return error ? path.string() : absolute.lexically_normal().string();
}

// Checks `cert` against the CA (and the revocation list) at the current time.
Status VerifyCertificate(const std::string& cert_path, X509* cert, X509* ca, X509_CRL* crl,
                         const std::string& ca_path) {
  StorePtr store(X509_STORE_new());
  StoreCtxPtr context(X509_STORE_CTX_new());
  if (!store || !context || X509_STORE_add_cert(store.get(), ca) != 1 ||
      X509_STORE_add_crl(store.get(), crl) != 1 ||
      X509_STORE_CTX_init(context.get(), store.get(), cert, nullptr) != 1) {
    return InternalError(cert_path + ": cannot check: " + TakeOpenSslError());
  }
  X509_STORE_CTX_set_flags(context.get(), X509_V_FLAG_CRL_CHECK);
  if (X509_verify_cert(context.get()) == 1) return Status::Ok();
  ERR_clear_error();
  const int code = X509_STORE_CTX_get_error(context.get());
  std::string why = X509_verify_cert_error_string(code);
  switch (code) {
    case X509_V_ERR_CERT_HAS_EXPIRED:
      why = "expired on " + UtcText(ToTime(X509_get0_notAfter(cert)));
      break;
    case X509_V_ERR_CERT_NOT_YET_VALID:
      why = "not valid before " + UtcText(ToTime(X509_get0_notBefore(cert)));
      break;
    case X509_V_ERR_CERT_REVOKED:
      why = "revoked (on the fleet's revocation list)";
      break;
    case X509_V_ERR_UNABLE_TO_GET_ISSUER_CERT_LOCALLY:
    case X509_V_ERR_CERT_SIGNATURE_FAILURE:
    case X509_V_ERR_UNABLE_TO_GET_CRL:
      why = "not issued by the fleet CA " + ca_path + " (" + why + ")";
      break;
    default:
      break;
  }
  return InvalidArgumentError(cert_path + ": " + why);
}

// Checks that the S/MIME document at `path` is signed by `ca`.
Status VerifySignedDocument(const std::string& path, X509* ca, const std::string& ca_path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return InvalidArgumentError(path + ": missing");
  BioPtr file(BIO_new_file(path.c_str(), "r"));
  BIO* content = nullptr;
  Pkcs7Ptr signature(file ? SMIME_read_PKCS7(file.get(), &content) : nullptr);
  BioPtr content_owner(content);
  if (!signature) {
    return InvalidArgumentError(path + ": not an S/MIME signed document (" + TakeOpenSslError() +
                                ")");
  }
  StorePtr store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca);
  BioPtr out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(signature.get(), nullptr, store.get(), content, out.get(), PKCS7_TEXT) != 1) {
    return InvalidArgumentError(path + ": not signed by the fleet CA " + ca_path + " (" +
                                TakeOpenSslError() + ")");
  }
  return Status::Ok();
}

Status CheckPrivate(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return InvalidArgumentError(path + ": missing");
  if ((info.st_mode & 0077) != 0) {
    return InvalidArgumentError(path + ": a private key readable by others (mode " +
                                fmt::format("{:04o}", info.st_mode & 0777) +
                                "); make it 0600 (chmod 600)");
  }
  return Status::Ok();
}

}  // namespace

StatusOr<SecurityIdentity> LoadIdentity(const std::string& dir, const std::string& name) {
  const SecurityFolder folder(dir);
  std::error_code error;
  if (!fs::is_directory(folder.root(), error)) {
    return InvalidArgumentError(dir + ": no such security folder");
  }
  if (!fs::is_directory(folder.identity(name), error)) {
    return InvalidArgumentError(folder.identity(name).string() + ": missing: " + name +
                                " is not enrolled in " + dir + " (fleetmap security enroll --dir " +
                                dir + " --robot " + name + ", or --viewer " + name + ")");
  }
  SecurityIdentity identity;
  identity.name = name;
  identity.ca_cert = Absolute(folder.ca_cert());
  identity.cert = Absolute(folder.cert(name));
  identity.key = Absolute(folder.key(name));
  identity.governance = Absolute(folder.governance());
  identity.permissions = Absolute(folder.permissions(name));
  identity.crl = Absolute(folder.crl());

  FLEETMAP_ASSIGN_OR_RETURN(const CertPtr ca, ReadCertificate(identity.ca_cert));
  if (X509_check_ca(ca.get()) == 0) {
    return InvalidArgumentError(identity.ca_cert + ": not a CA certificate");
  }
  FLEETMAP_ASSIGN_OR_RETURN(const CrlPtr crl, ReadRevocationList(identity.crl));
  {
    KeyPtr ca_key(X509_get_pubkey(ca.get()));
    if (X509_CRL_verify(crl.get(), ca_key.get()) != 1) {
      ERR_clear_error();
      return InvalidArgumentError(identity.crl + ": not signed by the fleet CA " +
                                  identity.ca_cert);
    }
    const ASN1_TIME* next = X509_CRL_get0_nextUpdate(crl.get());
    if (next != nullptr && X509_cmp_current_time(next) < 0) {
      return InvalidArgumentError(identity.crl + ": out of date since " + UtcText(ToTime(next)) +
                                  "; revoke again or re-run init");
    }
  }
  FLEETMAP_ASSIGN_OR_RETURN(const CertPtr cert, ReadCertificate(identity.cert));
  FLEETMAP_RETURN_IF_ERROR(
      VerifyCertificate(identity.cert, cert.get(), ca.get(), crl.get(), identity.ca_cert));
  const std::string common_name = SubjectField(cert.get(), NID_commonName);
  if (common_name != name) {
    return InvalidArgumentError(identity.cert + ": is the certificate of \"" + common_name +
                                "\", not of \"" + name + "\"");
  }
  const auto role = ParseRole(SubjectField(cert.get(), NID_organizationalUnitName));
  if (!role) return InvalidArgumentError(identity.cert + ": no fleetmap role (subject OU)");
  identity.role = *role;
  identity.not_after = ToTime(X509_get0_notAfter(cert.get()));

  FLEETMAP_RETURN_IF_ERROR(CheckPrivate(identity.key));
  FLEETMAP_ASSIGN_OR_RETURN(const KeyPtr key, ReadPrivateKey(identity.key));
  if (X509_check_private_key(cert.get(), key.get()) != 1) {
    ERR_clear_error();
    return InvalidArgumentError(identity.key + ": is not the key of " + identity.cert);
  }
  FLEETMAP_RETURN_IF_ERROR(VerifySignedDocument(identity.governance, ca.get(), identity.ca_cert));
  FLEETMAP_RETURN_IF_ERROR(VerifySignedDocument(identity.permissions, ca.get(), identity.ca_cert));
  return identity;
}

std::string CommonNameOfSubject(const std::string& one_line_subject) {
  // Fields are "/KEY=value"; the CN is the last "/CN=" (values with '/' are escaped by OpenSSL
  // only in other forms, and fleetmap names have none).
  const size_t at = one_line_subject.rfind("/CN=");
  if (at == std::string::npos) return "";
  const size_t begin = at + 4;
  const size_t end = one_line_subject.find('/', begin);
  return one_line_subject.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

}  // namespace fleetmap::security
