// SPDX-License-Identifier: Apache-2.0
// Keeps docs/session-format.md honest: its examples parse and it documents every key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "session/schema.h"
#include "session/session_test_util.h"

namespace mrh::session {
namespace {

namespace fs = std::filesystem;

std::string ReadDocs() {
  std::ifstream in(fs::path(MRH_SOURCE_DIR) / "docs" / "session-format.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The bodies of the ```json fenced blocks.
std::vector<std::string> JsonBlocks(const std::string& markdown) {
  std::vector<std::string> blocks;
  const std::string open = "```json\n";
  for (std::size_t at = markdown.find(open); at != std::string::npos;
       at = markdown.find(open, at)) {
    const std::size_t begin = at + open.size();
    const std::size_t end = markdown.find("```", begin);
    blocks.push_back(markdown.substr(begin, end - begin));
    at = end;
  }
  return blocks;
}

void Touch(const fs::path& path) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "";
}

// Writes the example into its own folder next to empty stand-ins for the files it names (only
// their existence is checked when a session is read) and loads it.
Session LoadExample(const std::string& text, int index) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder =
      fs::path(::testing::TempDir()) / (std::string("mrh_") + info->name() + "_" +
                                        std::to_string(::getpid()) + "_" + std::to_string(index));
  fs::create_directories(folder);
  const nlohmann::json document = nlohmann::json::parse(text);
  Touch(folder / document.at("scene").get<std::string>());
  // One `device`, or one per element of `pointers`.
  std::vector<nlohmann::json> devices;
  if (document.contains("pointers")) {
    for (const nlohmann::json& pointer : document.at("pointers"))
      devices.push_back(pointer.at("device"));
  } else {
    devices.push_back(document.at("device"));
  }
  for (const nlohmann::json& device : devices) {
    for (const char* key : {"trajectory", "replay"}) {
      if (device.contains(key)) Touch(folder / device.at(key).get<std::string>());
    }
  }
  std::ofstream(folder / "session.json") << text;
  return LoadSession(folder / "session.json");
}

TEST(SessionDocsTest, EveryJsonExampleIsAValidSession) {
  const std::vector<std::string> blocks = JsonBlocks(ReadDocs());
  std::set<std::string> device_types;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    try {
      device_types.insert(LoadExample(blocks[i], static_cast<int>(i)).device.type);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "example " << i << ": " << e.what();
    }
  }
  EXPECT_EQ(device_types, (std::set<std::string>{"fixed", "scripted", "hand", "replay"}));
}

template <typename Table>
void ExpectDocumented(const std::string& docs, const std::string& prefix, const Table& fields) {
  for (const auto& field : fields) {
    const std::string key = "`" + prefix + std::string(field.key) + "`";
    EXPECT_THAT(docs, ::testing::HasSubstr(key)) << key << " is not in docs/session-format.md";
  }
}

TEST(SessionDocsTest, EveryKeyOfTheCodeIsDocumented) {
  const std::string docs = ReadDocs();
  ExpectDocumented(docs, "", internal::kEngineFields);
  ExpectDocumented(docs, "pointer.", internal::kPointerFields);
  ExpectDocumented(docs, "rendering.", internal::kRenderingFields);
  ExpectDocumented(docs, "safety.", internal::kSafetyFields);
  ExpectDocumented(docs, "device.hand.", internal::kHandFields);
  ExpectDocumented(docs, "device.limits.", internal::kLimitFields);
  for (const std::string_view key : internal::kRenderingSpecialKeys) {
    EXPECT_THAT(docs, ::testing::HasSubstr("`rendering." + std::string(key) + "`")) << key;
  }
  for (const std::string_view key : internal::kTopLevelSpecialKeys) {
    EXPECT_THAT(docs, ::testing::HasSubstr("`" + std::string(key) + "`")) << key;
  }
  for (const std::string_view key : internal::kDeviceCommonKeys) {
    EXPECT_THAT(docs, ::testing::HasSubstr("`device." + std::string(key) + "`")) << key;
  }
  for (const internal::DeviceType& type : internal::kDeviceTypes) {
    EXPECT_THAT(docs, ::testing::HasSubstr("`" + std::string(type.name) + "`")) << type.name;
    for (const std::string_view key : type.keys) {
      if (key.empty()) continue;
      EXPECT_THAT(docs, ::testing::HasSubstr("`device." + std::string(key) + "`")) << key;
    }
  }
  for (const std::string_view key : internal::kCalibrationKeys) {
    EXPECT_THAT(docs, ::testing::HasSubstr("`device.calibration." + std::string(key) + "`"));
  }
}

}  // namespace
}  // namespace mrh::session
