#include "common/strict_yaml.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace stickrep {
namespace {

using ::testing::HasSubstr;

// Runs `fn`, expects an InputError and returns it for inspection.
template <typename Fn>
InputError CatchInputError(Fn fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", 0, "", "");
}

TEST(StrictYamlTest, ReadsTypedValuesAndAcceptsWhenEveryKeyIsUsed) {
  const StrictYaml root =
      StrictYaml::LoadString("sonar:\n  rate_hz: 10\n  name: ring\n  on: true\n", "cfg.yaml");
  const StrictYaml sonar = root.Child("sonar");
  EXPECT_DOUBLE_EQ(sonar.Get<double>("rate_hz", 0.1, 100.0), 10.0);
  EXPECT_EQ(sonar.Get<std::string>("name"), "ring");
  EXPECT_TRUE(sonar.Get<bool>("on"));
  EXPECT_NO_THROW(sonar.Finish());
  EXPECT_NO_THROW(root.Finish());
}

TEST(StrictYamlTest, QuotedTextReadsBackAsTheSameBytes) {
  const std::vector<std::string> texts = {
      "", "plain", "say \"hi\"", "back\\slash", "\\\xe9 after a backslash", "tab\there",
      "line\nbreak\r", std::string("nul\0byte", 8), "\x01\x1f\x7f", "na\xc3\xafve",
      "\\x41 is not an escape", "# not a comment", "key: value", "- item", "'single'"};
  for (const std::string& text : texts) {
    const std::string yaml = "text: " + YamlQuoted(text) + "\n";
    StrictYaml root = StrictYaml::LoadString(yaml, "quoted.yaml");
    EXPECT_EQ(root.Get<std::string>("text"), text) << yaml;
  }
}

TEST(StrictYamlTest, UnknownKeyNamesFileLineAndKey) {
  const StrictYaml root = StrictYaml::LoadString("sonar:\n  rate_hz: 10\n  rat_hz: 3\n", "c.yaml");
  const StrictYaml sonar = root.Child("sonar");
  sonar.Get<double>("rate_hz");
  const InputError e = CatchInputError([&] { sonar.Finish(); });
  EXPECT_EQ(e.file(), "c.yaml");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.key(), "sonar.rat_hz");
  EXPECT_THAT(e.what(), HasSubstr("unknown key"));
}

TEST(StrictYamlTest, MissingKeyNamesTheParentLine) {
  const StrictYaml root = StrictYaml::LoadString("a: 1\nsonar:\n  x: 2\n", "c.yaml");
  const InputError e = CatchInputError([&] { root.Child("sonar").Get<double>("rate_hz"); });
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.key(), "sonar.rate_hz");
  EXPECT_THAT(e.reason(), HasSubstr("missing"));
}

TEST(StrictYamlTest, WrongTypeIsRejected) {
  const StrictYaml root = StrictYaml::LoadString("rate_hz: fast\n", "c.yaml");
  const InputError e = CatchInputError([&] { root.Get<double>("rate_hz"); });
  EXPECT_EQ(e.line(), 1);
  EXPECT_THAT(e.reason(), HasSubstr("expected a number"));
}

TEST(StrictYamlTest, IntegerRejectsFraction) {
  const StrictYaml root = StrictYaml::LoadString("domain_id: 1.5\n", "c.yaml");
  EXPECT_THROW(root.Get<int>("domain_id"), InputError);
}

TEST(StrictYamlTest, OutOfRangeValueStatesTheRangeAndUnit) {
  const StrictYaml root = StrictYaml::LoadString("speed_ftps: 9.5\n", "c.yaml");
  const InputError e = CatchInputError([&] { root.Get<double>("speed_ftps", 0.0, 2.6, "ft/s"); });
  EXPECT_THAT(e.reason(), HasSubstr("outside [0, 2.6] ft/s"));
}

TEST(StrictYamlTest, NanIsNotAFiniteNumber) {
  const StrictYaml root = StrictYaml::LoadString("x: .nan\n", "c.yaml");
  EXPECT_THROW(root.Get<double>("x"), InputError);
}

TEST(StrictYamlTest, MalformedYamlReportsTheLine) {
  const InputError e =
      CatchInputError([] { StrictYaml::LoadString("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml"); });
  EXPECT_EQ(e.file(), "bad.yaml");
  EXPECT_GT(e.line(), 1);
  EXPECT_THAT(e.reason(), HasSubstr("malformed YAML"));
}

TEST(StrictYamlTest, BinaryDataIsRejected) {
  const std::string text("a: 1\n\0\x01\x02", 8);
  EXPECT_THROW(StrictYaml::LoadString(text, "bin.yaml"), InputError);
}

TEST(StrictYamlTest, DeeplyNestedGarbageDoesNotCrash) {
  const std::string text = "a: " + std::string(100000, '[');
  EXPECT_THROW(StrictYaml::LoadString(text, "deep.yaml"), InputError);
}

TEST(StrictYamlTest, OversizedFileIsRejectedBeforeParsing) {
  const std::string path = ::testing::TempDir() + "/oversized.yaml";
  {
    std::ofstream out(path);
    const std::string chunk(1 << 20, 'x');
    for (std::uintmax_t i = 0; i <= kMaxYamlFileBytes / chunk.size(); ++i) out << chunk;
  }
  const InputError e = CatchInputError([&] { StrictYaml::LoadFile(path); });
  EXPECT_THAT(e.reason(), HasSubstr("bytes at most"));
  std::remove(path.c_str());
}

TEST(StrictYamlTest, MissingFileIsAnInputError) {
  EXPECT_THROW(StrictYaml::LoadFile("/nonexistent/stickrep.yaml"), InputError);
}

TEST(StrictYamlTest, SequenceElementsCarryIndexedPaths) {
  const StrictYaml root = StrictYaml::LoadString("rings:\n  - id: a\n  - id: 7x\n", "m.yaml");
  const auto rings = root.Sequence("rings");
  ASSERT_EQ(rings.size(), 2u);
  EXPECT_EQ(rings[1].path(), "rings[1]");
  EXPECT_EQ(rings[1].line(), 3);
  const InputError e = CatchInputError([&] { rings[1].Get<int>("id"); });
  EXPECT_EQ(e.key(), "rings[1].id");
}

// A mapping, a sequence or null as a key is refused with the key's line (yaml-cpp's own
// conversion exception used to escape from Keys() and Finish(); found by fuzz_error_model).
TEST(StrictYamlTest, KeyThatIsNotAScalarIsAnInputError) {
  for (const char* text : {"m:\n  a: 1\n  {b: 2}: 3\n", "m:\n  a: 1\n  [b, c]: 3\n",
                           "m:\n  a: 1\n  ~: 3\n"}) {
    const StrictYaml m = StrictYaml::LoadString(text, "k.yaml").Child("m");
    m.Get<int>("a");
    const InputError finish = CatchInputError([&] { m.Finish(); });
    EXPECT_EQ(finish.file(), "k.yaml") << text;
    EXPECT_EQ(finish.line(), 3) << text;
    EXPECT_THAT(finish.reason(), HasSubstr("a key must be a plain word or number")) << text;
    const InputError keys = CatchInputError([&] { m.Keys(); });
    EXPECT_EQ(keys.line(), 3) << text;
  }
}

TEST(StrictYamlTest, TopLevelMustBeAMapping) {
  EXPECT_THROW(StrictYaml::LoadString("- 1\n- 2\n", "s.yaml"), InputError);
}

}  // namespace
}  // namespace stickrep
