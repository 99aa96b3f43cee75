#include "console/message_json.h"

#include <fastdds/rtps/common/SerializedPayload.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "console/message_types.h"
#include "runtime/qos_catalog.h"
#include "runtime/system_config.h"

namespace stickrep::console {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

// Samples per type: enough for every enum member to take every value of its enum.
constexpr int kSamples = 8;

// JSON forms of samples built from the generated description alone: every member of sample 0
// differs from its default (booleans true, numbers nonzero, strings and sequences non-empty,
// enums not the first enumerator) and numbers and strings differ from member to member.
// Sequences have 2 or 3 elements, strings quotes, a backslash and non-ASCII characters, 64-bit
// integers values a double cannot hold. Enumerators cycle per enum, so that kSamples samples of
// a type give each enum member every value.
class SampleMaker {
 public:
  explicit SampleMaker(std::map<std::string, std::set<std::string>>* enumerators_used = nullptr)
      : enumerators_used_(enumerators_used) {}

  json Sample(const idl::Struct& s, int k) {
    k_ = k;
    return Struct(s);
  }

 private:
  json Struct(const idl::Struct& s) {
    json j = json::object();
    for (const idl::Member& m : s.members) j[m.name] = Value(m.type);
    return j;
  }

  json Value(const idl::Type& t) {
    const std::uint64_t c = ++count_ * 10 + k_;
    switch (t.kind) {
      case idl::Kind::kBoolean:
        return k_ == 0 || c % 2 == 0;
      case idl::Kind::kOctet:
        return c % 255 + 1;
      case idl::Kind::kChar:
        return std::string(1, static_cast<char>('A' + c % 26));
      case idl::Kind::kShort:
        return -static_cast<std::int64_t>(c % 30000 + 1);
      case idl::Kind::kUnsignedShort:
        return 65535 - c % 60000;
      case idl::Kind::kLong:
        return -static_cast<std::int64_t>(c * 1009 + 1);
      case idl::Kind::kUnsignedLong:
        return 4294967295u - c;
      case idl::Kind::kLongLong:
        return std::numeric_limits<std::int64_t>::min() + 1 + static_cast<std::int64_t>(c) * 3;
      case idl::Kind::kUnsignedLongLong:
        return std::numeric_limits<std::uint64_t>::max() - c * 3;
      case idl::Kind::kFloat:
        return static_cast<double>(static_cast<float>(c) * 0.1f + 0.05f);
      case idl::Kind::kDouble:
        return -1.0 / 3.0 - static_cast<double>(c) * 0.1;
      case idl::Kind::kString:
        return "say \"" + std::to_string(c) + "\" \\ na\u00efve \u2713 \U0001F916";
      case idl::Kind::kEnum: {
        const idl::Enum* e = idl::FindEnum(t.name);
        const std::size_t n = e->enumerators.size();
        const std::string& name = e->enumerators[(1 + next_enumerator_[t.name]++) % n];
        if (enumerators_used_ != nullptr) (*enumerators_used_)[t.name].insert(name);
        return name;
      }
      case idl::Kind::kStruct:
        return Struct(*idl::FindStruct(t.name));
      case idl::Kind::kSequence: {
        if (t.element->kind == idl::Kind::kOctet) {
          std::vector<std::uint8_t> bytes(2 + c % 4);  // every base64 padding
          for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = 255 - (c + i) % 255;
          return idl::Base64Encode(bytes);
        }
        std::size_t n = 2 + c % 2;
        if (t.bound != 0 && n > t.bound) n = t.bound;
        json a = json::array();
        for (std::size_t i = 0; i < n; ++i) a.push_back(Value(*t.element));
        return a;
      }
      case idl::Kind::kArray: {
        json a = json::array();
        for (std::uint32_t i = 0; i < t.bound; ++i) a.push_back(Value(*t.element));
        return a;
      }
    }
    return nullptr;
  }

  std::map<std::string, std::set<std::string>>* enumerators_used_;
  std::map<std::string, std::size_t> next_enumerator_;
  std::uint64_t count_ = 0;
  int k_ = 0;
};

// The JSON form of a default-constructed value of the type.
json DefaultValue(const idl::Type& t) {
  switch (t.kind) {
    case idl::Kind::kBoolean:
      return false;
    case idl::Kind::kChar:
      return std::string(1, '\0');
    case idl::Kind::kFloat:
    case idl::Kind::kDouble:
      return 0.0;
    case idl::Kind::kString:
      return "";
    case idl::Kind::kEnum:
      return idl::FindEnum(t.name)->enumerators.front();
    case idl::Kind::kStruct: {
      json j = json::object();
      for (const idl::Member& m : idl::FindStruct(t.name)->members) {
        j[m.name] = DefaultValue(m.type);
      }
      return j;
    }
    case idl::Kind::kSequence:
      return t.element->kind == idl::Kind::kOctet ? json("") : json::array();
    case idl::Kind::kArray:
      return json(std::vector<json>(t.bound, DefaultValue(*t.element)));
    default:
      return 0;
  }
}

// The CDR payload of a sample, serialized by its type's own support class.
std::vector<std::uint8_t> Serialize(const MessageType& type, void* sample) {
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support(type.make_support());
  eprosima::fastrtps::rtps::SerializedPayload_t payload(
      support->getSerializedSizeProvider(sample)());
  EXPECT_TRUE(support->serialize(sample, &payload));
  return std::vector<std::uint8_t>(payload.data, payload.data + payload.length);
}

template <typename T>
void CheckRoundTrips(const idl::Struct& d, const json& form, int k) {
  SCOPED_TRACE(d.name + " sample " + std::to_string(k) + ": " + form.dump());
  T sample;
  try {
    sample = form.get<T>();
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  // Every member was read into the sample and written back.
  EXPECT_EQ(json(sample), form);
  EXPECT_TRUE(json::parse(json(sample).dump()).get<T>() == sample);
  if (k == 0) {
    EXPECT_FALSE(sample == T());
    // Each member reaches the sample and its operator==: setting one back to its default
    // makes another sample.
    for (const idl::Member& m : d.members) {
      json changed = form;
      changed[m.name] = DefaultValue(m.type);
      EXPECT_FALSE(changed.get<T>() == sample) << "member " << m.name;
    }
  }
  // Through CDR: serialized by the type's support class, decoded by the console's table.
  if (const MessageType* type = FindMessageType(d.name)) {
    const std::vector<std::uint8_t> cdr = Serialize(*type, &sample);
    json decoded;
    try {
      decoded = type->decode_json(cdr.data(), cdr.size());
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
    EXPECT_EQ(decoded, form);
    EXPECT_TRUE(decoded.get<T>() == sample);
  }
}

class RoundTripTest : public ::testing::TestWithParam<std::string> {};

// Every struct of the IDL, those the topics carry and those nested in them.
TEST_P(RoundTripTest, JsonAndCdrGiveTheSampleBack) {
  bool found = false;
  idl::ForEachStruct([&](auto tag, const idl::Struct& d) {
    using T = typename decltype(tag)::type;
    if (d.name != GetParam()) return;
    found = true;
    SampleMaker maker;
    for (int k = 0; k < kSamples; ++k) CheckRoundTrips<T>(d, maker.Sample(d, k), k);
  });
  EXPECT_TRUE(found);
}

std::vector<std::string> StructNames() {
  std::vector<std::string> names;
  for (const idl::Struct& s : idl::Structs()) names.push_back(s.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryIdlStruct, RoundTripTest, ::testing::ValuesIn(StructNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(info.param.rfind(':') + 1);
                         });

TEST(MessageJsonTest, TheSamplesGiveEveryEnumMemberEveryValue) {
  std::map<std::string, std::set<std::string>> used;
  for (const idl::Struct& s : idl::Structs()) {
    SampleMaker maker(&used);
    for (int k = 0; k < kSamples; ++k) maker.Sample(s, k);
  }
  ASSERT_FALSE(idl::Enums().empty());
  for (const idl::Enum& e : idl::Enums()) {
    EXPECT_EQ(used[e.name], std::set<std::string>(e.enumerators.begin(), e.enumerators.end()))
        << e.name;
    EXPECT_LE(e.enumerators.size(), static_cast<std::size_t>(kSamples)) << e.name;
  }
}

TEST(MessageJsonTest, TheTopicsCarryExactlyTheIdlsOutermostStructs) {
  // The structs no other struct contains.
  std::set<std::string> outermost;
  for (const idl::Struct& s : idl::Structs()) outermost.insert(s.name);
  for (const idl::Struct& s : idl::Structs()) {
    for (const idl::Member& m : s.members) {
      for (const idl::Type* t = &m.type; t != nullptr; t = t->element.get()) {
        if (t->kind == idl::Kind::kStruct) outermost.erase(t->name);
      }
    }
  }
  const auto catalog = runtime::QosCatalog::LoadFile(runtime::DefaultConfigDir() + "/qos.yaml");
  std::set<std::string> carried;
  for (const auto& [topic, stream] : catalog.streams()) {
    const MessageType* type = TypeOfTopic(topic);
    ASSERT_NE(type, nullptr) << topic << " in qos.yaml carries no type the console knows";
    carried.insert(type->name);
  }
  EXPECT_EQ(carried, outermost);
  std::set<std::string> table;
  for (const auto& [name, type] : MessageTypes()) {
    table.insert(name);
    EXPECT_NE(idl::FindStruct(name), nullptr) << name;
    for (const std::string& topic : type.topics) EXPECT_TRUE(catalog.HasTopic(topic)) << topic;
  }
  EXPECT_EQ(table, carried);
}

TEST(MessageJsonTest, TheDescriptionGivesEachMemberItsIdlType) {
  const idl::Struct* scan = idl::FindStruct("stickrep::msgs::SonarScan");
  ASSERT_NE(scan, nullptr);
  EXPECT_EQ(scan->file, "sensors.idl");
  std::vector<std::string> members;
  for (const idl::Member& m : scan->members) members.push_back(m.name + ": " + m.type.idl);
  EXPECT_THAT(members,
              ::testing::ElementsAre("header: stickrep::msgs::SampleHeader", "range_in: float[24]",
                                     "reading_state: stickrep::msgs::SonarReadingState[24]",
                                     "valid_count: unsigned short"));
  const idl::Struct* hypotheses = idl::FindStruct("stickrep::msgs::PoseHypotheses");
  ASSERT_NE(hypotheses, nullptr);
  const idl::Type& seq = hypotheses->members.at(1).type;
  EXPECT_EQ(seq.idl, "sequence<stickrep::msgs::PoseHypothesis, 64>");
  EXPECT_EQ(seq.bound, 64u);
  EXPECT_EQ(seq.element->name, "stickrep::msgs::PoseHypothesis");
  const idl::Struct* status = idl::FindStruct("stickrep::msgs::ComponentStatus");
  ASSERT_NE(status, nullptr);
  EXPECT_TRUE(status->members.at(1).key);
  EXPECT_EQ(status->members.at(1).name, "component_name");
  EXPECT_FALSE(status->members.at(2).key);
  const idl::Enum* mode = idl::FindEnum("stickrep::msgs::MotionMode");
  ASSERT_NE(mode, nullptr);
  EXPECT_THAT(mode->enumerators,
              ::testing::ElementsAre("MOTION_STOP", "MOTION_VELOCITY", "MOTION_FOLLOW_HALLWAY"));
  EXPECT_STREQ((idl::TypeName<msgs::Image>::value), "stickrep::msgs::Image");
}

TEST(MessageJsonTest, EnumsAreNamedAsTheIdlSpellsThem) {
  EXPECT_STREQ(msgs::EnumName(msgs::COMPONENT_ACTIVE), "COMPONENT_ACTIVE");
  EXPECT_STREQ(msgs::EnumName(msgs::LOCALIZATION_RECOVERING), "LOCALIZATION_RECOVERING");
  EXPECT_STREQ(msgs::EnumName(msgs::DOOR_36_36), "DOOR_36_36");
  EXPECT_STREQ(msgs::EnumName(static_cast<msgs::DoorClass>(99)), "?");
  msgs::DoorClass door = msgs::DOOR_30;
  EXPECT_TRUE(msgs::EnumFromName("DOOR_36_36", &door));
  EXPECT_EQ(door, msgs::DOOR_36_36);
  EXPECT_FALSE(msgs::EnumFromName("36_36", &door));
  EXPECT_EQ(door, msgs::DOOR_36_36);
  // A value outside the enum (a CDR payload can carry one) is written as its number.
  msgs::MotionCommand c;
  c.mode(static_cast<msgs::MotionMode>(7));
  EXPECT_EQ(json(c)["mode"], 7);
}

// from_json's error for `j` read as a T; "accepted" when there is none.
template <typename T>
std::string FromJsonError(const json& j) {
  try {
    j.get<T>();
  } catch (const idl::JsonFormError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(MessageJsonTest, FromJsonRefusesAnUnknownEnumName) {
  json command = msgs::MotionCommand();
  command["mode"] = "VELOCITY";
  EXPECT_EQ(FromJsonError<msgs::MotionCommand>(command),
            "mode: unknown stickrep::msgs::MotionMode name \"VELOCITY\"; the names are "
            "MOTION_STOP, MOTION_VELOCITY, MOTION_FOLLOW_HALLWAY");
  command["mode"] = 1;
  EXPECT_THAT(FromJsonError<msgs::MotionCommand>(command),
              HasSubstr("mode: expected a stickrep::msgs::MotionMode name, got a number (1)"));
  json scan = msgs::SonarScan();
  scan["reading_state"][3] = "NO_ECHO";
  EXPECT_THAT(FromJsonError<msgs::SonarScan>(scan),
              HasSubstr("reading_state[3]: unknown stickrep::msgs::SonarReadingState name"));
}

TEST(MessageJsonTest, FromJsonRefusesAMissingMember) {
  json pose = msgs::LocalizationPose();
  pose["best"]["pose"].erase("x_in");
  EXPECT_EQ(FromJsonError<msgs::LocalizationPose>(pose),
            "best.pose: missing member 'x_in' of stickrep::msgs::Pose2D");
  msgs::PoseHypotheses h;
  h.hypotheses().resize(2);
  json hypotheses = h;
  hypotheses["hypotheses"][1].erase("ring_id");
  EXPECT_EQ(FromJsonError<msgs::PoseHypotheses>(hypotheses),
            "hypotheses[1]: missing member 'ring_id' of stickrep::msgs::PoseHypothesis");
  EXPECT_EQ(FromJsonError<msgs::MissionGoal>(json::object()),
            "missing member 'header' of stickrep::msgs::MissionGoal");
}

TEST(MessageJsonTest, FromJsonRefusesIllTypedMembers) {
  const auto with = [](json j, const std::string& pointer, json value) {
    j[json::json_pointer(pointer)] = std::move(value);
    return j;
  };
  EXPECT_EQ(FromJsonError<msgs::Odometry>(with(msgs::Odometry(), "/distance_in", "far")),
            "distance_in: expected a number (double), \"nan\", \"inf\" or \"-inf\", got a "
            "string (\"far\")");
  EXPECT_EQ(FromJsonError<msgs::MotionState>(with(msgs::MotionState(), "/travel_sign", 1.5)),
            "travel_sign: expected an integer (long), got a number (1.5)");
  EXPECT_EQ(FromJsonError<msgs::SonarScan>(with(msgs::SonarScan(), "/valid_count", 70000)),
            "valid_count: a number (70000) is out of the range of unsigned short");
  EXPECT_EQ(FromJsonError<msgs::ComponentStatus>(with(msgs::ComponentStatus(), "/samples_in", -1)),
            "samples_in: a number (-1) is out of the range of unsigned long long");
  EXPECT_EQ(FromJsonError<msgs::GroundTruth>(with(msgs::GroundTruth(), "/forward_in_ring", "true")),
            "forward_in_ring: expected a boolean, got a string (\"true\")");
  EXPECT_EQ(
      FromJsonError<msgs::MissionStatus>(with(msgs::MissionStatus(), "/header", json::array())),
      "header: expected an object (stickrep::msgs::SampleHeader), got an array of 0 "
      "elements");
  EXPECT_EQ(FromJsonError<msgs::SonarEcho>(
                with(msgs::SonarEcho(), "/range_in", std::vector<float>(23, 1.0f))),
            "range_in: 23 elements; float[24] has 24");
  EXPECT_THAT(FromJsonError<msgs::Image>(with(msgs::Image(), "/data", "not base64")),
              HasSubstr("data: base64 of 10 characters"));
  EXPECT_THAT(FromJsonError<msgs::Image>(with(msgs::Image(), "/data", "AB*D")),
              HasSubstr("data: not base64"));
  msgs::PoseHypotheses many;
  many.hypotheses().resize(65);
  EXPECT_EQ(FromJsonError<msgs::PoseHypotheses>(json(many)),
            "hypotheses: 65 elements, more than the bound of "
            "sequence<stickrep::msgs::PoseHypothesis, 64>");
  EXPECT_EQ(FromJsonError<msgs::MissionGoal>(with(msgs::MissionGoal(), "/priority", 1)),
            "unknown member 'priority' of stickrep::msgs::MissionGoal");
}

TEST(MessageJsonTest, NonFiniteNumbersSurviveTheTextForm) {
  msgs::SonarEcho e;
  e.range_in()[0] = std::numeric_limits<float>::quiet_NaN();
  e.range_in()[1] = std::numeric_limits<float>::infinity();
  e.range_in()[2] = -std::numeric_limits<float>::infinity();
  e.range_in()[3] = 12.5f;
  const json j = e;
  EXPECT_EQ(j["range_in"][0], "nan");
  EXPECT_EQ(j["range_in"][1], "inf");
  EXPECT_EQ(j["range_in"][2], "-inf");
  const auto back = json::parse(j.dump()).get<msgs::SonarEcho>();
  EXPECT_TRUE(std::isnan(back.range_in()[0]));
  EXPECT_EQ(back.range_in()[1], std::numeric_limits<float>::infinity());
  EXPECT_EQ(back.range_in()[2], -std::numeric_limits<float>::infinity());
  EXPECT_EQ(back.range_in()[3], 12.5f);
  json big = j;
  big["range_in"][4] = 1e300;
  EXPECT_EQ(FromJsonError<msgs::SonarEcho>(big),
            "range_in[4]: a number (1e+300) is out of the range of float");
}

TEST(MessageJsonTest, EchoShowsOctetSequencesAsLengthAndHash) {
  msgs::Image img;
  img.width_px(4);
  img.height_px(2);
  img.step_bytes(4);
  img.encoding("mono8");
  img.data(std::vector<uint8_t>(8, 7));
  std::uint64_t fnv1a = 1469598103934665603ull;
  for (int i = 0; i < 8; ++i) fnv1a = (fnv1a ^ 7) * 1099511628211ull;
  const json echo = ToJson(img);
  EXPECT_FALSE(echo.contains("data"));
  EXPECT_EQ(echo["data_bytes"], 8);
  EXPECT_EQ(echo["data_fnv1a"], fnv1a);
  EXPECT_EQ(echo["width_px"], 4);
  EXPECT_EQ(echo["encoding"], "mono8");
  EXPECT_TRUE(echo.contains("header"));
  // The JSON form itself (decode_json's, stickrep-bag export's) keeps the pixels.
  const json form = img;
  EXPECT_EQ(form["data"], "BwcHBwcHBwc=");
  EXPECT_TRUE(form.get<msgs::Image>() == img);
  EXPECT_EQ(EchoForm("stickrep::msgs::Image", form), echo);
  // Types without octet sequences echo as their JSON form.
  msgs::StickRepMap map;
  map.rings().resize(2);
  map.rings()[1].edges().resize(3);
  EXPECT_EQ(ToJson(map), json(map));
}

// ---------------------------------------------------------------------------------------------
// The generator on IDL it must refuse.

class IdlJsonGenTest : public ::testing::Test {
 protected:
  IdlJsonGenTest()
      : dir_(std::filesystem::path(::testing::TempDir()) /
             ("idl_json_gen_test_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~IdlJsonGenTest() override { std::filesystem::remove_all(dir_); }

  // Runs the generator on `text` as t.idl: its exit status and what it printed.
  std::pair<int, std::string> Generate(const std::string& text) {
    std::ofstream(dir_ / "t.idl") << text;
    const std::string command = std::string(STICKREP_BINARY_DIR) + "/idl/idl_json_gen --header " +
                                (dir_ / "t.h").string() + " --source " + (dir_ / "t.cpp").string() +
                                " " + (dir_ / "t.idl").string() + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string output;
    std::array<char, 256> buffer;
    while (pipe != nullptr && std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
      output += buffer.data();
    }
    const int status = pipe == nullptr ? -1 : ::pclose(pipe);
    return {status, output};
  }

  std::filesystem::path dir_;
};

TEST_F(IdlJsonGenTest, WritesTheFormOfWhatItUnderstands) {
  const auto [status, output] = Generate(
      "module m { enum E { A, B }; /* c */ struct S { @key string<8> id; char c;\n"
      "  float grid[2][3]; sequence<sequence<long, 3>, 4> nested; E e; }; };\n");
  EXPECT_EQ(status, 0) << output;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "t.h"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "t.cpp"));
}

TEST_F(IdlJsonGenTest, RefusesWhatItDoesNotUnderstandWithFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"module m {\n  typedef long L;\n};\n", "t.idl:2: error: 'typedef' definitions are not"},
      {"module m {\n  union U switch (long) { case 1: long a; };\n};\n",
       "t.idl:2: error: 'union' definitions are not supported"},
      {"module m {\n@appendable\nstruct S { long a; };\n};\n",
       "t.idl:2: error: annotation @appendable is not supported here"},
      {"struct S {\n  @optional long a;\n};\n",
       "t.idl:2: error: annotation @optional is not supported (only @key)"},
      {"struct S {\n  long a;\n  wstring w;\n};\n",
       "t.idl:3: error: type 'wstring' is not supported"},
      {"struct S {\n  Pose p;\n};\n", "t.idl:2: error: unknown type 'Pose'"},
      {"#define N 3\nstruct S { long a; };\n",
       "t.idl:1: error: preprocessor directive #define is not supported"},
      {"struct S {\n  long a[N];\n};\n", "t.idl:2: error: expected an array length"},
      {"enum E {\n  A = 1\n};\n", "t.idl:2: error: enumerator values are not supported"},
      {"struct S {\n  long a\n};\n", "t.idl:3: error: expected ';' after member a"},
      {"struct S {\n  long double d;\n};\n", "t.idl:2: error: type 'long double' is not supported"},
      {"struct S {\n  long a;\n  short a;\n};\n",
       "t.idl:3: error: member 'a' of struct S is declared twice"},
      {"#include \"missing.idl\"\n",
       "t.idl:1: error: cannot find the included file \"missing.idl\""},
      {"struct S { long a; };\n/* open\n", "t.idl:2: error: unterminated /* comment"},
  };
  for (const auto& [idl, expected] : cases) {
    std::filesystem::remove(dir_ / "t.h");
    const auto [status, output] = Generate(idl);
    EXPECT_NE(status, 0) << idl;
    EXPECT_THAT(output, HasSubstr(expected)) << idl;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "t.h")) << idl;
  }
}

}  // namespace
}  // namespace stickrep::console
