// check_security_files() on the files compose/make-security.sh makes, and on bad copies of them: each
// bad file is refused with its own path and what is wrong with it. The files are made once per suite
// (two independent sets: the second has another CA); each test spoils a copy.
#include "common/fastdds/security_files.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "temp_dir.hpp"

namespace slam::dds {
namespace {

namespace fs = std::filesystem;
using testkit::TempDir;

// Runs a shell command line; true when it exits 0 (its output goes to the test log).
bool shell(const std::string& command) {
  return std::system(("set -e; " + command).c_str()) == 0;
}

std::string make_security(const fs::path& dir) {
  return "bash " SLAM_SOURCE_DIR "/compose/make-security.sh '" + dir.string() + "' >/dev/null";
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class CheckSecurityFiles : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    made_ = std::make_unique<TempDir>("security-files");
    ASSERT_TRUE(shell(make_security(*made_ / "good")));
    ASSERT_TRUE(shell(make_security(*made_ / "other")));
  }
  static void TearDownTestSuite() { made_.reset(); }

  void SetUp() override {
    fs::copy(*made_ / "good", dir_.path() / "good", fs::copy_options::recursive);
    files_ = SecurityFiles::in((dir_.path() / "good").string(), "gateway");
  }

  fs::path good(const std::string& name) const { return dir_.path() / "good" / name; }
  static fs::path other(const std::string& name) { return *made_ / "other" / name; }

  // The check fails, naming `file` and saying `problem`.
  void expect_refused(const fs::path& file, const std::string& problem) const {
    const Status s = check_security_files(files_);
    ASSERT_FALSE(s) << "accepted, expected: " << file << ": " << problem;
    EXPECT_EQ(s.message().rfind(file.string() + ": ", 0), 0u) << s.message();
    EXPECT_NE(s.message().find(problem), std::string::npos) << s.message();
    EXPECT_EQ(s.message().find('\n'), std::string::npos) << "not one line: " << s.message();
  }

  static std::unique_ptr<TempDir> made_;
  TempDir dir_{"security-case"};
  SecurityFiles files_;
};

std::unique_ptr<TempDir> CheckSecurityFiles::made_;

TEST_F(CheckSecurityFiles, WhatTheScriptMakesPassesForEveryIdentity) {
  for (const char* identity : {"gateway", "mapper", "planner", "viewer", "slamctl", "bridge"}) {
    const Status s = check_security_files(SecurityFiles::in((dir_.path() / "good").string(), identity));
    EXPECT_TRUE(s) << identity << ": " << s.message();
  }
}

TEST_F(CheckSecurityFiles, LayoutIsTheScriptsWithAbsolutePaths) {
  EXPECT_EQ(files_.identity_certificate, good("identities/gateway.crt").string());
  EXPECT_EQ(files_.permissions, good("identities/gateway.permissions.p7s").string());
  EXPECT_EQ(files_.governance, good("governance.p7s").string());
  EXPECT_TRUE(fs::path(SecurityFiles::in("relative/dir", "x").identity_ca).is_absolute());
}

TEST_F(CheckSecurityFiles, MissingCertificateIsRefused) {
  fs::remove(good("identities/gateway.crt"));
  expect_refused(good("identities/gateway.crt"), "missing");
}

TEST_F(CheckSecurityFiles, MissingGovernanceIsRefused) {
  fs::remove(good("governance.p7s"));
  expect_refused(good("governance.p7s"), "missing");
}

TEST_F(CheckSecurityFiles, GarbageInsteadOfACertificateIsRefused) {
  std::ofstream(good("ca.crt")) << "not a certificate\n";
  expect_refused(good("ca.crt"), "not a PEM certificate");
}

TEST_F(CheckSecurityFiles, ExpiredCertificateIsRefused) {
  // The same key and name, signed by the right CA, valid until yesterday.
  const fs::path d = dir_.path() / "good";
  ASSERT_TRUE(
      shell("cd '" + d.string() +
            "' && openssl req -new -key identities/gateway.key -subj /CN=gateway -out g.csr 2>/dev/null"
            " && openssl x509 -req -in g.csr -CA ca.crt -CAkey ca.key -days -1"
            " -out identities/gateway.crt 2>/dev/null"));
  expect_refused(good("identities/gateway.crt"), "certificate expired on ");
}

TEST_F(CheckSecurityFiles, CertificateOfAnotherCaIsRefused) {
  fs::copy_file(other("identities/gateway.crt"), good("identities/gateway.crt"),
                fs::copy_options::overwrite_existing);
  fs::copy_file(other("identities/gateway.key"), good("identities/gateway.key"),
                fs::copy_options::overwrite_existing);
  expect_refused(good("identities/gateway.crt"), "not signed by " + good("ca.crt").string());
}

TEST_F(CheckSecurityFiles, KeyOfAnotherIdentityIsRefused) {
  fs::copy_file(good("identities/mapper.key"), good("identities/gateway.key"),
                fs::copy_options::overwrite_existing);
  expect_refused(good("identities/gateway.key"),
                 "is not the key of " + good("identities/gateway.crt").string());
}

TEST_F(CheckSecurityFiles, UnsignedPermissionsAreRefused) {
  fs::copy_file(good("identities/gateway.permissions.xml"), good("identities/gateway.permissions.p7s"),
                fs::copy_options::overwrite_existing);
  expect_refused(good("identities/gateway.permissions.p7s"), "not signed");
}

TEST_F(CheckSecurityFiles, TamperedPermissionsAreRefused) {
  // The gateway grants itself the goal topic: same length, so only the signature can tell.
  std::string text = read(good("identities/gateway.permissions.p7s"));
  const std::string granted = "<topic>slam/nav/waypoint</topic>";
  const size_t at = text.find(granted);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, granted.size(), "<topic>slam/nav/goal*****</topic>");
  std::ofstream(good("identities/gateway.permissions.p7s")) << text;
  expect_refused(good("identities/gateway.permissions.p7s"), "tampered");
}

TEST_F(CheckSecurityFiles, PermissionsSignedByAnotherCaAreRefused) {
  fs::copy_file(other("identities/gateway.permissions.p7s"), good("identities/gateway.permissions.p7s"),
                fs::copy_options::overwrite_existing);
  expect_refused(good("identities/gateway.permissions.p7s"),
                 "not signed by " + good("permissions-ca.crt").string());
}

TEST_F(CheckSecurityFiles, PermissionsCaThatMayNotSignDocumentsIsRefused) {
  // A permissions CA without digitalSignature: Fast DDS's S/MIME check refuses what it signs.
  const fs::path d = dir_.path() / "good";
  ASSERT_TRUE(
      shell("cd '" + d.string() +
            "' && openssl req -x509 -new -key permissions-ca.key -subj '/CN=slamfleet permissions CA'"
            " -days 1 -addext basicConstraints=critical,CA:TRUE -addext keyUsage=critical,keyCertSign"
            " -out permissions-ca.crt 2>/dev/null"
            " && openssl smime -sign -text -in governance.xml -out governance.p7s -signer permissions-ca.crt"
            " -inkey permissions-ca.key"));
  expect_refused(good("governance.p7s"), "unsuitable certificate purpose");
}

TEST_F(CheckSecurityFiles, GovernanceSignedByAnotherCaIsRefused) {
  fs::copy_file(other("governance.p7s"), good("governance.p7s"), fs::copy_options::overwrite_existing);
  expect_refused(good("governance.p7s"), "not signed by ");
}

class SecurityEnvironment : public ::testing::Test {
 protected:
  void TearDown() override {
    ::unsetenv(kSecurityDirVariable);
    ::unsetenv(kIdentityVariable);
  }
};

TEST_F(SecurityEnvironment, NothingSetMeansNoSecurity) {
  auto security = security_from_environment();
  ASSERT_TRUE(security) << security.message();
  EXPECT_FALSE(security->has_value());
}

TEST_F(SecurityEnvironment, BothSetNameTheIdentitysFiles) {
  ::setenv(kSecurityDirVariable, "/data/security", 1);
  ::setenv(kIdentityVariable, "planner", 1);
  auto security = security_from_environment();
  ASSERT_TRUE(security) << security.message();
  ASSERT_TRUE(security->has_value());
  EXPECT_EQ((*security)->identity_certificate, "/data/security/identities/planner.crt");
}

TEST_F(SecurityEnvironment, OneWithoutTheOtherIsAnError) {
  ::setenv(kSecurityDirVariable, "/data/security", 1);
  auto security = security_from_environment();
  ASSERT_FALSE(security);
  EXPECT_NE(security.message().find(kIdentityVariable), std::string::npos);
}

}  // namespace
}  // namespace slam::dds
