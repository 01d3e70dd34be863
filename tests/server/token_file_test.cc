// The token file (server/token_file.h): both line forms, every refusal with its file and line,
// the permissions it must have, and the tokens and lines `orbit token` makes.
#include "server/token_file.h"

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/server_process.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit::server {
namespace {

using orbit::testing::ErrorMessageOf;
using orbit::testing::ScratchDir;

constexpr char kAdminToken[] = "admin-token-0123456789";
constexpr char kDeviceToken[] = "device-token-0123456789";

class TokenFileTest : public ::testing::Test {
 protected:
  std::filesystem::path Write(const std::string& text) {
    testing::WriteTokenFile(file_, text);
    return file_;
  }
  std::string At(int line) const { return file_.string() + ":" + std::to_string(line) + ": "; }
  std::string ReadError() {
    return ErrorMessageOf<std::runtime_error>([&] { ReadTokenFile(file_); });
  }

  ScratchDir dir_;
  const std::filesystem::path file_ = dir_ / "tokens";
};

TEST(TokenDigestTest, IsTheSha256OfTheToken) {
  // FIPS 180-2's first example.
  EXPECT_EQ(HexOf(DigestOf("abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(TokenFileLine("ops", Role::kAdmin, "abc"),
            "ops admin ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(TokenDigestTest, NewTokensAre43Base64UrlCharactersAndNeverRepeat) {
  std::set<std::string> seen;
  for (int i = 0; i < 100; ++i) {
    const std::string token = NewToken();
    EXPECT_EQ(token.size(), 43u);
    EXPECT_EQ(token.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                      "0123456789-_"),
              std::string::npos)
        << token;
    EXPECT_TRUE(seen.insert(token).second);
  }
}

TEST_F(TokenFileTest, ReadsHashedLinesByNameAndClearOnesWithAWarning) {
  const TokenFile read =
      ReadTokenFile(Write("# operators\n" + TokenFileLine("ops-laptop", Role::kAdmin, kAdminToken) +
                          "\n\n" + kDeviceToken + "  recognize\n"));
  ASSERT_EQ(read.grants.size(), 2u);
  EXPECT_EQ(read.grants[0].name, "ops-laptop");
  EXPECT_EQ(read.grants[0].role, Role::kAdmin);
  EXPECT_EQ(read.grants[0].digest, DigestOf(kAdminToken));
  const std::string device_name = "token-" + HexOf(DigestOf(kDeviceToken)).substr(0, 8);
  EXPECT_EQ(read.grants[1].name, device_name);
  EXPECT_EQ(read.grants[1].role, Role::kRecognize);
  EXPECT_EQ(read.grants[1].digest, DigestOf(kDeviceToken));
  ASSERT_EQ(read.warnings.size(), 1u);
  EXPECT_EQ(read.warnings[0], At(4) + "a token in clear text (named " + device_name + "): give `" +
                                  TokenFileLine(device_name, Role::kRecognize, kDeviceToken) +
                                  "` instead, which holds only its SHA-256");
}

TEST_F(TokenFileTest, ReadsAGrantToAClientCertificateByItsName) {
  const TokenFile read =
      ReadTokenFile(Write("device-7 recognize certificate\n"
                          "device-8 recognize certificate\n" +
                          TokenFileLine("ops", Role::kAdmin, kAdminToken) + "\n"));
  ASSERT_EQ(read.grants.size(), 3u);
  EXPECT_EQ(read.grants[0].name, "device-7");
  EXPECT_TRUE(read.grants[0].certificate);
  EXPECT_TRUE(read.grants[1].certificate);
  EXPECT_FALSE(read.grants[2].certificate);
  Write("device-7 recognize certificate\ndevice-7 admin certificate\n");
  EXPECT_EQ(ReadError(), At(2) + "duplicate name 'device-7'");
}

TEST_F(TokenFileTest, WarnsOfACommentThatLooksLikeATokenLine) {
  const TokenFile read =
      ReadTokenFile(Write("#secret-token-012345 admin\n" +
                          TokenFileLine("ops", Role::kAdmin, kAdminToken) + "\n# two words\n"));
  EXPECT_EQ(read.grants.size(), 1u);
  ASSERT_EQ(read.warnings.size(), 1u);
  EXPECT_EQ(read.warnings[0], At(1) +
                                  "read as a comment, though it looks like a token and a role: "
                                  "a token may not start with '#'");
}

TEST_F(TokenFileTest, RefusesEachBadLineNamingFileAndLine) {
  const std::string good = TokenFileLine("ops", Role::kAdmin, kAdminToken) + "\n";
  Write(good + "just-one-field-here\n");
  EXPECT_EQ(ReadError(), At(2) + "expected `<name> <role> <sha256>` (or `<token> <role>`)");
  Write(good + "a b c d\n");
  EXPECT_EQ(ReadError(), At(2) + "expected `<name> <role> <sha256>` (or `<token> <role>`)");
  Write(good + "phone Admin " + HexOf(DigestOf("x")) + "\n");
  EXPECT_EQ(ReadError(), At(2) + "unknown role 'Admin' (recognize or admin)");
  Write(good + "phone/7 recognize " + HexOf(DigestOf("x")) + "\n");
  EXPECT_EQ(ReadError(), At(2) + "name 'phone/7' is not 1..64 letters, digits, '_', '-' or '.'");
  Write(good + "phone recognize 0123abcd\n");
  EXPECT_EQ(ReadError(), At(2) + "expected the token's SHA-256 as 64 hex digits, or `certificate`");
  Write(good + "0123456789abcde admin\n");  // 15 characters
  EXPECT_EQ(ReadError(), At(2) + "token shorter than 16 characters");
  Write(good + std::string(kAdminToken) + " recognize\n");  // the same token, in clear text
  EXPECT_EQ(ReadError(), At(2) + "duplicate token");
  Write(good + TokenFileLine("ops", Role::kRecognize, kDeviceToken) + "\n");
  EXPECT_EQ(ReadError(), At(2) + "duplicate name 'ops'");
}

TEST_F(TokenFileTest, RefusesAMissingOrEmptyFile) {
  const std::filesystem::path missing = dir_ / "no-such-file";
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { ReadTokenFile(missing); }),
            missing.string() + ": cannot read the token file");
  Write("# nobody may call yet\n\n");
  EXPECT_EQ(ReadError(), file_.string() + ": no tokens in the file");
}

TEST_F(TokenFileTest, RefusesAFileOtherUsersMayReadOrWrite) {
  Write(TokenFileLine("ops", Role::kAdmin, kAdminToken) + "\n");
  using std::filesystem::perms;
  std::filesystem::permissions(file_, perms::others_read, std::filesystem::perm_options::add);
  EXPECT_EQ(ReadError(), file_.string() +
                             ": other users may read the token file (mode 0604); make it the "
                             "server's alone: chmod 600 " +
                             file_.string());
  std::filesystem::permissions(file_, perms::owner_read | perms::owner_write | perms::group_write);
  EXPECT_EQ(ReadError(), file_.string() +
                             ": other users may write the token file (mode 0620); make it the "
                             "server's alone: chmod 600 " +
                             file_.string());
  // Its group may read it (a service group, a container's user).
  std::filesystem::permissions(file_, perms::owner_read | perms::owner_write | perms::group_read);
  EXPECT_EQ(ReadTokenFile(file_).grants.size(), 1u);
}

}  // namespace
}  // namespace orbit::server
