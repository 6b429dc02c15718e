#pragma once
// The DDS Security files of one participant (made by compose/make-security.sh, docs/security.md), and
// the check a service runs on them before it joins a secure domain: a bad file stops it at start
// with one line naming the file and the problem, instead of a participant that silently matches no one.
#include <optional>
#include <string>

#include "common/core/result.hpp"

namespace slam::dds {

// Environment of every Fast DDS program: the folder of compose/make-security.sh and the identity
// (a certificate and its permissions in DIR/identities) the process joins the domain as.
inline constexpr const char* kSecurityDirVariable = "SLAM_DDS_SECURITY_DIR";
inline constexpr const char* kIdentityVariable = "SLAM_DDS_IDENTITY";

struct SecurityFiles {
  std::string identity_ca;           // PEM: the CA that signs every identity
  std::string identity_certificate;  // PEM: this participant's certificate
  std::string private_key;           // PEM: its key
  std::string permissions_ca;        // PEM: the CA that signs governance and permissions
  std::string governance;            // S/MIME signed governance XML
  std::string permissions;           // S/MIME signed permissions XML of this identity

  // The files of `identity` in the folder layout of compose/make-security.sh (absolute paths).
  static SecurityFiles in(const std::string& dir, const std::string& identity);
};

// From SLAM_DDS_SECURITY_DIR and SLAM_DDS_IDENTITY: nullopt when the folder is not set (no security);
// an error when only one of the two is.
Result<std::optional<SecurityFiles>> security_from_environment();

// Ok, or "FILE: PROBLEM" for the first bad file: missing or unreadable, not PEM or S/MIME, a
// certificate expired or not valid yet, not signed by its CA, a key that does not belong to the
// certificate, a document unsigned, tampered with or signed by another CA.
Status check_security_files(const SecurityFiles& files);

}  // namespace slam::dds
