// Figure label markup (app/render/label_markup.hpp): Greek names, sub- and superscripts drawn
// as Unicode where the font atlas has them, never a brace or a backslash in what is drawn.
#include "app/render/label_markup.hpp"

#include <gtest/gtest.h>

namespace formsim::app {
namespace {

TEST(LabelMarkup, GreekAndScripts) {
  EXPECT_EQ(MarkupText("max|e_{\\phi}| [rad]"), "max|e_φ| [rad]");  // no subscript φ in the atlas
  EXPECT_EQ(MarkupText("e_{l} [m]"), "eₗ [m]");
  EXPECT_EQ(MarkupText("\\sigma^{2}"), "σ²");
  EXPECT_EQ(MarkupText("\\Delta \\omega_{c}, {1}"), "Δ ω_c, {1}");
  EXPECT_EQ(MarkupText("x_{12}"), "x₁₂");
}

TEST(LabelMarkup, PlainTextAndUnknownNamesStay) {
  EXPECT_EQ(MarkupText("time [s]"), "time [s]");
  EXPECT_EQ(MarkupText("links.R1-R2.max_abs_error.phi"), "links.R1-R2.max_abs_error.phi");
  EXPECT_EQ(MarkupText("\\unknown x"), "\\unknown x");
  EXPECT_EQ(MarkupText("a_{unclosed"), "a_{unclosed");
}

}  // namespace
}  // namespace formsim::app
