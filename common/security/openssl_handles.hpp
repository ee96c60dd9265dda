#pragma once

// Owning handles for the OpenSSL objects the security module uses, and OpenSSL's error queue as
// text. Private to common/security.

#include <openssl/bio.h>
#include <openssl/evp.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>

#include <memory>
#include <string>

namespace fleetmap::security {

struct OpenSslDeleter {
  void operator()(BIO* p) const { BIO_free_all(p); }
  void operator()(EVP_PKEY* p) const { EVP_PKEY_free(p); }
  void operator()(X509* p) const { X509_free(p); }
  void operator()(X509_CRL* p) const { X509_CRL_free(p); }
  void operator()(X509_STORE* p) const { X509_STORE_free(p); }
  void operator()(X509_STORE_CTX* p) const { X509_STORE_CTX_free(p); }
  void operator()(PKCS7* p) const { PKCS7_free(p); }
  void operator()(X509_REVOKED* p) const { X509_REVOKED_free(p); }
};

using BioPtr = std::unique_ptr<BIO, OpenSslDeleter>;
using KeyPtr = std::unique_ptr<EVP_PKEY, OpenSslDeleter>;
using CertPtr = std::unique_ptr<X509, OpenSslDeleter>;
using CrlPtr = std::unique_ptr<X509_CRL, OpenSslDeleter>;
using StorePtr = std::unique_ptr<X509_STORE, OpenSslDeleter>;
using StoreCtxPtr = std::unique_ptr<X509_STORE_CTX, OpenSslDeleter>;
using Pkcs7Ptr = std::unique_ptr<PKCS7, OpenSslDeleter>;

// The oldest error on OpenSSL's queue of this thread, as text, and clears the queue; "unknown
// OpenSSL error" if it is empty.
std::string TakeOpenSslError();

// A memory BIO holding `text`, and everything written to a memory BIO.
BioPtr MemoryBio(const std::string& text);
std::string BioText(BIO* bio);

// A certificate's serial number in hex, and its subject as RFC 2253 text (the form DDS
// permissions name a subject in, e.g. "CN=robot1,OU=robot,O=fleetmap").
std::string SerialHex(X509* cert);
std::string SubjectRfc2253(X509* cert);

}  // namespace fleetmap::security
