// The audit log (server/audit_log.h): one JSON line per event, appended to a file of the
// server's alone.
#include "server/audit_log.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_data.h"

namespace orbit::server {
namespace {

std::vector<nlohmann::json> Lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

TEST(AuditLogTest, WritesOneJsonLinePerEventAndAppendsAcrossRestarts) {
  testing::ScratchDir dir;
  const std::filesystem::path file = dir / "audit.jsonl";
  {
    AuditLog log(file.string());
    log.Record({.call = "Models/Enroll",
                .token = "ops",
                .peer = "ipv4:127.0.0.1:5000",
                .object = "mug",
                .outcome = grpc::StatusCode::OK});
  }
  {
    AuditLog log(file.string());  // a restarted server appends
    log.Record({.call = "Models/DeleteObject",
                .token = "ops",
                .peer = "ipv6:[::1]:5001",
                .object = "id 7",
                .outcome = grpc::StatusCode::NOT_FOUND,
                .message = "no object with id 7 \xff"});
  }
  const std::vector<nlohmann::json> lines = Lines(file);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0]["call"], "Models/Enroll");
  EXPECT_EQ(lines[0]["token"], "ops");
  EXPECT_EQ(lines[0]["peer"], "ipv4:127.0.0.1:5000");
  EXPECT_EQ(lines[0]["object"], "mug");
  EXPECT_EQ(lines[0]["outcome"], "OK");
  EXPECT_FALSE(lines[0].contains("message"));
  EXPECT_TRUE(std::regex_match(lines[0]["time"].get<std::string>(),
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)")))
      << lines[0]["time"];
  EXPECT_EQ(lines[1]["outcome"], "NOT_FOUND");
  EXPECT_EQ(lines[1]["message"], "no object with id 7 \xef\xbf\xbd") << "invalid UTF-8 replaced";
  EXPECT_EQ(std::filesystem::status(file).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

TEST(AuditLogTest, RefusesAFileItCannotOpenNamingIt) {
  try {
    AuditLog log("/nonexistent-folder/audit.jsonl");
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot open the audit log /nonexistent-folder/audit.jsonl");
  }
}

}  // namespace
}  // namespace orbit::server
