#include "runtime/qos_catalog.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "runtime/system_config.h"

namespace stickrep::runtime {
namespace {

using ::testing::HasSubstr;

const char* kProfiles = R"(qos:
  profiles:
    sensor:
      reliability: best_effort
      durability: volatile
      history_depth: 5
      deadline_s: 0
      liveliness_lease_s: 0
      publish_mode: synchronous
  streams:
)";

TEST(QosCatalogTest, ShippedCatalogHasAChoiceForEveryStream) {
  const QosCatalog c = QosCatalog::LoadFile(DefaultConfigDir() + "/qos.yaml");
  for (const char* topic :
       {"device/sonar/echo", "device/camera/frame", "device/base/encoders",
        "device/base/wheel_command", "robot/sonar", "robot/camera/image", "robot/odometry",
        "robot/motion/command", "perception/landmark", "localization/pose",
        "localization/hypotheses", "map/stickrep", "mission/goal", "mission/status",
        "system/status", "sim/ground_truth"}) {
    EXPECT_TRUE(c.HasTopic(topic)) << topic;
  }
  EXPECT_EQ(c.ForTopic("robot/camera/image").history_depth, 1);
  EXPECT_EQ(c.ForTopic("localization/pose").durability, QosProfile::Durability::kTransientLocal);
  EXPECT_GT(c.ForTopic("robot/motion/command").deadline_s, 0.0);
  EXPECT_GT(c.ForTopic("system/status").liveliness_lease_s, 0.0);
}

TEST(QosCatalogTest, UnknownProfileNameIsRejectedWithItsLine) {
  const std::string text = std::string(kProfiles) +
                           "    - topic: robot/sonar\n"
                           "      profile: sensr\n"
                           "      reason: newest scan supersedes the rest\n";
  try {
    QosCatalog::Load(StrictYaml::LoadString(text, "qos.yaml"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 12);
    EXPECT_THAT(e.what(), HasSubstr("no QoS profile named 'sensr'"));
  }
}

TEST(QosCatalogTest, StreamWithoutAReasonIsRejected) {
  const std::string text = std::string(kProfiles) +
                           "    - topic: robot/sonar\n"
                           "      profile: sensor\n"
                           "      reason: x\n";
  EXPECT_THROW(QosCatalog::Load(StrictYaml::LoadString(text, "qos.yaml")), InputError);
}

TEST(QosCatalogTest, TopicListedTwiceIsRejected) {
  const std::string entry =
      "    - topic: robot/sonar\n      profile: sensor\n      reason: newest scan supersedes\n";
  EXPECT_THROW(QosCatalog::Load(StrictYaml::LoadString(kProfiles + entry + entry, "q.yaml")),
               InputError);
}

TEST(QosCatalogTest, BadReliabilityValueNamesTheChoices) {
  std::string text = kProfiles;
  text.replace(text.find("best_effort"), 11, "sometimes");
  try {
    QosCatalog::Load(StrictYaml::LoadString(text, "qos.yaml"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_THAT(e.what(), HasSubstr("best_effort, reliable"));
  }
}

TEST(QosCatalogTest, TopicWithoutAChoiceIsAnError) {
  const QosCatalog c = QosCatalog::Load(StrictYaml::LoadString(kProfiles + std::string("    []\n"),
                                                               "qos.yaml"));
  EXPECT_THROW(c.ForTopic("robot/nowhere"), InputError);
}

TEST(SystemConfigTest, ShippedSystemFileResolvesPathsNextToIt) {
  const SystemConfig s = SystemConfig::LoadFile(DefaultConfigDir() + "/system.yaml");
  EXPECT_EQ(s.qos_file, DefaultConfigDir() + "/qos.yaml");
  EXPECT_THAT(s.map_file, HasSubstr("maps/engineering_building_3f.yaml"));
}

TEST(SystemConfigTest, SharedMemoryIsOffUnlessTheFileTurnsItOn) {
  const std::string base =
      "system:\n  domain_id: 1\n  qos_file: q.yaml\n  robot_file: r.yaml\n  map_file: m.yaml\n";
  EXPECT_FALSE(SystemConfig::Load(StrictYaml::LoadString(base, "system.yaml")).shared_memory);
  EXPECT_FALSE(SystemConfig::LoadFile(DefaultConfigDir() + "/system.yaml").shared_memory);
  EXPECT_TRUE(SystemConfig::Load(StrictYaml::LoadString(base + "  shared_memory: true\n",
                                                        "system.yaml"))
                  .shared_memory);
  try {
    SystemConfig::Load(StrictYaml::LoadString(base + "  shared_memory: sometimes\n", "system.yaml"));
    FAIL() << "a value that is not a boolean was taken";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("shared_memory"));
  }
}

TEST(SystemConfigTest, DomainIdOutOfRangeIsRejected) {
  const char* text =
      "system:\n  domain_id: 300\n  qos_file: q.yaml\n  robot_file: r.yaml\n  map_file: m.yaml\n";
  EXPECT_THROW(SystemConfig::Load(StrictYaml::LoadString(text, "system.yaml")), InputError);
}

}  // namespace
}  // namespace stickrep::runtime
