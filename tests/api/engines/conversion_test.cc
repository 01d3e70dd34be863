// What the engines answer, on the wire (api/engines/conversion.h), with hand-built values.
#include "api/engines/conversion.h"

#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(EngineConversionTest, DecisionsAndMoves) {
  EXPECT_EQ(ToProtoDecision(Decision::kAccept), v1::DECISION_ACCEPT);
  EXPECT_EQ(ToProtoDecision(Decision::kUnknown), v1::DECISION_UNKNOWN);
  EXPECT_EQ(ToProtoDecision(Decision::kUndecided), v1::DECISION_UNDECIDED);
  for (const Decision decision : {Decision::kAccept, Decision::kUnknown, Decision::kUndecided}) {
    EXPECT_EQ(FromProtoDecision(ToProtoDecision(decision)), decision);
  }
  // An update that states no decision is no answer.
  EXPECT_EQ(FromProtoDecision(v1::DECISION_UNSPECIFIED), Decision::kUndecided);
  EXPECT_EQ(ToProtoMove(SuggestedMove::kNone), v1::MOVE_NONE);
  EXPECT_EQ(ToProtoMove(SuggestedMove::kLeft), v1::MOVE_LEFT);
  EXPECT_EQ(ToProtoMove(SuggestedMove::kRight), v1::MOVE_RIGHT);
}

TEST(EngineConversionTest, SessionUpdateNamesCandidatesFromTheSnapshot) {
  ObjectModel mug;
  mug.id = 4;
  mug.name = "mug";
  mug.views.push_back({});
  ViewIndex index(std::vector<ObjectModel>{mug});
  FrameUpdate update;
  update.frame_index = 12;
  update.ranking = {{4, 0.75}, {9, 0.5}};  // object 9 was deleted meanwhile: no name
  update.decision = Decision::kAccept;
  update.move = SuggestedMove::kLeft;
  const v1::SessionUpdate wire = ToSessionUpdate(update, *index.Snapshot());
  EXPECT_EQ(wire.frame_index(), 12);
  ASSERT_EQ(wire.candidates_size(), 2);
  EXPECT_EQ(wire.candidates(0).id(), 4);
  EXPECT_EQ(wire.candidates(0).name(), "mug");
  EXPECT_EQ(wire.candidates(0).score(), 0.75);
  EXPECT_EQ(wire.candidates(1).id(), 9);
  EXPECT_EQ(wire.candidates(1).name(), "");
  EXPECT_EQ(wire.decision(), v1::DECISION_ACCEPT);
  EXPECT_EQ(wire.move(), v1::MOVE_LEFT);
}

}  // namespace
}  // namespace orbit
