// EngineOptions: options outside their ranges are refused with one message naming the option
// and the range.
#include "core/engines/engine_options.h"

#include <string>

#include <gtest/gtest.h>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

// The message ValidateEngineOptions gives for the default options changed by `change`.
std::string MessageFor(void (*change)(EngineOptions&)) {
  return testing::ErrorMessageOf([change] {
    EngineOptions options;
    change(options);
    ValidateEngineOptions(options);
  });
}

TEST(EngineOptionsTest, TheRulesRatesAreRefusedOutsideTheirRanges) {
  EXPECT_EQ(MessageFor([](EngineOptions& o) { o.known_accept_rate = 1; }),
            "engine option known_accept_rate must be in [0, 1), got 1");
  EXPECT_EQ(MessageFor([](EngineOptions& o) { o.known_accept_rate = -0.1; }),
            "engine option known_accept_rate must be in [0, 1), got -0.1");
  EXPECT_EQ(MessageFor([](EngineOptions& o) { o.false_accept_rate = 0; }),
            "engine option false_accept_rate must be in (0, 1), got 0");
  // 0 turns the known share off; the defaults are valid.
  EngineOptions options;
  EXPECT_NO_THROW(ValidateEngineOptions(options));
  options.known_accept_rate = 0;
  EXPECT_NO_THROW(ValidateEngineOptions(options));
}

TEST(EngineOptionsTest, CandidateOptionsOutsideTheirRangesAreRefused) {
  EXPECT_EQ(MessageFor([](EngineOptions& o) { o.candidate_objects = kMaxCandidateObjects + 1; }),
            "engine option candidate_objects must be in 0..4096, got 4097");
  EXPECT_EQ(MessageFor([](EngineOptions& o) { o.candidate_objects = -1; }),
            "engine option candidate_objects must be in 0..4096, got -1");
  EXPECT_EQ(MessageFor([](EngineOptions& o) { o.candidates_above = -1; }),
            "engine option candidates_above must be in 0..1000000000, got -1");
}

}  // namespace
}  // namespace orbit
