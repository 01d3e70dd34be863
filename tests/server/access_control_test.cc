// Who may call what (server/access_control.h; docs/design.md#access-control): the status each
// call gets, the grant's name, constant-time matching of digests, reloading the token file, and
// the refusals recorded in the audit log. The file's own rules are token_file_test.cc's.
//
// The calls' metadata is put on a real grpc::ServerContext with gRPC's own test peer,
// grpc::testing::ServerContextTestSpouse, so no server needs to run.
#include "server/access_control.h"

#include "server/audit_log.h"

#include <fstream>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <grpcpp/test/server_context_test_spouse.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/server_process.h"
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
    testing::WriteTokenFile(file_, text);
    return file_;
  }

  // "<file>:<line>: " as every per-line refusal begins.
  std::string At(int line) const { return file_.string() + ":" + std::to_string(line) + ": "; }

  ScratchDir dir_;
  const std::filesystem::path file_ = dir_ / "tokens.txt";
};

// The status of a call carrying `authorization` (none when nullptr) that needs `needed`; the
// grant's name in *name when given.
grpc::Status Call(const AccessControl& access, const char* authorization, Role needed,
                  std::string* name = nullptr) {
  grpc::ServerContext context;
  grpc::testing::ServerContextTestSpouse spouse(&context);
  if (authorization != nullptr) spouse.AddClientMetadata("authorization", authorization);
  return access.Authorize(context, needed, "Models/Test", name);
}

std::string Bearer(const std::string& token) { return "Bearer " + token; }

class AccessControlAuthorizeTest : public AccessControlFileTest {
 protected:
  AccessControlAuthorizeTest() {
    access_ = AccessControl::FromFile(
        Write(TokenFileLine("ops", Role::kAdmin, kAdminToken) + "\n" +
              TokenFileLine("phone", Role::kRecognize, kRecognizeToken) + "\n"));
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

TEST_F(AccessControlAuthorizeTest, NamesTheGrantOfAnAuthorizedCaller) {
  std::string name = "stale";
  ASSERT_TRUE(Call(access_, Bearer(kRecognizeToken).c_str(), Role::kRecognize, &name).ok());
  EXPECT_EQ(name, "phone");
  ASSERT_TRUE(Call(access_, Bearer(kAdminToken).c_str(), Role::kAdmin, &name).ok());
  EXPECT_EQ(name, "ops");
  EXPECT_FALSE(Call(access_, "Bearer unknown-token-000000", Role::kRecognize, &name).ok());
  EXPECT_EQ(name, "");
}

TEST_F(AccessControlAuthorizeTest, AReloadHoldsAtTheNextCallAndNamesTheRevoked) {
  const std::string other_token = "other-token-0123456789";
  Write(TokenFileLine("ops", Role::kRecognize, kAdminToken) + "\n" +    // lessened
        TokenFileLine("phone", Role::kAdmin, kRecognizeToken) + "\n" +  // raised
        TokenFileLine("drone", Role::kRecognize, other_token) + "\n");  // new
  EXPECT_TRUE(access_.FileChanged());
  EXPECT_EQ(access_.Reload(), std::vector<std::string>{"ops"});
  EXPECT_FALSE(access_.FileChanged());
  EXPECT_EQ(Call(access_, Bearer(kAdminToken).c_str(), Role::kAdmin).error_code(),
            grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_TRUE(Call(access_, Bearer(kRecognizeToken).c_str(), Role::kAdmin).ok());
  EXPECT_TRUE(Call(access_, Bearer(other_token).c_str(), Role::kRecognize).ok());
  // A name that now holds another token is revoked too, as is a name that is gone.
  Write(TokenFileLine("phone", Role::kAdmin, "phone-token-rotated-0001") + "\n");
  const std::vector<std::string> revoked = access_.Reload();
  EXPECT_EQ(std::set<std::string>(revoked.begin(), revoked.end()),
            (std::set<std::string>{"ops", "phone", "drone"}));
  EXPECT_EQ(Call(access_, Bearer(kRecognizeToken).c_str(), Role::kRecognize).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_TRUE(Call(access_, "Bearer phone-token-rotated-0001", Role::kAdmin).ok());
}

TEST_F(AccessControlAuthorizeTest, ABadFileOnReloadKeepsTheGrantsInForce) {
  Write("phone recognize not-a-digest\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { access_.Reload(); }),
            At(1) + "expected the token's SHA-256 as 64 hex digits, or `certificate`");
  EXPECT_TRUE(Call(access_, Bearer(kAdminToken).c_str(), Role::kAdmin).ok());
  EXPECT_EQ(access_.token_count(), 2u);
}

TEST_F(AccessControlAuthorizeTest, RecordsEveryRefusedCallInTheAuditLog) {
  const std::filesystem::path log = dir_ / "audit.jsonl";
  {
    AuditLog audit(log.string());
    access_.AuditTo(&audit);
    EXPECT_FALSE(Call(access_, "Bearer unknown-token-000000", Role::kRecognize).ok());
    EXPECT_FALSE(Call(access_, Bearer(kRecognizeToken).c_str(), Role::kAdmin).ok());
    EXPECT_TRUE(Call(access_, Bearer(kAdminToken).c_str(), Role::kAdmin).ok());  // not recorded
    access_.AuditTo(nullptr);
  }
  std::ifstream in(log);
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0]["call"], "Models/Test");
  EXPECT_EQ(lines[0]["token"], "");
  EXPECT_EQ(lines[0]["outcome"], "UNAUTHENTICATED");
  EXPECT_EQ(lines[0]["message"], "unknown token");
  EXPECT_EQ(lines[1]["token"], "phone");
  EXPECT_EQ(lines[1]["outcome"], "PERMISSION_DENIED");
  EXPECT_EQ(std::filesystem::status(log).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
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
