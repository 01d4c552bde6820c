#include "app/render/vector_fonts.hpp"

#ifndef __EMSCRIPTEN__
#include <cairo-ft.h>
#include <cairo.h>
#endif
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_TRUETYPE_TABLES_H

#include <cmath>
#include <mutex>
#include <stdexcept>

#include "sim/scenario/asset_dirs.hpp"

namespace formsim::app {
namespace {

constexpr unsigned kCodes = 0x2600;  // past the last range of FontGlyphRanges()

// One FreeType library for the process: faces are created once, under the call_once below,
// and Cairo locks a face whenever it uses one, so nothing here races.
FT_Library Library() {
  static FT_Library lib = [] {
    FT_Library l = nullptr;
    if (FT_Init_FreeType(&l) != 0) throw std::runtime_error("FreeType failed to initialise");
    return l;
  }();
  return lib;
}

#ifndef __EMSCRIPTEN__
void DoneFace(void* face) {
  FT_Done_Face(static_cast<FT_Face>(face));
}
#endif

int FaceIndex(FontRole role) {
  if (role == FontRole::kMono) return 2;
  return FontSpecOf(role).bold ? 1 : 0;
}

// Decodes one UTF-8 code point starting at s[i] (ImGui's rules: a bad byte is U+FFFD).
unsigned NextCodePoint(const std::string& s, std::size_t& i) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  int n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
  if (n == 0 || i + n > s.size()) {
    ++i;
    return 0xFFFD;
  }
  unsigned cp = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
  for (int k = 1; k < n; ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
  i += n;
  return cp;
}

}  // namespace

// Never destroyed: Cairo may hold the faces in its caches until the process ends.
const VectorFonts& VectorFonts::Get() {
  static VectorFonts* fonts = nullptr;
  static std::once_flag once;
  std::call_once(once, [] { fonts = new VectorFonts(); });
  return *fonts;
}

VectorFonts::VectorFonts() {
  const std::string regular = FindFont(FontSpecOf(FontRole::kUi).file);
  if (regular.empty())
    throw std::runtime_error(
        "SVG and PDF figures need the font DejaVuSans.ttf (Debian: fonts-dejavu-core), which "
        "was not found in " + sim::AssetDir("fonts") + " or /usr/share/fonts/truetype/dejavu");
  for (FontRole role : {FontRole::kUi, FontRole::kTitle, FontRole::kMono}) {
    Face f;
    f.path = FindFont(FontSpecOf(role).file);
    if (f.path.empty()) f.path = regular;
    FT_Face face = nullptr;
    if (FT_New_Face(Library(), f.path.c_str(), 0, &face) != 0)
      throw std::runtime_error("cannot read the font " + f.path);
    const auto* hhea = static_cast<const TT_HoriHeader*>(FT_Get_Sfnt_Table(face, FT_SFNT_HHEA));
    f.units_per_em = face->units_per_EM;
    // stb_truetype (ImGui) sizes fonts by the hhea ascent and descent.
    f.ascent = hhea != nullptr ? hhea->Ascender : face->ascender;
    f.descent = hhea != nullptr ? hhea->Descender : face->descender;
    f.advance.assign(kCodes, -1.0f);
    for (const unsigned short* r = FontGlyphRanges(); r[0] != 0; r += 2)
      for (unsigned cp = r[0]; cp <= r[1] && cp < kCodes; ++cp) {
        const FT_UInt glyph = FT_Get_Char_Index(face, cp);
        if (glyph == 0 || FT_Load_Glyph(face, glyph, FT_LOAD_NO_SCALE) != 0) continue;
        f.advance[cp] = static_cast<float>(face->glyph->metrics.horiAdvance);
      }
    f.fallback = f.advance['?'] >= 0 ? f.advance['?'] : 0.0f;
#ifdef __EMSCRIPTEN__
    // The browser page writes SVG only (no Cairo, no PDF): the metrics are all it needs.
    FT_Done_Face(face);
#else
    // Cairo owns the FreeType face from here and frees it with its font face.
    f.cairo = cairo_ft_font_face_create_for_ft_face(face, FT_LOAD_NO_HINTING);
    static cairo_user_data_key_t key;
    if (cairo_font_face_set_user_data(f.cairo, &key, face, DoneFace) != CAIRO_STATUS_SUCCESS) {
      cairo_font_face_destroy(f.cairo);
      FT_Done_Face(face);
      throw std::runtime_error("cairo: cannot use the font " + f.path);
    }
#endif
    faces_.push_back(std::move(f));
  }
}

const VectorFonts::Face& VectorFonts::FaceOf(FontRole role) const {
  return faces_[FaceIndex(role)];
}

float VectorFonts::Width(FontRole role, const std::string& text) const {
  const Face& f = FaceOf(role);
  double units = 0;
  for (std::size_t i = 0; i < text.size();) {
    const unsigned cp = NextCodePoint(text, i);
    if (cp == '\n' || cp == '\r') continue;
    const float a = cp < kCodes ? f.advance[cp] : -1.0f;
    units += a >= 0 ? a : f.fallback;
  }
  return static_cast<float>(units * FontSpecOf(role).pixels / (f.ascent - f.descent));
}

float VectorFonts::Baseline(FontRole role) const {
  const Face& f = FaceOf(role);
  const double ascent_px = f.ascent * FontSpecOf(role).pixels / (f.ascent - f.descent);
  return static_cast<float>(std::floor(ascent_px + 1.0));
}

float VectorFonts::EmSize(FontRole role) const {
  const Face& f = FaceOf(role);
  return static_cast<float>(FontSpecOf(role).pixels * f.units_per_em / (f.ascent - f.descent));
}

cairo_font_face_t* VectorFonts::CairoFace(FontRole role) const {
  return FaceOf(role).cairo;
}

}  // namespace formsim::app
