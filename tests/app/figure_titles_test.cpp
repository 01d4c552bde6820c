// `--titles full|short|none`: the panel letter belongs to the full title only; short drops it
// and a closing parenthesis of detail; bad values are refused naming the flag.
#include "app/export/figure_titles.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace formsim::app {
namespace {

TEST(FigureTitles, FullShortAndNone) {
  const std::string t = "(f) Estimation error φ_est − φ with ±2σ (UKF)";
  EXPECT_EQ(TitleFor(t, TitleMode::kFull), t);
  EXPECT_EQ(TitleFor(t, TitleMode::kShort), "Estimation error φ_est − φ with ±2σ");
  EXPECT_EQ(TitleFor(t, TitleMode::kNone), "");
  EXPECT_EQ(TitleFor("(b) Bearing error e_φ = φ_des − φ", TitleMode::kShort),
            "Bearing error e_φ = φ_des − φ");
  EXPECT_EQ(TitleFor("Fig. 9: Y on the first straight", TitleMode::kShort),
            "Y on the first straight");
  // Nothing to drop: as it is; a title that is only a parenthesis keeps it.
  EXPECT_EQ(TitleFor("Trajectories (true)", TitleMode::kShort), "Trajectories");
  EXPECT_EQ(TitleFor("(true)", TitleMode::kShort), "(true)");
  EXPECT_EQ(TitleFor("Route and trajectories", TitleMode::kShort), "Route and trajectories");
}

TEST(FigureTitles, BadValueNamesTheFlagAndTheChoices) {
  EXPECT_EQ(ParseTitleMode("short"), TitleMode::kShort);
  try {
    ParseTitleMode("long", "--titles");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--titles 'long'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("full|short|none"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace formsim::app
