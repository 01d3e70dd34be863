// The rules `orbit serve` checks before it opens anything (server/server_config.h).
#include "server/server_config.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

TEST(ServerConfigTest, DefaultsAreValidAndAnHmmAboveTheCellLimitIsRefused) {
  ServerConfig config;
  EXPECT_NO_THROW(ValidateServerConfig(config));
  config.session_defaults.options.hmm_states = 200;  // 8 x 200 = 1600 > 1024
  try {
    ValidateServerConfig(config);
    ADD_FAILURE() << "accepted 8 x 200";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "the default session (window 8 x 200 HMM states) is above --max-hmm-cells 1024");
  }
  config.limits.max_hmm_cells = 1600;
  EXPECT_NO_THROW(ValidateServerConfig(config));
  config.session_defaults.options.hmm_states = 200;
  config.session_defaults.engine = v1::ENGINE_VCI;
  config.limits.max_hmm_cells = 1;
  EXPECT_NO_THROW(ValidateServerConfig(config));
  config.session_defaults.options.threshold = -1;
  EXPECT_THROW(ValidateServerConfig(config), std::invalid_argument);
}

TEST(ServerConfigTest, LoopbackAddresses) {
  for (const char* address :
       {"127.0.0.1:50051", "127.8.9.10:1", "localhost:80", "[::1]:50051", "::1"}) {
    EXPECT_TRUE(IsLoopbackAddress(address)) << address;
  }
  for (const char* address : {"0.0.0.0:50051", "10.0.0.1:50051", "[::]:50051", "example.com:443",
                              "128.0.0.1:1", "127.example.com:443", "127.0.0.1.nip.io:50051"}) {
    EXPECT_FALSE(IsLoopbackAddress(address)) << address;
  }
}

TEST(ServerConfigTest, DescribeNamesEngineAndLimits) {
  ServerConfig config;
  config.session_defaults.engine = v1::ENGINE_VCI_HMM;
  const std::string text = config.Describe();
  EXPECT_NE(text.find("session defaults    engine vci-hmm, top-k 5, window 8"), std::string::npos)
      << text;
  EXPECT_NE(text.find("HMM window x states <= 1024"), std::string::npos) << text;
  EXPECT_NE(text.find("access control      none (loopback only)"), std::string::npos) << text;
}

TEST(ServerConfigTest, TheCandidatesThresholdIsTheVariantsUnlessGivenAndGivenOnlyInRange) {
  ServerConfig config;
  EXPECT_NE(config.Describe().find("candidates          8 objects a frame, proposed by the index, "
                                   "above the variant's (500 with appearance channels, 5000 "
                                   "without) objects\n"),
            std::string::npos)
      << config.Describe();
  config.variant = DescriptorVariant::kCeddRobust;
  EXPECT_NE(config.Describe().find("proposed by the index, above 5000 objects\n"),
            std::string::npos)
      << config.Describe();

  config.candidates_above = 0;
  EXPECT_NE(config.Describe().find("proposed by the index, above 0 objects\n"), std::string::npos)
      << config.Describe();
  EXPECT_NO_THROW(ValidateServerConfig(config));
  config.candidates_above = -1;
  try {
    ValidateServerConfig(config);
    ADD_FAILURE() << "accepted -1";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "engine option candidates_above must be in 0..1000000000, got -1");
  }
}

TEST(ServerConfigTest, TheTargetRateIsTheVariantsUnlessGivenAndGivenOnlyInRange) {
  ServerConfig config;
  EXPECT_NE(config.Describe().find("rejection calibrated (false-accept rate the variant's: 0.15, "
                                   "0.09 on cedd-hsv-layout, known-accept rate 0.95)\n"),
            std::string::npos)
      << config.Describe();
  config.variant = DescriptorVariant::kCeddHsvLayout;
  EXPECT_NE(config.Describe().find("(false-accept rate 0.09, known-accept rate"), std::string::npos)
      << config.Describe();
  config.false_accept_rate = 0.2;
  EXPECT_NE(config.Describe().find("(false-accept rate 0.2, known-accept rate"), std::string::npos)
      << config.Describe();
  EXPECT_NO_THROW(ValidateServerConfig(config));
  config.false_accept_rate = 1;
  try {
    ValidateServerConfig(config);
    ADD_FAILURE() << "accepted 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "engine option false_accept_rate must be in (0, 1), got 1");
  }
}

TEST(ServerConfigTest, TheStoreIsNamedWithoutItsPasswordAndAMalformedOneIsRefused) {
  ServerConfig config;
  config.database = "/var/lib/orbit/models.db";
  EXPECT_NE(config.Describe().find("model store         SQLite /var/lib/orbit/models.db\n"),
            std::string::npos)
      << config.Describe();

  config.store = "postgresql://orbit:s3cret@db.example/models";
  EXPECT_NO_THROW(ValidateServerConfig(config));
  const std::string text = config.Describe();
  EXPECT_NE(text.find("model store         PostgreSQL user=orbit dbname=models host=db.example\n"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("s3cret"), std::string::npos) << text;

  config.store = "host=db.example dbname";
  try {
    ValidateServerConfig(config);
    ADD_FAILURE() << "accepted a malformed connection string";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--store: invalid PostgreSQL connection string", 0), 0u)
        << e.what();
  }
}

}  // namespace
}  // namespace orbit::server
