#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>

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

// How the participant discovers the others: the governance differs (make-keys.sh), since
// Fast DDS 2.9's discovery server cannot relay encrypted endpoint discovery and liveliness.
enum class DiscoveryKind { kSimple, kDiscoveryServer };

// Where the files of `config` are; throws InputError naming the first one that is missing
// (or an identity name that is empty or not a plain name).
SecurityFiles FindSecurityFiles(const SecurityConfig& config,
                                DiscoveryKind discovery = DiscoveryKind::kSimple);

// Turns on Fast DDS's built-in plugins (PKI-DH authentication, Access-Permissions access
// control, AES-GCM-GMAC crypto) in a participant's QoS with the files of `config`. Throws
// InputError as FindSecurityFiles does.
void ApplySecurity(const SecurityConfig& config,
                   eprosima::fastdds::dds::DomainParticipantQos& qos,
                   DiscoveryKind discovery = DiscoveryKind::kSimple);

// The GUID prefix a secured discovery server really has. DDS Security derives every secured
// participant's GUID prefix from its certificate's subject name and the prefix it was
// configured with (Fast DDS's PKI-DH adjust_participant_key), so a client must expect the
// server `fast-discovery-server -i N -x DIR/discovery_server.xml` at this prefix instead of
// the configured `candidate`. Reads DIR/discovery_server/cert.pem; throws InputError.
eprosima::fastrtps::rtps::GuidPrefix_t SecuredServerPrefix(
    const SecurityConfig& config, const eprosima::fastrtps::rtps::GuidPrefix_t& candidate);

}  // namespace stickrep::runtime
