#include "runtime/security.h"

#include <filesystem>

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

SecurityFiles FindSecurityFiles(const SecurityConfig& c) {
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
                       Existing(dir / "governance.p7s", "signed governance document"),
                       Existing(id / "permissions.p7s", "signed permissions document")};
}

void ApplySecurity(const SecurityConfig& c, eprosima::fastdds::dds::DomainParticipantQos& qos) {
  const SecurityFiles f = FindSecurityFiles(c);
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

}  // namespace stickrep::runtime
