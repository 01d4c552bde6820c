// Contrast you can test: every text and line colour of every theme's table, and every ink the
// themes make of a scene's colours, meets WCAG 2.1 against the background (4.5:1 text, 3:1 lines
// and marks). Computed from the theme tables, not from pictures.
#include "app/render/contrast.hpp"

#include <gtest/gtest.h>

#include "app/render/theme.hpp"

namespace formsim::app {
namespace {

constexpr ThemeId kThemes[] = {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint,
                               ThemeId::kHighContrast};

TEST(Contrast, RatiosFollowWcag) {
  EXPECT_NEAR(ContrastRatio({0, 0, 0, 1}, {1, 1, 1, 1}), 21.0, 1e-9);
  EXPECT_NEAR(ContrastRatio({1, 1, 1, 1}, {1, 1, 1, 1}), 1.0, 1e-9);
  // #767676 on white is the classic 4.54:1 grey.
  EXPECT_NEAR(ContrastRatio({118 / 255.f, 118 / 255.f, 118 / 255.f, 1}, {1, 1, 1, 1}), 4.54, 0.01);
  const sim::Color lifted = WithContrast({1.0f, 0.8f, 0.0f, 1}, {1, 1, 1, 1}, 4.5);
  EXPECT_GE(ContrastRatio(lifted, {1, 1, 1, 1}), 4.5);
  EXPECT_GT(lifted.r, lifted.b) << "the hue is kept";
}

TEST(Contrast, EveryThemeTableColourReadsOnItsBackground) {
  for (ThemeId id : kThemes) {
    const Theme& t = GetTheme(id);
    for (const ThemeInk& ink : ThemeInks()) {
      if (ink.use == InkUse::kDecoration) continue;
      const sim::Color seen = Over(t.*ink.member, t.background);
      const double need = ink.use == InkUse::kText ? kTextContrast : kLineContrast;
      EXPECT_GE(ContrastRatio(seen, t.background), need) << t.name << "." << ink.name;
    }
  }
}

TEST(Contrast, SceneInksReadOnEveryTheme) {
  // The palette, and the scene's own inks the issue found unreadable: the graph's purple, the
  // estimate's dark orange, the grey of link labels, black outlines and names.
  std::vector<sim::Color> colours = {{0.55f, 0.2f, 0.75f, 1}, {0.85f, 0.4f, 0.0f, 1},
                                     {0.25f, 0.25f, 0.25f, 0.9f}, {0.1f, 0.1f, 0.1f, 1},
                                     {0.9f, 0.45f, 0.0f, 1}, {1, 1, 1, 0.9f}};
  for (int i = 0; i < 10; ++i) colours.push_back(sim::PaletteColor(i));
  for (float r : {0.0f, 0.5f, 1.0f})
    for (float g : {0.0f, 0.5f, 1.0f})
      for (float b : {0.0f, 0.5f, 1.0f}) colours.push_back({r, g, b, 1});
  for (ThemeId id : kThemes) {
    const Theme& t = GetTheme(id);
    for (const sim::Color& c : colours) {
      const sim::Color line = t.Ink(c).WithAlpha(1.0f), text = t.TextInk(c);
      EXPECT_GE(ContrastRatio(line, t.background), kLineContrast)
          << t.name << " line ink of " << c.r << "," << c.g << "," << c.b;
      EXPECT_GE(ContrastRatio(text, t.background), kTextContrast)
          << t.name << " text ink of " << c.r << "," << c.g << "," << c.b;
      EXPECT_FLOAT_EQ(text.a, 1.0f) << "labels are opaque";
      EXPECT_FLOAT_EQ(t.Ink(c).a, c.a) << "lines keep their alpha (fades, ghosts)";
    }
  }
}

TEST(Contrast, HighContrastThickensLines) {
  EXPECT_GT(GetTheme(ThemeId::kHighContrast).line_scale, 1.0f);
  EXPECT_FLOAT_EQ(GetTheme(ThemeId::kLight).line_scale, 1.0f);
}

}  // namespace
}  // namespace formsim::app
