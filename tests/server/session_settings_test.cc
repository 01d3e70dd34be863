// ResolveSessionSettings and the HMM memory rule (server/session_settings.h): what a session
// runs with, and every refusal with its status and the field it names.
#include "server/session_settings.h"

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

constexpr auto kLire = DescriptorVariant::kCeddLire;

grpc::Status Resolve(const v1::SessionOptions& requested, SessionSettings* out,
                     const ServerLimits& limits = {}) {
  return ResolveSessionSettings(requested, SessionSettings{}, kLire, limits, out);
}

TEST(SessionSettingsTest, UnsetFieldsKeepTheDefaultsAndSetOnesWin) {
  SessionSettings settings;
  ASSERT_TRUE(Resolve({}, &settings).ok());
  EXPECT_EQ(settings.engine, v1::ENGINE_HMM);
  EXPECT_EQ(settings.options.window, 8);
  EXPECT_EQ(settings.options.threshold, 2.0);

  v1::SessionOptions requested;
  requested.set_engine(v1::ENGINE_VCI);
  requested.set_top_k(3);
  requested.set_window(64);
  requested.set_orientation_weight(0);  // an explicit 0 is a value, not "unset"
  requested.set_list_length(6);
  requested.set_hmm_states(16);
  requested.set_threshold(0.5);
  requested.set_variant(v1::CEDD_LIRE);
  requested.set_rejection(v1::REJECTION_TH);
  requested.set_false_accept_rate(0.02);
  requested.set_known_accept_rate(0);  // an explicit 0 turns the known share off
  ASSERT_TRUE(Resolve(requested, &settings).ok());
  EXPECT_EQ(settings.options.rejection, RejectionRule::kTypicalDistance);
  EXPECT_EQ(settings.options.false_accept_rate, 0.02);
  EXPECT_EQ(settings.options.known_accept_rate, 0.0);
  EXPECT_EQ(settings.engine, v1::ENGINE_VCI);
  EXPECT_EQ(settings.options.top_k, 3);
  EXPECT_EQ(settings.options.window, 64);
  EXPECT_EQ(settings.options.orientation_weight, 0.0);
  EXPECT_EQ(settings.options.list_length, 6);
  EXPECT_EQ(settings.options.hmm_states, 16);
  EXPECT_EQ(settings.options.threshold, 0.5);
}

TEST(SessionSettingsTest, OutOfRangeValuesAreInvalidArgumentNamingTheField) {
  struct Case {
    void (*set)(v1::SessionOptions&);
    const char* message;
  };
  const Case cases[] = {
      {[](v1::SessionOptions& o) { o.set_engine(static_cast<v1::Engine>(42)); },
       "options.engine 42 is not an engine"},
      {[](v1::SessionOptions& o) { o.set_top_k(101); }, "options.top_k must be in 1..100, got 101"},
      {[](v1::SessionOptions& o) { o.set_window(-1); }, "options.window must be in 1..64, got -1"},
      // Beyond the API's range is a bad argument, whatever this server's limit.
      {[](v1::SessionOptions& o) { o.set_window(1000); },
       "options.window must be in 1..64, got 1000"},
      {[](v1::SessionOptions& o) { o.set_orientation_weight(-0.5); },
       "options.orientation_weight must be in [0, 1000], got -0.5"},
      // Found by fuzzing: a huge finite w made VCI's scores infinite or NaN.
      {[](v1::SessionOptions& o) { o.set_orientation_weight(9.998e307); },
       "options.orientation_weight must be in [0, 1000], got 9.998e+307"},
      {[](v1::SessionOptions& o) { o.set_list_length(65); },
       "options.list_length must be in 1..64, got 65"},
      {[](v1::SessionOptions& o) { o.set_hmm_states(361); },
       "options.hmm_states must be in 1..360, got 361"},
      {[](v1::SessionOptions& o) { o.set_threshold(0); },
       "options.threshold must be in (0, inf), got 0"},
      {[](v1::SessionOptions& o) { o.set_rejection(static_cast<v1::Rejection>(7)); },
       "options.rejection 7 is not a rule (REJECTION_TH = 1, REJECTION_CALIBRATED = 2)"},
      {[](v1::SessionOptions& o) { o.set_false_accept_rate(1); },
       "options.false_accept_rate must be in (0, 1), got 1"},
      {[](v1::SessionOptions& o) { o.set_false_accept_rate(0); },
       "options.false_accept_rate must be in (0, 1), got 0"},
      {[](v1::SessionOptions& o) { o.set_known_accept_rate(1); },
       "options.known_accept_rate must be in [0, 1), got 1"},
      {[](v1::SessionOptions& o) { o.set_known_accept_rate(-0.5); },
       "options.known_accept_rate must be in [0, 1), got -0.5"},
      {[](v1::SessionOptions& o) { o.set_variant(v1::CEDD_FULL); },
       "options.variant is cedd-full but this server's models are cedd-lire; variants cannot be "
       "mixed"},
  };
  for (const Case& c : cases) {
    v1::SessionOptions requested;
    c.set(requested);
    SessionSettings settings;
    settings.options.top_k = 77;  // untouched on refusal
    const grpc::Status status = Resolve(requested, &settings);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.message;
    EXPECT_EQ(status.error_message(), c.message);
    EXPECT_EQ(settings.options.top_k, 77);
  }
}

TEST(SessionSettingsTest, LimitsAreResourceExhausted) {
  ServerLimits limits;
  limits.max_window = 16;
  v1::SessionOptions requested;
  requested.set_window(17);
  SessionSettings settings;
  grpc::Status status = Resolve(requested, &settings, limits);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(status.error_message(), "options.window 17 is above this server's 16");

  // The HMM rule: 16 x 64 = 1024 is admitted, 16 x 65 is not; VCI does not keep an HMM.
  requested.set_window(16);
  requested.set_hmm_states(64);
  EXPECT_TRUE(Resolve(requested, &settings, limits).ok());
  requested.set_hmm_states(65);
  status = Resolve(requested, &settings, limits);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(status.error_message(),
            "options.window x options.hmm_states = 16 x 65 is above this server's 1024 (the HMM "
            "keeps window x states values per object)");
  requested.set_engine(v1::ENGINE_VCI_HMM);
  EXPECT_EQ(Resolve(requested, &settings, limits).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
  requested.set_engine(v1::ENGINE_VCI);
  EXPECT_TRUE(Resolve(requested, &settings, limits).ok());
}

TEST(SessionSettingsTest, CheckHmmCellsIsTheRuleForDefaultsToo) {
  SessionSettings settings;
  ServerLimits limits;
  limits.max_hmm_cells = 63;  // the defaults, 8 x 8, need 64
  EXPECT_EQ(CheckHmmCells(settings, limits).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  limits.max_hmm_cells = 64;
  EXPECT_TRUE(CheckHmmCells(settings, limits).ok());
  settings.engine = v1::ENGINE_EIS;
  limits.max_hmm_cells = 1;
  EXPECT_TRUE(CheckHmmCells(settings, limits).ok());
}

TEST(SessionSettingsTest, DescribeSettingsFillsEveryField) {
  SessionSettings settings;
  settings.engine = v1::ENGINE_VCI_HMM;
  settings.options.window = 12;
  const v1::SessionOptions described = DescribeSettings(settings, DescriptorVariant::kCeddFull);
  EXPECT_EQ(described.engine(), v1::ENGINE_VCI_HMM);
  EXPECT_EQ(described.window(), 12);
  EXPECT_EQ(described.top_k(), 5);
  EXPECT_EQ(described.orientation_weight(), 0.5);
  EXPECT_EQ(described.list_length(), 4);
  EXPECT_EQ(described.hmm_states(), 8);
  EXPECT_EQ(described.threshold(), 2.0);
  EXPECT_EQ(described.rejection(), v1::REJECTION_CALIBRATED);  // the product's
  EXPECT_EQ(described.false_accept_rate(), 0.15);
  EXPECT_EQ(described.known_accept_rate(), 0.95);
  EXPECT_EQ(described.variant(), v1::CEDD_FULL);
}

}  // namespace
}  // namespace orbit::server
