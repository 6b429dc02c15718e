// Checks of the DDS Security files with OpenSSL, the library Fast DDS's own security plugins use.
#include "common/fastdds/security_files.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

namespace slam::dds {
namespace {

template <class T, void (*Free)(T*)>
struct Freer {
  void operator()(T* p) const { Free(p); }
};
using Bio = std::unique_ptr<BIO, Freer<BIO, BIO_free_all>>;
using Certificate = std::unique_ptr<X509, Freer<X509, X509_free>>;
using Key = std::unique_ptr<EVP_PKEY, Freer<EVP_PKEY, EVP_PKEY_free>>;
using Store = std::unique_ptr<X509_STORE, Freer<X509_STORE, X509_STORE_free>>;
using StoreContext = std::unique_ptr<X509_STORE_CTX, Freer<X509_STORE_CTX, X509_STORE_CTX_free>>;
using Pkcs7 = std::unique_ptr<PKCS7, Freer<PKCS7, PKCS7_free>>;

Error problem(const std::string& file, const std::string& what) {
  ERR_clear_error();  // OpenSSL's queue would otherwise carry this failure into the next check
  return Error{file + ": " + what};
}

Result<Bio> open(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return problem(file, "missing");
  if (!std::ifstream(file)) return problem(file, "cannot be read");
  Bio bio(BIO_new_file(file.c_str(), "r"));
  if (!bio) return problem(file, "cannot be read");
  return bio;
}

std::string time_text(const ASN1_TIME* time) {
  Bio out(BIO_new(BIO_s_mem()));
  if (!out || ASN1_TIME_print(out.get(), time) != 1) return "?";
  char* data = nullptr;
  const long n = BIO_get_mem_data(out.get(), &data);
  return std::string(data, static_cast<size_t>(n));
}

// A PEM certificate that is valid now.
Result<Certificate> load_certificate(const std::string& file) {
  auto bio = open(file);
  if (!bio) return bio.error();
  Certificate certificate(PEM_read_bio_X509(bio->get(), nullptr, nullptr, nullptr));
  if (!certificate) return problem(file, "not a PEM certificate");
  if (X509_cmp_current_time(X509_get0_notAfter(certificate.get())) < 0)
    return problem(file, "certificate expired on " + time_text(X509_get0_notAfter(certificate.get())));
  if (X509_cmp_current_time(X509_get0_notBefore(certificate.get())) > 0)
    return problem(file, "certificate not valid before " + time_text(X509_get0_notBefore(certificate.get())));
  return certificate;
}

Status check_signed_by(const std::string& file, X509* certificate, const std::string& ca_file, X509* ca) {
  Store store(X509_STORE_new());
  StoreContext context(X509_STORE_CTX_new());
  if (!store || !context || X509_STORE_add_cert(store.get(), ca) != 1 ||
      X509_STORE_CTX_init(context.get(), store.get(), certificate, nullptr) != 1) {
    return problem(file, "cannot be checked (out of memory)");
  }
  if (X509_verify_cert(context.get()) != 1) {
    const int code = X509_STORE_CTX_get_error(context.get());
    return problem(file, "not signed by " + ca_file + " (" + X509_verify_cert_error_string(code) + ")");
  }
  return Status::ok();
}

Status check_private_key(const std::string& file, X509* certificate, const std::string& certificate_file) {
  auto bio = open(file);
  if (!bio) return bio.error();
  Key key(PEM_read_bio_PrivateKey(bio->get(), nullptr, nullptr, nullptr));
  if (!key) return problem(file, "not a PEM private key (or one with a pass phrase)");
  if (X509_check_private_key(certificate, key.get()) != 1)
    return problem(file, "is not the key of " + certificate_file);
  return Status::ok();
}

// An S/MIME document signed with a certificate the permissions CA vouches for (the CA itself, as
// compose/make-security.sh signs), over this exact content: verified the way the Fast DDS access
// plugin verifies it, signer's certificate purpose included.
Status check_signed_document(const std::string& file, X509* ca, const std::string& ca_file) {
  auto bio = open(file);
  if (!bio) return bio.error();
  BIO* content_raw = nullptr;
  Pkcs7 document(SMIME_read_PKCS7(bio->get(), &content_raw));
  Bio content(content_raw);
  if (!document) return problem(file, "not signed (no S/MIME signature)");
  if (!content) return problem(file, "signature without the signed document (not multipart/signed)");
  Store store(X509_STORE_new());
  if (!store || X509_STORE_add_cert(store.get(), ca) != 1)
    return problem(file, "cannot be checked (out of memory)");
  Bio discard(BIO_new(BIO_s_null()));
  if (PKCS7_verify(document.get(), nullptr, store.get(), content.get(), discard.get(), PKCS7_TEXT) != 1) {
    const char* detail = nullptr;
    int detail_flags = 0;
    const unsigned long reason = ERR_peek_last_error_data(&detail, &detail_flags);
    if (ERR_GET_REASON(reason) == PKCS7_R_CERTIFICATE_VERIFY_ERROR) {
      const bool text = detail != nullptr && (detail_flags & ERR_TXT_STRING) != 0;
      return problem(file,
                     "not signed by " + ca_file + (text ? " (" + std::string(detail) + ")" : std::string()));
    }
    return problem(file, "signature does not match the content (tampered with?)");
  }
  return Status::ok();
}

std::string absolute(const std::string& path) {
  std::error_code ec;
  const auto full = std::filesystem::absolute(path, ec);
  return ec ? path : full.lexically_normal().string();
}

}  // namespace

SecurityFiles SecurityFiles::in(const std::string& dir, const std::string& identity) {
  const std::string root = absolute(dir);
  const std::string base = root + "/identities/" + identity;
  return SecurityFiles{root + "/ca.crt",
                       base + ".crt",
                       base + ".key",
                       root + "/permissions-ca.crt",
                       root + "/governance.p7s",
                       base + ".permissions.p7s"};
}

Result<std::optional<SecurityFiles>> security_from_environment() {
  const char* dir = std::getenv(kSecurityDirVariable);
  const char* identity = std::getenv(kIdentityVariable);
  const bool has_dir = dir != nullptr && *dir != '\0';
  const bool has_identity = identity != nullptr && *identity != '\0';
  if (!has_dir && !has_identity) return std::optional<SecurityFiles>{};
  if (!has_dir)
    return Error{std::string(kIdentityVariable) + " is set but " + kSecurityDirVariable + " is not"};
  if (!has_identity)
    return Error{std::string(kSecurityDirVariable) + " is set but " + kIdentityVariable + " is not"};
  return std::optional<SecurityFiles>{SecurityFiles::in(dir, identity)};
}

Status check_security_files(const SecurityFiles& files) {
  auto identity_ca = load_certificate(files.identity_ca);
  if (!identity_ca) return identity_ca.status();
  auto certificate = load_certificate(files.identity_certificate);
  if (!certificate) return certificate.status();
  if (auto s = check_signed_by(files.identity_certificate, certificate->get(), files.identity_ca,
                               identity_ca->get());
      !s)
    return s;
  if (auto s = check_private_key(files.private_key, certificate->get(), files.identity_certificate); !s)
    return s;
  auto permissions_ca = load_certificate(files.permissions_ca);
  if (!permissions_ca) return permissions_ca.status();
  if (auto s = check_signed_document(files.governance, permissions_ca->get(), files.permissions_ca); !s)
    return s;
  return check_signed_document(files.permissions, permissions_ca->get(), files.permissions_ca);
}

}  // namespace slam::dds
