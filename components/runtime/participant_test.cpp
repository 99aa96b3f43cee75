#include "runtime/participant.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include "basePubSubTypes.h"
#include "common/input_error.h"
#include "runtime/deployment_options.h"
#include "runtime/system_config.h"
#include "runtime/test_domain.h"

namespace stickrep::runtime {
namespace {

const std::string kClientXml =
    std::string(STICKREP_SOURCE_DIR) + "/deploy/fastdds/discovery_client.xml";

QosCatalog Catalog() { return QosCatalog::LoadFile(DefaultConfigDir() + "/qos.yaml"); }

TEST(ParticipantTest, AProfileFileWithoutANameUsesItsDefaultProfile) {
  EXPECT_EQ(CheckProfileXml(kClientXml), "stickrep_client");
  Participant p(ParticipantConfig{TestDomainId(), "test", kClientXml, "", {}}, Catalog());
  EXPECT_TRUE(p.discovery().UsesServers());
  EXPECT_EQ(p.servers_text(), "127.0.0.1:11811");
}

TEST(ParticipantTest, ServersOnTheCommandLineReplaceTheProfilesAndMakeAClient) {
  Participant p(ParticipantConfig{TestDomainId(), "test", "", "",
                                  SplitServerList("10.1.0.1:11811, 10.1.0.2:11812")},
                Catalog());
  EXPECT_TRUE(p.discovery().UsesServers());
  EXPECT_EQ(p.servers_text(), "10.1.0.1:11811,10.1.0.2:11812");
  EXPECT_EQ(p.discovery().ServersReached(), 0);
}

TEST(ParticipantTest, WithoutProfileOrServersDiscoveryIsSimple) {
  Participant p(ParticipantConfig{TestDomainId(), "test", "", "", {}}, Catalog());
  EXPECT_FALSE(p.discovery().UsesServers());
  EXPECT_EQ(p.servers_text(), "");
}

bool HasTransport(Participant& p, bool shared_memory) {
  const auto& t = p.dds()->get_qos().transport();
  return std::any_of(t.user_transports.begin(), t.user_transports.end(), [&](const auto& d) {
    return shared_memory
               ? std::dynamic_pointer_cast<eprosima::fastdds::rtps::SharedMemTransportDescriptor>(
                     d) != nullptr
               : std::dynamic_pointer_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor>(
                     d) != nullptr;
  });
}

TEST(ParticipantTest, ByDefaultProcessesTalkOverUdpOnly) {
  Participant p(ParticipantConfig{TestDomainId(), "test", "", "", {}}, Catalog());
  EXPECT_FALSE(p.dds()->get_qos().transport().use_builtin_transports);
  EXPECT_TRUE(HasTransport(p, /*shared_memory=*/false));
  EXPECT_FALSE(HasTransport(p, /*shared_memory=*/true));
}

TEST(ParticipantTest, SharedMemoryAskedForIsUsedAlsoBesideAProfilesOwnTransports) {
  ParticipantConfig plain{TestDomainId(), "test", "", "", {}};
  plain.shared_memory = true;
  Participant builtin(plain, Catalog());
  EXPECT_TRUE(builtin.dds()->get_qos().transport().use_builtin_transports);

  ParticipantConfig profiled{TestDomainId(), "test", kClientXml, "", {}};
  Participant udp_only(profiled, Catalog());
  EXPECT_FALSE(HasTransport(udp_only, /*shared_memory=*/true));
  profiled.shared_memory = true;
  Participant both(profiled, Catalog());
  EXPECT_TRUE(HasTransport(both, /*shared_memory=*/true));
  EXPECT_TRUE(HasTransport(both, /*shared_memory=*/false));
}

// Data sharing (shared-memory delivery between the endpoints of one host) goes with shared
// memory: robot/odometry is a plain type, for which Fast DDS would use it by default.
TEST(ParticipantTest, DataSharingIsOffUnlessSharedMemoryIsAskedFor) {
  // The participant owns each type support handed to it.
  const auto odometry = [] { return new msgs::OdometryPubSubType(); };
  ParticipantConfig config{TestDomainId(), "test", "", "", {}};
  Participant udp_only(config, Catalog());
  auto* writer = udp_only.CreateDataWriter("robot/odometry", odometry(), nullptr);
  auto* reader = udp_only.CreateDataReader("robot/odometry", odometry(), nullptr);
  EXPECT_EQ(writer->get_qos().data_sharing().kind(), eprosima::fastdds::dds::OFF);
  EXPECT_EQ(reader->get_qos().data_sharing().kind(), eprosima::fastdds::dds::OFF);
  config.shared_memory = true;
  Participant shared(config, Catalog());
  EXPECT_EQ(shared.CreateDataWriter("robot/odometry", odometry(), nullptr)
                ->get_qos()
                .data_sharing()
                .kind(),
            eprosima::fastdds::dds::AUTO);
}

TEST(ParticipantTest, TheSystemFileDecidesSharedMemory) {
  SystemConfig system;
  EXPECT_FALSE(MakeParticipantConfig(system, {}, "stickrep-sonar").shared_memory);
  system.shared_memory = true;
  EXPECT_TRUE(MakeParticipantConfig(system, {}, "stickrep-sonar").shared_memory);
}

// Security material made once for these tests by the shipped script.
std::string Keys() {
  static const std::string dir = [] {
    const std::string d = ::testing::TempDir() + "/stickrep_keys_" + std::to_string(getpid());
    const std::string command = "bash " + std::string(STICKREP_SOURCE_DIR) +
                                "/deploy/security/make-keys.sh " + d + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return d;
  }();
  return dir;
}

TEST(ParticipantTest, ASecuredDiscoveryServersPrefixIsTheOneItsCertificateGivesIt) {
  // What fast-discovery-server -i 0 -x DIR/discovery_server.xml prints as its prefix: it
  // depends only on the certificate's subject and the prefix of server id 0.
  eprosima::fastrtps::rtps::GuidPrefix_t id0;
  std::istringstream("44.53.00.5f.45.50.52.4f.53.49.4d.41") >> id0;
  std::ostringstream text;
  text << SecuredServerPrefix(SecurityConfig{Keys(), "sonar"}, id0);
  EXPECT_EQ(text.str(), "90.2e.c0.55.1d.0f.25.ff.38.7f.fc.76");
}

TEST(ParticipantTest, ASecuredParticipantAuthenticatesWithItsIdentity) {
  ParticipantConfig c{TestDomainId(), "stickrep-sonar", "", "", {}};
  c.security = SecurityConfig{Keys(), "sonar"};
  EXPECT_NO_THROW(Participant(c, Catalog()));
}

TEST(ParticipantTest, AMissingSecurityFileIsBadInputNamingIt) {
  ParticipantConfig c{TestDomainId(), "stickrep-sonar", "", "", {}};
  c.security = SecurityConfig{Keys(), "wheel"};
  try {
    Participant p(c, Catalog());
    FAIL() << "an identity that is not there was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no identity 'wheel'"), std::string::npos) << e.what();
  }
  c.security = SecurityConfig{Keys() + "/nowhere", "sonar"};
  EXPECT_THROW(Participant(c, Catalog()), InputError);
}

TEST(ParticipantTest, SecuredAProcessIsTheIdentityOfItsName) {
  DeploymentOptions o;
  o.security_dir = "/keys";
  SystemConfig system;
  EXPECT_EQ(MakeParticipantConfig(system, o, "stickrep-executive").security.identity, "executive");
  o.security_identity = "console";
  EXPECT_EQ(MakeParticipantConfig(system, o, "stickrep-record").security.identity, "console");
  EXPECT_FALSE(MakeParticipantConfig(system, DeploymentOptions{}, "x").security.enabled());
}

TEST(ParticipantTest, SplitServerListTakesCommasAndSemicolons) {
  EXPECT_EQ(SplitServerList("a:1;b:2, c:3,"), (std::vector<std::string>{"a:1", "b:2", "c:3"}));
  EXPECT_TRUE(SplitServerList("").empty());
}

}  // namespace
}  // namespace stickrep::runtime
