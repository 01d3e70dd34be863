// orbit token (cli/token_command.cc): a new token and the line that grants it, which a server
// started on that line accepts the token by.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "server/token_file.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::RunOrbit;

TEST(TokenCommandTest, PrintsATokenAndTheLineThatGrantsItByItsDigest) {
  const testing::CommandResult made = RunOrbit("token --name phone-7 --role admin");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  std::istringstream lines(made.out);
  std::string token, line, extra;
  ASSERT_TRUE(std::getline(lines, token));
  ASSERT_TRUE(std::getline(lines, line));
  EXPECT_FALSE(std::getline(lines, extra)) << "two lines only";
  EXPECT_EQ(token.size(), 43u);
  EXPECT_EQ(line, "phone-7 admin " + server::HexOf(server::DigestOf(token)));

  // The line, in a token file, grants the token; the token itself appears nowhere in it.
  testing::ScratchDir dir;
  testing::WriteTokenFile(dir / "tokens", line + "\n");
  const server::TokenFile read = server::ReadTokenFile(dir / "tokens");
  ASSERT_EQ(read.grants.size(), 1u);
  EXPECT_EQ(read.grants[0].name, "phone-7");
  EXPECT_EQ(read.grants[0].role, server::Role::kAdmin);
  EXPECT_TRUE(read.warnings.empty());

  const testing::CommandResult again = RunOrbit("token --name phone-7");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.substr(0, 43), token) << "a new token each time";
  EXPECT_NE(again.out.find("phone-7 recognize "), std::string::npos) << "recognize by default";
}

TEST(TokenCommandTest, RefusesANameTheServerWouldRefuse) {
  const testing::CommandResult refused = RunOrbit("token --name 'phone 7'");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("'phone 7' is not 1..64 letters, digits, '_', '-' or '.'"),
            std::string::npos)
      << refused.err;
  EXPECT_NE(RunOrbit("token").exit_code, 0) << "--name is required";
}

}  // namespace
}  // namespace orbit
