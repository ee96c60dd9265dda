// Exclusive ownership of the served topics over real DDS on loopback (docs/standby.md): a reader
// takes each instance from the strongest writer; a standby's samples refused while the stronger
// server lived reach the reader when the standby writes its served state again.

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <string>

#include "common/core/wake_up.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "tests/integration/loopback_participant.hpp"

namespace fleetmap {
namespace {

using std::chrono::milliseconds;

constexpr std::chrono::seconds kDeadline{20};

std::unique_ptr<transport::Participant> ServerParticipant(int domain, int32_t strength) {
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  options.ownership_strength = strength;
  auto participant = transport::Participant::Create(options);
  EXPECT_TRUE(participant.ok()) << participant.status();
  return participant.ok() ? std::move(participant).value() : nullptr;
}

transport::RobotFrameMessage Frame(const std::string& robot, double confidence) {
  transport::RobotFrameMessage frame;
  frame.robot = RobotId{robot};
  frame.state = transport::RobotFrameMessage::State::kPlaced;
  frame.confidence = confidence;
  frame.placed_against = "fleet";
  return frame;
}

class ServedStateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    domain_ = process::RandomDomainId();
    auto participant = testing::LoopbackParticipant(domain_);
    ASSERT_TRUE(participant.ok()) << participant.status();
    reader_participant_ = std::move(participant).value();
    auto reader = transport::RobotFrameReader::Create(*reader_participant_, wake_up_);
    ASSERT_TRUE(reader.ok()) << reader.status();
    reader_ = std::move(reader).value();
  }

  void TearDown() override {
    reader_.reset();
    reader_participant_.reset();
  }

  // Drains the reader for `how_long`, or until `done`; keeps each robot's newest confidence.
  void Follow(milliseconds how_long, const std::function<bool()>& done = nullptr) {
    const auto until = std::chrono::steady_clock::now() + how_long;
    while (std::chrono::steady_clock::now() < until) {
      wake_up_->WaitFor(milliseconds(50));
      for (const transport::RobotFrameEvent& event : reader_->Drain()) {
        if (event.kind == transport::RobotFrameEvent::Kind::kSample) {
          confidence_[event.message.robot.value] = event.message.confidence;
        }
      }
      if (done && done()) return;
    }
  }

  bool Holds(const std::string& robot, double confidence) const {
    const auto it = confidence_.find(robot);
    return it != confidence_.end() && it->second == confidence;
  }

  int domain_ = 0;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::Participant> reader_participant_;
  std::unique_ptr<transport::RobotFrameReader> reader_;
  std::map<std::string, double> confidence_;
};

TEST_F(ServedStateTest, TheReaderTakesTheStrongerServerAndGetsTheStandbysStateWhenItIsRewritten) {
  auto primary = ServerParticipant(domain_, 100);
  auto standby = ServerParticipant(domain_, 50);
  ASSERT_TRUE(primary && standby);
  auto primary_frames = transport::RobotFrameWriter::Create(*primary);
  auto standby_frames = transport::RobotFrameWriter::Create(*standby);
  ASSERT_TRUE(primary_frames.ok() && standby_frames.ok());

  ASSERT_TRUE((*primary_frames)->Write(Frame("alpha", 0.5)).ok());
  Follow(kDeadline, [&] { return Holds("alpha", 0.5); });
  ASSERT_TRUE(Holds("alpha", 0.5));
  // The standby's word on alpha is refused while the primary lives; on beta, which only it
  // wrote, it is taken.
  ASSERT_TRUE((*standby_frames)->Write(Frame("alpha", 0.25)).ok());
  ASSERT_TRUE((*standby_frames)->Write(Frame("beta", 0.75)).ok());
  Follow(kDeadline, [&] { return Holds("beta", 0.75); });
  ASSERT_TRUE(Holds("beta", 0.75));
  Follow(milliseconds(500));
  EXPECT_TRUE(Holds("alpha", 0.5)) << "the weaker writer's sample was taken";

  // The primary goes: the reader keeps its last word until the standby writes its state again.
  primary_frames->reset();
  Follow(milliseconds(1500));
  EXPECT_TRUE(Holds("alpha", 0.5));
  EXPECT_EQ(standby->RepublishServedState(), 2u);
  Follow(kDeadline, [&] { return Holds("alpha", 0.25); });
  EXPECT_TRUE(Holds("alpha", 0.25));
}

TEST_F(ServedStateTest, ADisposalIsWrittenAgainToo) {
  auto standby = ServerParticipant(domain_, 50);
  ASSERT_TRUE(standby);
  auto frames = transport::RobotFrameWriter::Create(*standby);
  ASSERT_TRUE(frames.ok());
  ASSERT_TRUE((*frames)->Write(Frame("alpha", 0.5)).ok());
  ASSERT_TRUE((*frames)->Write(Frame("beta", 0.5)).ok());
  ASSERT_TRUE((*frames)->Dispose(Frame("beta", 0.0)).ok());
  // alpha's sample and beta's disposal: two instances written again.
  EXPECT_EQ(standby->RepublishServedState(), 2u);
}

}  // namespace
}  // namespace fleetmap
