// Figure label markup (app/render/label_markup.hpp): one parser into runs (normal, sub, super)
// for every backend; Greek names; escapes; errors for what it does not know; the Unicode form
// drawn in the window and PNGs never shows a brace or a backslash.
#include "app/render/label_markup.hpp"

#include <gtest/gtest.h>

namespace formsim::app {
namespace {

// The runs of a parse as "text|_sub|^super" (kinds marked), for compact expectations.
std::string Runs(const std::vector<MarkupRun>& runs) {
  std::string out;
  for (const MarkupRun& r : runs) {
    if (!out.empty()) out += "|";
    out += (r.kind == ScriptKind::kSub ? "_" : r.kind == ScriptKind::kSuper ? "^" : "") + r.text;
  }
  return out;
}
std::string Runs(const std::string& label) {
  return Runs(ParseMarkup(label).runs);
}

TEST(LabelMarkup, ParsesIntoRuns) {
  EXPECT_EQ(Runs("e_{l} [m]"), "e|_l| [m]");
  EXPECT_EQ(Runs("\\sigma^{2}"), "σ|^2");
  EXPECT_EQ(Runs("φ_{est} − φ"), "φ|_est| − φ");
  EXPECT_EQ(Runs("max|e_{\\phi}| [rad]"), "max|e|_φ|| [rad]");
  EXPECT_EQ(Runs("x_{a}^{2}"), "x|_a|^2");
  EXPECT_EQ(Runs("x_{1}_{2}"), "x|_12");  // adjacent runs of a kind merge
  EXPECT_EQ(Runs(""), "");
  EXPECT_TRUE(ParseMarkup("e_{l}").error.empty());
}

TEST(LabelMarkup, NestedBracesGroupInsideAScript) {
  EXPECT_EQ(Runs("x_{a{b}c}"), "x|_abc");
  EXPECT_EQ(Runs("x_{a_{b}}"), "x|_ab");  // one level of scripts: the inner one is flattened
  EXPECT_EQ(Runs("x^{\\{n\\}}"), "x|^{n}");
  EXPECT_TRUE(ParseMarkup("x_{a{b}c}").error.empty());
  // Braces outside a script are text.
  EXPECT_EQ(Runs("{1}"), "{1}");
}

TEST(LabelMarkup, LoneUnderscoreAndCaretAreThemselves) {
  EXPECT_EQ(Runs("max_abs_error"), "max_abs_error");
  EXPECT_EQ(Runs("a_b ^c _"), "a_b ^c _");
  EXPECT_TRUE(ParseMarkup("links.R1-R2.max_abs_error.phi").error.empty());
}

TEST(LabelMarkup, EscapesAreTheCharacters) {
  EXPECT_EQ(Runs("a\\\\b"), "a\\b");
  EXPECT_EQ(Runs("\\_{x}"), "_{x}");
  EXPECT_EQ(Runs("\\^\\{\\}"), "^{}");
  EXPECT_TRUE(ParseMarkup("a\\\\b").error.empty());
}

TEST(LabelMarkup, UnknownCommandIsAnErrorListingWhatIsAccepted) {
  const ParsedMarkup p = ParseMarkup("e_{\\phii} x");
  EXPECT_EQ(p.error, "unknown markup command '\\phii'");
  EXPECT_EQ(Runs("\\foo x"), "\\foo x");  // drawn as written, never a crash
  const std::string e = MarkupError("gain \\kappaa");
  EXPECT_NE(e.find("unknown markup command '\\kappaa' in 'gain \\kappaa'"), std::string::npos) << e;
  EXPECT_NE(e.find("\\kappa"), std::string::npos) << e;
  EXPECT_NE(e.find("x_{sub}"), std::string::npos) << e;
  EXPECT_EQ(MarkupError("e_{\\kappa}"), "");
  // A lone backslash and an unclosed group are errors too.
  EXPECT_NE(ParseMarkup("a \\").error.find("lone '\\'"), std::string::npos);
  EXPECT_NE(ParseMarkup("a \\1").error.find("lone '\\'"), std::string::npos);
  EXPECT_NE(ParseMarkup("a_{unclosed").error.find("without its closing"), std::string::npos);
  EXPECT_EQ(Runs("a_{unclosed"), "a_{unclosed");
}

TEST(LabelMarkup, EscapedTextDrawsItself) {
  for (const std::string s : {"R_1", "a\\b", "x_{y}", "^{2}", "{}", "plain", "\\phi"}) {
    const std::string m = EscapeMarkup(s);
    EXPECT_EQ(ParseMarkup(m).error, "") << m;
    ASSERT_EQ(ParseMarkup(m).runs.size(), 1u) << m;
    EXPECT_EQ(ParseMarkup(m).runs[0].kind, ScriptKind::kNormal) << m;
    EXPECT_EQ(ParseMarkup(m).runs[0].text, s) << m;
  }
}

TEST(LabelMarkup, AtlasRunsUseUnicodeScriptsWhereEveryCharacterHasOne) {
  EXPECT_EQ(Runs(AtlasRuns("e_{l} [m]")), "eₗ [m]");
  EXPECT_EQ(Runs(AtlasRuns("φ_{est} − φ_{des}")), "φₑₛₜ − φ|_des");
  EXPECT_EQ(Runs(AtlasRuns("e_{\\phi}, \\sigma^{2}")), "e|_φ|, σ²");
  EXPECT_EQ(PlacementOf(ScriptKind::kNormal).scale, 1.0f);
  EXPECT_LT(PlacementOf(ScriptKind::kSub).scale, 1.0f);
  EXPECT_GT(PlacementOf(ScriptKind::kSub).shift_em, 0.0f);    // down
  EXPECT_LT(PlacementOf(ScriptKind::kSuper).shift_em, 0.0f);  // up
}

TEST(LabelMarkup, ShortenedMarkupCutsTheDrawnTextKeepingScripts) {
  EXPECT_EQ(ShortenMarkup("e_{l} R1-R2", 80), "e_{l} R1-R2");
  EXPECT_EQ(ShortenMarkup("φ_{est} − φ", 4), "φ_{es}…");  // φ is 2 bytes
  EXPECT_EQ(ShortenMarkup("φ_{est} − φ", 1), "…");        // never half a character
  EXPECT_EQ(ShortenMarkup("a\\\\b_c and more", 4), "a\\\\b\\_…");
  EXPECT_EQ(RunsMarkup(ParseMarkup("x^{2}_{i} \\{").runs), "x^{2}_{i} \\{");
}

TEST(LabelMarkup, PlainTextHasNoMarkers) {
  EXPECT_EQ(PlainText("(c) Distance errors e_{l} = l_{des} − l"),
            "(c) Distance errors eₗ = ldes − l");
  EXPECT_EQ(PlainText("max_abs_error"), "max_abs_error");
}

TEST(LabelMarkup, UnicodeFormForTheAtlas) {
  EXPECT_EQ(MarkupText("max|e_{\\phi}| [rad]"), "max|e_φ| [rad]");  // no subscript φ in the atlas
  EXPECT_EQ(MarkupText("e_{l} [m]"), "eₗ [m]");
  EXPECT_EQ(MarkupText("\\sigma^{2}"), "σ²");
  EXPECT_EQ(MarkupText("\\Delta \\omega_{c}, {1}"), "Δ ω_c, {1}");
  EXPECT_EQ(MarkupText("x_{12}"), "x₁₂");
  EXPECT_EQ(MarkupText("a\\\\b"), "a\\b");
  EXPECT_EQ(MarkupText("time [s]"), "time [s]");
  EXPECT_EQ(MarkupText("links.R1-R2.max_abs_error.phi"), "links.R1-R2.max_abs_error.phi");
  EXPECT_EQ(MarkupText("\\unknown x"), "\\unknown x");
  EXPECT_EQ(MarkupText("a_{unclosed"), "a_{unclosed");
}

}  // namespace
}  // namespace formsim::app
