#include "runtime/participant.h"

#include <gtest/gtest.h>

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

TEST(ParticipantTest, SplitServerListTakesCommasAndSemicolons) {
  EXPECT_EQ(SplitServerList("a:1;b:2, c:3,"), (std::vector<std::string>{"a:1", "b:2", "c:3"}));
  EXPECT_TRUE(SplitServerList("").empty());
}

}  // namespace
}  // namespace stickrep::runtime
