// The stickrep-map tool's answers to bad map files: exit 2 with file, line, key and reason.
#include "map_tool/map_tool.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "common/input_error.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

using testing::EditedBoxMap;
using testing::kBoxMapYaml;
using testing::LineOf;

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(MapToolTest, ValidateExitsTwoWithFileLineKeyAndReason) {
  const std::string text = EditedBoxMap("class: \"36\"", "class: \"34\"");
  const std::string path = WriteTemp("illegal_class.yaml", text);
  std::ostringstream out, err;
  EXPECT_EQ(tool::Validate({path}, out, err), kExitBadInput);
  const std::string want = path + ":" + std::to_string(LineOf(text, "class: \"34\"")) +
                           ": key 'rings[0].path[3].edge.class'";
  EXPECT_EQ(err.str().rfind(want, 0), 0u) << err.str();
  std::remove(path.c_str());
}

TEST(MapToolTest, ValidateAcceptsAGoodMap) {
  const std::string path = WriteTemp("box.yaml", kBoxMapYaml);
  std::ostringstream out, err;
  EXPECT_EQ(tool::Validate({path}, out, err), 0);
  EXPECT_TRUE(err.str().empty());
  std::remove(path.c_str());
}

TEST(MapToolTest, FiftyMegabytesOfGarbageExitsTwoWithoutReadingIt) {
  const std::string path = ::testing::TempDir() + "garbage_50mb.yaml";
  {
    std::ofstream f(path, std::ios::binary);
    std::mt19937_64 rng(7);
    std::string block(1 << 20, '\0');
    for (int mb = 0; mb < 50; ++mb) {
      for (char& c : block) c = static_cast<char>(rng());
      f << block;
    }
  }
  std::ostringstream out, err;
  EXPECT_EQ(tool::Validate({path}, out, err), kExitBadInput);
  EXPECT_NE(err.str().find(path + ": file is 52428800 bytes"), std::string::npos) << err.str();
  std::remove(path.c_str());
}

TEST(MapToolTest, BinaryGarbageUnderTheSizeLimitExitsTwo) {
  const std::string path = WriteTemp("garbage_small.yaml", std::string("\x01\x02\x00\xff", 4));
  std::ostringstream out, err;
  EXPECT_EQ(tool::Validate({path}, out, err), kExitBadInput);
  EXPECT_NE(err.str().find("NUL byte"), std::string::npos) << err.str();
  std::remove(path.c_str());
}

TEST(MapToolTest, EveryCommandThatLoadsAMapExitsTwoOnABadOne) {
  const std::string path = WriteTemp("dangling.yaml", EditedBoxMap("to_ring: box", "to_ring: nowhere"));
  std::ostringstream out, err;
  EXPECT_EQ(tool::Census(path, false, std::nullopt, out, err), kExitBadInput);
  EXPECT_EQ(tool::Ambiguity(path, {}, out, err), kExitBadInput);
  EXPECT_EQ(tool::Render(path, ::testing::TempDir() + "x.png", out, err), kExitBadInput);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace stickrep::map
