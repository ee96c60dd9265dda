#include "common/core/progress_line.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <string>

namespace fleetmap {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// A clock the test steps by hand: the throttling is checked without sleeping.
class ManualClock {
 public:
  ProgressLineOptions Options(bool terminal) {
    ProgressLineOptions options;
    options.terminal = terminal;
    options.now = [this] { return now_; };
    return options;
  }
  void Set(ProgressLine::Clock::duration since_start) {
    now_ = ProgressLine::Clock::time_point() + since_start;
  }

 private:
  ProgressLine::Clock::time_point now_;
};

TEST(ProgressLineTest, OnATerminalRewritesInPlaceAndBlanksWhatALongerTextLeft) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/true));
  line.Update("[tiles wire] 9 / 10 s");
  line.Update("[tiles wire] 10 / 10 s");
  line.Update("done");  // shorter: blanks over the 18 characters the previous text left
  line.Finish();
  EXPECT_EQ(out.str(),
            "\r[tiles wire] 9 / 10 s"
            "\r[tiles wire] 10 / 10 s"
            "\rdone                  \n");
}

TEST(ProgressLineTest, OnATerminalFinishWithATextEndsTheLineAndTheNextUpdateStartsANewOne) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/true));
  line.Update("scene 1/2");
  line.Finish("all done, 12 s");
  line.Update("x");  // a new line: nothing to blank
  EXPECT_EQ(out.str(), "\rscene 1/2\rall done, 12 s\n\rx");
}

TEST(ProgressLineTest, OnATerminalTheRedrawPeriodHoldsUpdatesBackUntilFinish) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLineOptions options = clock.Options(/*terminal=*/true);
  options.terminal_period = milliseconds(200);
  ProgressLine line(out, options);
  line.Update("a");
  clock.Set(milliseconds(100));
  line.Update("b");  // held back
  clock.Set(milliseconds(150));
  line.Update("c");  // held back, replacing b
  line.Finish();
  EXPECT_EQ(out.str(), "\ra\rc\n");
}

TEST(ProgressLineTest, InALogWritesWholeLinesAtMostOncePerPeriodFirstAndLastAlways) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/false));  // the default period: 10 s
  for (int s = 0; s <= 25; ++s) {
    clock.Set(seconds(s));
    line.Update(std::to_string(s) + " / 25 s");
  }
  line.Finish();
  // The first, one every 10 s after it, and the last held back; no '\r' anywhere.
  EXPECT_EQ(out.str(), "0 / 25 s\n10 / 25 s\n20 / 25 s\n25 / 25 s\n");
}

TEST(ProgressLineTest, InALogFinishWritesNothingTwice) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/false));
  line.Update("waiting: 0 / 2 s");
  line.Finish();  // the last update was written already
  EXPECT_EQ(out.str(), "waiting: 0 / 2 s\n");
}

TEST(ProgressLineTest, InALogFinishWithATextReplacesTheUpdateHeldBack) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/false));
  line.Update("1/3");
  clock.Set(seconds(1));
  line.Update("2/3");  // held back, then superseded by the final state
  clock.Set(seconds(2));
  line.Finish("3/3 done");
  EXPECT_EQ(out.str(), "1/3\n3/3 done\n");
}

TEST(ProgressLineTest, AMilestoneIsWrittenWhateverThePeriodAndRestartsIt) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/false));
  line.Update("extracting");
  clock.Set(seconds(1));
  line.Milestone("searching, iteration 1");
  clock.Set(seconds(10));
  line.Update("searching, iteration 9");  // 9 s after the milestone: held back
  clock.Set(seconds(11));
  line.Update("searching, iteration 10");
  EXPECT_EQ(out.str(), "extracting\nsearching, iteration 1\nsearching, iteration 10\n");
}

TEST(ProgressLineTest, InALogANewLineAfterFinishIsWrittenAtOnce) {
  ManualClock clock;
  std::ostringstream out;
  ProgressLine line(out, clock.Options(/*terminal=*/false));
  line.Update("run 1: 0 s");
  line.Finish();
  clock.Set(seconds(1));
  line.Update("run 2: 0 s");  // a new job's first update, within the old period
  EXPECT_EQ(out.str(), "run 1: 0 s\nrun 2: 0 s\n");
}

TEST(ProgressLineTest, AMessageAmidTheUpdatesGetsALineOfItsOwn) {
  ManualClock clock;
  std::ostringstream terminal;
  ProgressLine on_terminal(terminal, clock.Options(/*terminal=*/true));
  on_terminal.Update("5/40 pairs");
  on_terminal.Print("office overlap 0.7: no pair");
  on_terminal.Update("6/40");  // below the message, nothing to blank
  on_terminal.Finish();
  EXPECT_EQ(terminal.str(), "\r5/40 pairs\noffice overlap 0.7: no pair\n\r6/40\n");

  std::ostringstream log;
  ProgressLine in_log(log, clock.Options(/*terminal=*/false));
  in_log.Update("5/40 pairs");
  in_log.Print("office overlap 0.7: no pair");
  in_log.Update("6/40 pairs");  // within the period: held back
  in_log.Finish();
  EXPECT_EQ(log.str(), "5/40 pairs\noffice overlap 0.7: no pair\n6/40 pairs\n");
}

TEST(ProgressLineTest, TheDestructorEndsAnOpenTerminalLineButWritesNothingHeldBack) {
  ManualClock clock;
  std::ostringstream terminal;
  { ProgressLine(terminal, clock.Options(/*terminal=*/true)).Update("3 / 10 s"); }
  EXPECT_EQ(terminal.str(), "\r3 / 10 s\n");

  std::ostringstream log;
  {
    ProgressLine line(log, clock.Options(/*terminal=*/false));
    line.Update("3 / 10 s");
    clock.Set(seconds(1));
    line.Update("4 / 10 s");  // the job did not finish: its error says why, not this
  }
  EXPECT_EQ(log.str(), "3 / 10 s\n");
}

TEST(ProgressLineTest, AProgressTextOfTwoLinesIsABug) {
  std::ostringstream out;
  ProgressLine line(out, ProgressLineOptions{});
  EXPECT_DEATH(line.Update("a\nb"), "a progress text is one line");
  EXPECT_DEATH(line.Update("\ra"), "a progress text is one line");
}

}  // namespace
}  // namespace fleetmap
