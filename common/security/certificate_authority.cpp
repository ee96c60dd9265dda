#include "common/security/certificate_authority.hpp"

#include <openssl/bn.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/rand.h>
#include <openssl/x509v3.h>

#include "common/security/openssl_handles.hpp"

namespace fleetmap::security {

struct CertificateAuthority::Keys {
  KeyPtr key;
  CertPtr cert;
};

namespace {

constexpr char kOrganization[] = "fleetmap";

StatusOr<KeyPtr> NewKey() {
  KeyPtr key(EVP_EC_gen("P-256"));
  if (!key) return InternalError("cannot make a P-256 key: " + TakeOpenSslError());
  return key;
}

// 64 random bits, positive: serials must be unique per CA (RFC 5280 4.1.2.2).
Status SetRandomSerial(X509* cert) {
  unsigned char bytes[8];
  if (RAND_bytes(bytes, sizeof(bytes)) != 1) {
    return InternalError("no random serial: " + TakeOpenSslError());
  }
  bytes[0] &= 0x7f;
  std::unique_ptr<BIGNUM, decltype(&BN_free)> number(BN_bin2bn(bytes, sizeof(bytes), nullptr),
                                                     BN_free);
  if (!number || BN_to_ASN1_INTEGER(number.get(), X509_get_serialNumber(cert)) == nullptr) {
    return InternalError("no random serial: " + TakeOpenSslError());
  }
  return Status::Ok();
}

Status AddEntry(X509_NAME* name, const char* field, const std::string& value) {
  if (X509_NAME_add_entry_by_txt(name, field, MBSTRING_UTF8,
                                 reinterpret_cast<const unsigned char*>(value.c_str()), -1, -1,
                                 0) != 1) {
    return InvalidArgumentError(std::string("bad certificate subject ") + field + "=" + value +
                                ": " + TakeOpenSslError());
  }
  return Status::Ok();
}

Status AddExtension(X509* cert, X509* issuer, int nid, const char* value) {
  X509V3_CTX context;
  X509V3_set_ctx_nodb(&context);
  X509V3_set_ctx(&context, issuer, cert, nullptr, nullptr, 0);
  X509_EXTENSION* extension = X509V3_EXT_conf_nid(nullptr, &context, nid, value);
  if (extension == nullptr) {
    return InternalError(std::string("certificate extension ") + value + ": " + TakeOpenSslError());
  }
  const int added = X509_add_ext(cert, extension, -1);
  X509_EXTENSION_free(extension);
  if (added != 1) return InternalError("certificate extension: " + TakeOpenSslError());
  return Status::Ok();
}

// A certificate for `key` with `subject`, valid for `validity`, signed by `issuer_key` (issuer:
// `issuer`, or itself when null).
StatusOr<CertPtr> MakeCertificate(EVP_PKEY* key,
                                  const std::vector<std::pair<const char*, std::string>>& subject,
                                  Validity validity, bool is_ca, X509* issuer,
                                  EVP_PKEY* issuer_key) {
  CertPtr cert(X509_new());
  if (!cert || X509_set_version(cert.get(), 2) != 1) {
    return InternalError("cannot make a certificate: " + TakeOpenSslError());
  }
  FLEETMAP_RETURN_IF_ERROR(SetRandomSerial(cert.get()));
  if (X509_time_adj_ex(X509_getm_notBefore(cert.get()), 0, 0, &validity.not_before) == nullptr ||
      X509_time_adj_ex(X509_getm_notAfter(cert.get()), 0, 0, &validity.not_after) == nullptr) {
    return InternalError("bad certificate validity: " + TakeOpenSslError());
  }
  X509_NAME* name = X509_get_subject_name(cert.get());
  for (const auto& [field, value] : subject) {
    FLEETMAP_RETURN_IF_ERROR(AddEntry(name, field, value));
  }
  X509* signer = issuer != nullptr ? issuer : cert.get();
  if (X509_set_issuer_name(cert.get(), X509_get_subject_name(signer)) != 1 ||
      X509_set_pubkey(cert.get(), key) != 1) {
    return InternalError("cannot make a certificate: " + TakeOpenSslError());
  }
  if (is_ca) {
    FLEETMAP_RETURN_IF_ERROR(
        AddExtension(cert.get(), signer, NID_basic_constraints, "critical,CA:TRUE"));
    FLEETMAP_RETURN_IF_ERROR(AddExtension(cert.get(), signer, NID_key_usage,
                                          "critical,digitalSignature,keyCertSign,cRLSign"));
  } else {
    FLEETMAP_RETURN_IF_ERROR(AddExtension(cert.get(), signer, NID_basic_constraints, "CA:FALSE"));
    FLEETMAP_RETURN_IF_ERROR(
        AddExtension(cert.get(), signer, NID_key_usage, "critical,digitalSignature,keyAgreement"));
  }
  FLEETMAP_RETURN_IF_ERROR(AddExtension(cert.get(), signer, NID_subject_key_identifier, "hash"));
  if (X509_sign(cert.get(), issuer_key, EVP_sha256()) == 0) {
    return InternalError("cannot sign a certificate: " + TakeOpenSslError());
  }
  return cert;
}

std::string PemOf(X509* cert) {
  BioPtr out(BIO_new(BIO_s_mem()));
  PEM_write_bio_X509(out.get(), cert);
  return BioText(out.get());
}

std::string PemOf(EVP_PKEY* key) {
  BioPtr out(BIO_new(BIO_s_mem()));
  PEM_write_bio_PrivateKey(out.get(), key, nullptr, nullptr, 0, nullptr, nullptr);
  return BioText(out.get());
}

}  // namespace

Validity Validity::FromNow(int days) {
  const std::time_t now = std::time(nullptr);
  return Validity{now - 60, now + static_cast<std::time_t>(days) * 86400};
}

CertificateAuthority::CertificateAuthority(std::unique_ptr<Keys> keys) : keys_(std::move(keys)) {}
CertificateAuthority::~CertificateAuthority() = default;

StatusOr<std::unique_ptr<CertificateAuthority>> CertificateAuthority::Create(
    const std::string& common_name, Validity validity) {
  auto keys = std::make_unique<Keys>();
  FLEETMAP_ASSIGN_OR_RETURN(keys->key, NewKey());
  FLEETMAP_ASSIGN_OR_RETURN(
      keys->cert, MakeCertificate(keys->key.get(), {{"O", kOrganization}, {"CN", common_name}},
                                  validity, /*is_ca=*/true, nullptr, keys->key.get()));
  return std::unique_ptr<CertificateAuthority>(new CertificateAuthority(std::move(keys)));
}

StatusOr<std::unique_ptr<CertificateAuthority>> CertificateAuthority::Load(
    const std::string& cert_path, const std::string& key_path) {
  auto keys = std::make_unique<Keys>();
  BioPtr cert_file(BIO_new_file(cert_path.c_str(), "r"));
  if (cert_file) keys->cert.reset(PEM_read_bio_X509(cert_file.get(), nullptr, nullptr, nullptr));
  if (!keys->cert) {
    return InvalidArgumentError(cert_path + ": not a readable PEM certificate (" +
                                TakeOpenSslError() + ")");
  }
  BioPtr key_file(BIO_new_file(key_path.c_str(), "r"));
  if (key_file) {
    keys->key.reset(PEM_read_bio_PrivateKey(key_file.get(), nullptr, nullptr, nullptr));
  }
  if (!keys->key) {
    return InvalidArgumentError(key_path + ": not a readable PEM private key (" +
                                TakeOpenSslError() + ")");
  }
  if (X509_check_private_key(keys->cert.get(), keys->key.get()) != 1) {
    ERR_clear_error();
    return InvalidArgumentError(key_path + ": is not the key of " + cert_path);
  }
  return std::unique_ptr<CertificateAuthority>(new CertificateAuthority(std::move(keys)));
}

std::string CertificateAuthority::cert_pem() const { return PemOf(keys_->cert.get()); }
std::string CertificateAuthority::key_pem() const { return PemOf(keys_->key.get()); }

StatusOr<IssuedIdentity> CertificateAuthority::Issue(const std::string& name,
                                                     const std::string& organizational_unit,
                                                     Validity validity) const {
  FLEETMAP_ASSIGN_OR_RETURN(KeyPtr key, NewKey());
  FLEETMAP_ASSIGN_OR_RETURN(
      CertPtr cert,
      MakeCertificate(key.get(), {{"O", kOrganization}, {"OU", organizational_unit}, {"CN", name}},
                      validity,
                      /*is_ca=*/false, keys_->cert.get(), keys_->key.get()));
  return IssuedIdentity{PemOf(key.get()), PemOf(cert.get()), SerialHex(cert.get()),
                        SubjectRfc2253(cert.get())};
}

StatusOr<std::string> CertificateAuthority::SignDocument(const std::string& text) const {
  constexpr int kFlags = PKCS7_DETACHED | PKCS7_STREAM | PKCS7_TEXT;
  BioPtr content = MemoryBio(text);
  Pkcs7Ptr signature(
      PKCS7_sign(keys_->cert.get(), keys_->key.get(), nullptr, content.get(), kFlags));
  if (!signature) return InternalError("cannot sign a document: " + TakeOpenSslError());
  BioPtr out(BIO_new(BIO_s_mem()));
  if (SMIME_write_PKCS7(out.get(), signature.get(), content.get(), kFlags) != 1) {
    return InternalError("cannot write a signed document: " + TakeOpenSslError());
  }
  return BioText(out.get());
}

StatusOr<std::string> CertificateAuthority::RevocationList(
    const std::vector<std::string>& revoked_serials) const {
  CrlPtr crl(X509_CRL_new());
  const std::time_t now = std::time(nullptr);
  std::unique_ptr<ASN1_TIME, decltype(&ASN1_TIME_free)> last(ASN1_TIME_set(nullptr, now - 60),
                                                             ASN1_TIME_free);
  if (!crl || X509_CRL_set_version(crl.get(), 1) != 1 ||
      X509_CRL_set_issuer_name(crl.get(), X509_get_subject_name(keys_->cert.get())) != 1 ||
      X509_CRL_set1_lastUpdate(crl.get(), last.get()) != 1 ||
      X509_CRL_set1_nextUpdate(crl.get(), X509_get0_notAfter(keys_->cert.get())) != 1) {
    return InternalError("cannot make a revocation list: " + TakeOpenSslError());
  }
  for (const std::string& serial : revoked_serials) {
    BIGNUM* number = nullptr;
    if (BN_hex2bn(&number, serial.c_str()) == 0) {
      return InvalidArgumentError("revocation list: \"" + serial + "\" is not a hex serial");
    }
    std::unique_ptr<BIGNUM, decltype(&BN_free)> owned(number, BN_free);
    std::unique_ptr<ASN1_INTEGER, decltype(&ASN1_INTEGER_free)> asn1(
        BN_to_ASN1_INTEGER(number, nullptr), ASN1_INTEGER_free);
    X509_REVOKED* entry = X509_REVOKED_new();
    if (entry == nullptr || X509_REVOKED_set_serialNumber(entry, asn1.get()) != 1 ||
        X509_REVOKED_set_revocationDate(entry, last.get()) != 1 ||
        X509_CRL_add0_revoked(crl.get(), entry) != 1) {
      X509_REVOKED_free(entry);
      return InternalError("cannot make a revocation list: " + TakeOpenSslError());
    }
  }
  if (X509_CRL_sort(crl.get()) != 1 ||
      X509_CRL_sign(crl.get(), keys_->key.get(), EVP_sha256()) == 0) {
    return InternalError("cannot sign a revocation list: " + TakeOpenSslError());
  }
  BioPtr out(BIO_new(BIO_s_mem()));
  PEM_write_bio_X509_CRL(out.get(), crl.get());
  return BioText(out.get());
}

}  // namespace fleetmap::security
