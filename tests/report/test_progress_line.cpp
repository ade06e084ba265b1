// ProgressLine: drawn in place on a terminal, silent on anything else and when
// disabled; notes are permanent lines, the line redrawn under them; the time
// left is the pace so far.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "talus/report/progress_line.hpp"

namespace talus {
namespace {

TEST(ProgressLine, OnATerminalTheLineIsRewrittenInPlaceAndClearedAtTheEnd) {
  std::ostringstream out;
  {
    ProgressLine line("talus plan", true, out, true);
    EXPECT_TRUE(line.drawn());
    line.update("global search");
    line.update("local optimisation, candidate 1 of 3", 0, 3);
  }
  const std::string s = out.str();
  EXPECT_EQ(s.rfind("\rtalus plan: global search, 0.0 s\033[K", 0), 0u) << s;
  EXPECT_NE(s.find("\rtalus plan: local optimisation, candidate 1 of 3, 0.0 s\033[K"),
            std::string::npos)
      << s;
  EXPECT_EQ(s.substr(s.size() - 4), "\r\033[K") << "cleared when it goes";
  EXPECT_EQ(s.find('\n'), std::string::npos) << "no new line of its own";
}

TEST(ProgressLine, ASameStatusIsRedrawnAtMostTenTimesASecond) {
  std::ostringstream out;
  ProgressLine line("x", true, out, true);
  for (int k = 0; k < 1000; ++k) line.update("busy");
  std::size_t draws = 0;
  for (const char c : out.str()) draws += c == '\r' ? 1 : 0;
  EXPECT_LE(draws, 2u);
}

TEST(ProgressLine, NotAtTerminalOrQuietOnlyNotesOrNothing) {
  std::ostringstream pipe, quiet;
  {
    ProgressLine line("sweep", true, pipe, false);
    EXPECT_FALSE(line.drawn());
    line.update("3/10 done", 3, 10);
    line.note("case 3 done");
  }
  EXPECT_EQ(pipe.str(), "case 3 done\n");
  {
    ProgressLine line("sweep", false, quiet, true);
    line.update("3/10 done", 3, 10);
    line.note("case 3 done");
  }
  EXPECT_EQ(quiet.str(), "");
}

TEST(ProgressLine, ANoteOnATerminalIsPrintedAboveTheLineWhichIsRedrawn) {
  std::ostringstream out;
  ProgressLine line("exp", true, out, true);
  line.update("case 1 of 2", 0, 2);
  const std::string drawn = out.str().substr(1, out.str().size() - 4);  // without \r and \033[K
  line.note("case 1: ok");
  EXPECT_EQ(out.str().substr(out.str().size() - drawn.size() - 11 - 4),
            "\r\033[Kcase 1: ok\n" + drawn);
}

TEST(ProgressLine, TheTimeLeftIsThePaceSoFar) {
  std::ostringstream out;
  const ProgressLine line("exp", true, out, true);
  EXPECT_EQ(line.text("start", 0, 4).find("left"), std::string::npos);
  EXPECT_NE(line.text("half", 2, 4).find(", about "), std::string::npos);
  EXPECT_EQ(line.text("all", 4, 4).find("left"), std::string::npos);
}

}  // namespace
}  // namespace talus
