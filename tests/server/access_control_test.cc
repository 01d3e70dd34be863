// Who may call what: the token file `orbit serve --tokens` reads, every refusal it promises
// (each naming the file, and the line when there is one), and the status each call gets
// (server/access_control.h; docs/design.md#service-behaviour).
//
// The calls' metadata is put on a real grpc::ServerContext with gRPC's own test peer,
// grpc::testing::ServerContextTestSpouse, so no server needs to run.
#include "server/access_control.h"

#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include <grpcpp/test/server_context_test_spouse.h>
#include <gtest/gtest.h>

#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit::server {
namespace {

using orbit::testing::ErrorMessageOf;
using orbit::testing::ScratchDir;

constexpr char kAdminToken[] = "admin-token-0123456789";          // 22 characters
constexpr char kRecognizeToken[] = "recognize-token-0123456789";  // 26 characters

// A token file in a scratch folder, written with the given text.
class AccessControlFileTest : public ::testing::Test {
 protected:
  std::filesystem::path Write(const std::string& text) {
    std::ofstream(file_) << text;
    return file_;
  }

  // "<file>:<line>: " as every per-line refusal begins.
  std::string At(int line) const { return file_.string() + ":" + std::to_string(line) + ": "; }

  ScratchDir dir_;
  const std::filesystem::path file_ = dir_ / "tokens.txt";
};

// The status of a call carrying `authorization` (none when nullptr) that needs `needed`.
grpc::Status Call(const AccessControl& access, const char* authorization, Role needed) {
  grpc::ServerContext context;
  grpc::testing::ServerContextTestSpouse spouse(&context);
  if (authorization != nullptr) spouse.AddClientMetadata("authorization", authorization);
  return access.Authorize(context, needed);
}

std::string Bearer(const std::string& token) { return "Bearer " + token; }

TEST_F(AccessControlFileTest, ReadsOneTokenPerLineIgnoringBlankLinesAndComments) {
  const AccessControl access =
      AccessControl::FromFile(Write("# the operators\n"
                                    "\n" +
                                    std::string(kAdminToken) + " admin\n" +
                                    "   \t\n"
                                    "#the devices, one per line\n" +
                                    kRecognizeToken + "   recognize\n"));
  EXPECT_TRUE(access.enabled());
  EXPECT_EQ(access.token_count(), 2u);
  EXPECT_TRUE(Call(access, Bearer(kAdminToken).c_str(), Role::kAdmin).ok());
  EXPECT_TRUE(Call(access, Bearer(kRecognizeToken).c_str(), Role::kRecognize).ok());
}

TEST_F(AccessControlFileTest, AcceptsATokenOfExactlySixteenCharacters) {
  const AccessControl access = AccessControl::FromFile(Write("0123456789abcdef recognize\n"));
  EXPECT_EQ(access.token_count(), 1u);
  EXPECT_TRUE(Call(access, "Bearer 0123456789abcdef", Role::kRecognize).ok());
}

TEST_F(AccessControlFileTest, RefusesAnUnreadableFile) {
  const std::filesystem::path missing = dir_ / "no-such-file.txt";
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(missing); }),
            missing.string() + ": cannot read the token file");
}

TEST_F(AccessControlFileTest, RefusesALineWithoutExactlyATokenAndARole) {
  Write("# header\n" + std::string(kAdminToken) + "\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            At(2) + "expected `<token> <role>`");
  Write(std::string(kAdminToken) + " admin\n\n" + kRecognizeToken + " recognize extra\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            At(3) + "expected `<token> <role>`");
}

TEST_F(AccessControlFileTest, RefusesAnUnknownRole) {
  Write(std::string(kAdminToken) + " admin\n" + kRecognizeToken + " Admin\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            At(2) + "unknown role 'Admin' (recognize or admin)");
}

TEST_F(AccessControlFileTest, RefusesATokenShorterThanSixteenCharacters) {
  Write("\n\n0123456789abcde admin\n");  // 15 characters
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            At(3) + "token shorter than 16 characters");
}

TEST_F(AccessControlFileTest, RefusesADuplicateTokenAtItsSecondLine) {
  Write(std::string(kAdminToken) + " admin\n" + kRecognizeToken + " recognize\n# again\n" +
        kAdminToken + " recognize\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            At(4) + "duplicate token");
}

TEST_F(AccessControlFileTest, RefusesAFileWithNoTokenAtAll) {
  Write("");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            file_.string() + ": no tokens in the file");
  Write("# nobody may call yet\n\n   \n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { AccessControl::FromFile(file_); }),
            file_.string() + ": no tokens in the file");
}

class AccessControlAuthorizeTest : public AccessControlFileTest {
 protected:
  AccessControlAuthorizeTest() {
    access_ = AccessControl::FromFile(
        Write(std::string(kAdminToken) + " admin\n" + kRecognizeToken + " recognize\n"));
  }

  AccessControl access_ = AccessControl::Open();
};

TEST_F(AccessControlAuthorizeTest, AdminTokenMayMakeEveryCall) {
  EXPECT_TRUE(Call(access_, Bearer(kAdminToken).c_str(), Role::kAdmin).ok());
  EXPECT_TRUE(Call(access_, Bearer(kAdminToken).c_str(), Role::kRecognize).ok());
}

TEST_F(AccessControlAuthorizeTest, RecognizeTokenMayRecognizeButNotAdminister) {
  EXPECT_TRUE(Call(access_, Bearer(kRecognizeToken).c_str(), Role::kRecognize).ok());
  EXPECT_EQ(Call(access_, Bearer(kRecognizeToken).c_str(), Role::kAdmin).error_code(),
            grpc::StatusCode::PERMISSION_DENIED);
}

TEST_F(AccessControlAuthorizeTest, CallWithoutAuthorizationIsUnauthenticated) {
  EXPECT_EQ(Call(access_, nullptr, Role::kRecognize).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(Call(access_, nullptr, Role::kAdmin).error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

TEST_F(AccessControlAuthorizeTest, AuthorizationThatIsNotABearerTokenIsUnauthenticated) {
  // A known token, but without the scheme or with another one ("Digest " is as long as
  // "Bearer ", so only the scheme itself is wrong).
  EXPECT_EQ(Call(access_, kAdminToken, Role::kRecognize).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(
      Call(access_, ("Digest " + std::string(kAdminToken)).c_str(), Role::kRecognize).error_code(),
      grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(Call(access_, "Bearer", Role::kRecognize).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
}

TEST_F(AccessControlAuthorizeTest, UnknownTokenIsUnauthenticatedWhateverTheCall) {
  EXPECT_EQ(Call(access_, "Bearer not-a-token-in-the-file", Role::kRecognize).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(Call(access_, "Bearer not-a-token-in-the-file", Role::kAdmin).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  // A token must match whole: a prefix of the admin token is not the admin token.
  EXPECT_EQ(Call(access_, Bearer(std::string(kAdminToken).substr(0, 16)).c_str(), Role::kAdmin)
                .error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(Call(access_, "Bearer ", Role::kRecognize).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
}

TEST(AccessControlOpenTest, AdmitsEveryCallerWithEveryRight) {
  const AccessControl access = AccessControl::Open();
  EXPECT_FALSE(access.enabled());
  EXPECT_EQ(access.token_count(), 0u);
  EXPECT_TRUE(Call(access, nullptr, Role::kAdmin).ok());
  EXPECT_TRUE(Call(access, nullptr, Role::kRecognize).ok());
  EXPECT_TRUE(Call(access, "Bearer anything-at-all", Role::kAdmin).ok());
  EXPECT_TRUE(Call(access, "Basic whatever", Role::kAdmin).ok());
}

}  // namespace
}  // namespace orbit::server
