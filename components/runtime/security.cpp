#include "runtime/security.h"

#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "common/input_error.h"

namespace stickrep::runtime {

namespace {

std::string Existing(const std::filesystem::path& path, const std::string& what) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(path.string(), 0, "",
                     "no " + what + " here (make the security directory with "
                     "deploy/security/make-keys.sh DIR)");
  }
  return std::filesystem::absolute(path).lexically_normal().string();
}

}  // namespace

SecurityFiles FindSecurityFiles(const SecurityConfig& c, DiscoveryKind discovery) {
  if (c.identity.empty() || c.identity.find('/') != std::string::npos || c.identity == "." ||
      c.identity == "..") {
    throw InputError("--security-identity", 0, c.identity,
                     "not an identity name of the security directory (e.g. executive)");
  }
  if (!std::filesystem::is_directory(c.dir)) {
    throw InputError(c.dir, 0, "", "no such security directory (make it with "
                                   "deploy/security/make-keys.sh DIR)");
  }
  const std::filesystem::path dir(c.dir);
  const std::filesystem::path id = dir / c.identity;
  if (!std::filesystem::is_directory(id)) {
    throw InputError(id.string(), 0, "", "no identity '" + c.identity +
                                             "' in the security directory");
  }
  return SecurityFiles{Existing(dir / "identity_ca.cert.pem", "identity CA certificate"),
                       Existing(id / "cert.pem", "identity certificate"),
                       Existing(id / "key.pem", "private key"),
                       Existing(dir / "permissions_ca.cert.pem", "permissions CA certificate"),
                       Existing(dir / (discovery == DiscoveryKind::kSimple
                                           ? "governance.p7s"
                                           : "governance_discovery_server.p7s"),
                                "signed governance document"),
                       Existing(id / "permissions.p7s", "signed permissions document")};
}

void ApplySecurity(const SecurityConfig& c, eprosima::fastdds::dds::DomainParticipantQos& qos,
                   DiscoveryKind discovery) {
  const SecurityFiles f = FindSecurityFiles(c, discovery);
  auto& p = qos.properties().properties();
  const auto set = [&p](const std::string& name, const std::string& value) {
    p.emplace_back(name, value);
  };
  const std::string auth = "dds.sec.auth.builtin.PKI-DH.";
  const std::string access = "dds.sec.access.builtin.Access-Permissions.";
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set(auth + "identity_ca", "file://" + f.identity_ca);
  set(auth + "identity_certificate", "file://" + f.certificate);
  set(auth + "private_key", "file://" + f.private_key);
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set(access + "permissions_ca", "file://" + f.permissions_ca);
  set(access + "governance", "file://" + f.governance);
  set(access + "permissions", "file://" + f.permissions);
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

eprosima::fastrtps::rtps::GuidPrefix_t SecuredServerPrefix(
    const SecurityConfig& c, const eprosima::fastrtps::rtps::GuidPrefix_t& candidate) {
  const std::string path =
      Existing(std::filesystem::path(c.dir) / "discovery_server" / "cert.pem",
               "discovery server certificate");
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "r"), &std::fclose);
  std::unique_ptr<X509, void (*)(X509*)> cert(
      file ? PEM_read_X509(file.get(), nullptr, nullptr, nullptr) : nullptr, &X509_free);
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (!cert || !X509_NAME_digest(X509_get_subject_name(cert.get()), EVP_sha256(), md, &length) ||
      length != 32) {
    throw InputError(path, 0, "", "not a PEM certificate whose subject can be hashed");
  }
  eprosima::fastrtps::rtps::GuidPrefix_t adjusted;
  // The first 47 bits: the subject name's SHA-256, behind a leading 1 bit.
  adjusted.value[0] = static_cast<uint8_t>(0x80 | (md[0] >> 1));
  for (int i = 1; i < 6; ++i) {
    adjusted.value[i] = static_cast<uint8_t>((md[i - 1] << 7) | (md[i] >> 1));
  }
  // The last 48 bits: the SHA-256 of the candidate GUID (prefix + the participant's entity id).
  unsigned char key[16];
  for (int i = 0; i < 12; ++i) key[i] = candidate.value[i];
  const unsigned char participant_entity[4] = {0x00, 0x00, 0x01, 0xc1};
  for (int i = 0; i < 4; ++i) key[12 + i] = participant_entity[i];
  if (!EVP_Digest(key, sizeof(key), md, nullptr, EVP_sha256(), nullptr)) {
    throw std::runtime_error("OpenSSL could not hash a GUID");
  }
  for (int i = 0; i < 6; ++i) adjusted.value[6 + i] = md[i];
  return adjusted;
}

}  // namespace stickrep::runtime
