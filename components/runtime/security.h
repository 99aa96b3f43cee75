#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <string>

namespace stickrep::runtime {

// DDS Security for one participant: the directory deploy/security/make-keys.sh wrote and
// the identity in it that this participant is (its certificate, private key and signed
// permissions). An empty directory: no security (plain DDS).
struct SecurityConfig {
  std::string dir;
  std::string identity;
  bool enabled() const { return !dir.empty(); }
};

// The files a secured participant is configured with.
struct SecurityFiles {
  std::string identity_ca;
  std::string certificate;
  std::string private_key;
  std::string permissions_ca;
  std::string governance;
  std::string permissions;
};

// Where the files of `config` are; throws InputError naming the first one that is missing
// (or an identity name that is empty or not a plain name).
SecurityFiles FindSecurityFiles(const SecurityConfig& config);

// Turns on Fast DDS's built-in plugins (PKI-DH authentication, Access-Permissions access
// control, AES-GCM-GMAC crypto) in a participant's QoS with the files of `config`. Throws
// InputError as FindSecurityFiles does.
void ApplySecurity(const SecurityConfig& config,
                   eprosima::fastdds::dds::DomainParticipantQos& qos);

}  // namespace stickrep::runtime
