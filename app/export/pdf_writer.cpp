#include "app/export/pdf_writer.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "app/render/label_markup.hpp"
#include "app/render/vector_fonts.hpp"
#include "sim/core/run_output.hpp"

namespace formsim::app {
namespace {

constexpr const char* kPdfCreationDate = "2000-01-01T00:00:00Z";

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void SetColor(cairo_t* cr, sim::Color c) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a);
}

void RectPath(cairo_t* cr, ImVec2 a, ImVec2 b, float r) {
  const double w = std::fmax(0.f, b.x - a.x), h = std::fmax(0.f, b.y - a.y);
  r = std::fmin(r, static_cast<float>(0.5 * std::fmin(w, h)));
  if (r <= 0) {
    cairo_rectangle(cr, a.x, a.y, w, h);
    return;
  }
  cairo_new_sub_path(cr);
  cairo_arc(cr, a.x + w - r, a.y + r, r, -M_PI / 2, 0);
  cairo_arc(cr, a.x + w - r, a.y + h - r, r, 0, M_PI / 2);
  cairo_arc(cr, a.x + r, a.y + h - r, r, M_PI / 2, M_PI);
  cairo_arc(cr, a.x + r, a.y + r, r, M_PI, 3 * M_PI / 2);
  cairo_close_path(cr);
}

// A text op from its baseline start: plain text at once, markup run by run (scripts smaller,
// on a shifted baseline, each run starting where the one before ended).
void ShowText(cairo_t* cr, const VectorOp& op, float em) {
  if (!op.markup) {
    cairo_set_font_size(cr, em);
    cairo_move_to(cr, op.pts[0].x, op.pts[0].y);
    cairo_show_text(cr, op.text.c_str());
    return;
  }
  double x = op.pts[0].x, y_end = 0;
  for (const MarkupRun& run : ParseMarkup(op.text).runs) {
    const RunPlacement place = PlacementOf(run.kind);
    cairo_set_font_size(cr, place.scale * em);
    cairo_move_to(cr, x, op.pts[0].y + place.shift_em * em);
    cairo_show_text(cr, run.text.c_str());
    cairo_get_current_point(cr, &x, &y_end);
  }
}

void Draw(cairo_t* cr, const VectorFigure& fig) {
  const VectorFonts& fonts = VectorFonts::Get();
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  for (const VectorOp& op : fig.ops) {
    switch (op.kind) {
      case VectorOp::Kind::kFillRect:
        RectPath(cr, op.pts[0], op.pts[1], op.size);
        SetColor(cr, op.color);
        cairo_fill(cr);
        break;
      case VectorOp::Kind::kStrokeRect: {
        const float in = 0.5f * op.width;
        RectPath(cr, ImVec2(op.pts[0].x + in, op.pts[0].y + in),
                 ImVec2(op.pts[1].x - in, op.pts[1].y - in), op.size);
        SetColor(cr, op.color);
        cairo_set_line_width(cr, op.width);
        cairo_set_dash(cr, nullptr, 0, 0);
        cairo_stroke(cr);
        break;
      }
      case VectorOp::Kind::kPath:
      case VectorOp::Kind::kFillPath: {
        cairo_new_path(cr);
        for (std::size_t i = 0; i < op.pts.size(); ++i)
          (i == 0 ? cairo_move_to : cairo_line_to)(cr, op.pts[i].x, op.pts[i].y);
        if (op.closed) cairo_close_path(cr);
        SetColor(cr, op.color);
        if (op.kind == VectorOp::Kind::kFillPath) {
          cairo_fill(cr);
        } else {
          double dash[4];
          for (int k = 0; k < op.dash.count; ++k) dash[k] = op.dash.lengths[k];
          cairo_set_dash(cr, dash, op.dash.count, 0);
          cairo_set_line_width(cr, op.width);
          cairo_stroke(cr);
        }
        break;
      }
      case VectorOp::Kind::kFillCircle:
      case VectorOp::Kind::kStrokeCircle:
        cairo_new_path(cr);
        cairo_arc(cr, op.pts[0].x, op.pts[0].y, op.size, 0, 2 * M_PI);
        SetColor(cr, op.color);
        if (op.kind == VectorOp::Kind::kFillCircle) {
          cairo_fill(cr);
        } else {
          cairo_set_dash(cr, nullptr, 0, 0);
          cairo_set_line_width(cr, op.width);
          cairo_stroke(cr);
        }
        break;
      case VectorOp::Kind::kText:
        cairo_save(cr);
        if (op.vertical) {
          cairo_translate(cr, op.pts[1].x, op.pts[1].y);
          cairo_rotate(cr, -M_PI / 2);
          cairo_translate(cr, -op.pts[1].x, -op.pts[1].y);
        }
        cairo_set_font_face(cr, fonts.CairoFace(op.font));
        SetColor(cr, op.color);
        ShowText(cr, op, fonts.EmSize(op.font));
        cairo_restore(cr);
        break;
      case VectorOp::Kind::kPushClip:
        cairo_save(cr);
        cairo_rectangle(cr, op.pts[0].x, op.pts[0].y, std::fmax(0.f, op.pts[1].x - op.pts[0].x),
                        std::fmax(0.f, op.pts[1].y - op.pts[0].y));
        cairo_clip(cr);
        break;
      case VectorOp::Kind::kPopClip:
        cairo_restore(cr);
        break;
      case VectorOp::Kind::kBeginGroup:  // groups only structure SVG files
      case VectorOp::Kind::kEndGroup:
        break;
    }
  }
}

// Draws `fig` onto `surface`, scaled to `width` x `height` surface units. Returns the drawing's
// status (the surface's own is the caller's to check).
cairo_status_t DrawOnSurface(cairo_surface_t* surface, const VectorFigure& fig, double width,
                             double height) {
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface), cairo_destroy);
  cairo_scale(cr.get(), width / fig.width, height / fig.height);
  Draw(cr.get(), fig);
  return cairo_status(cr.get());
}

}  // namespace

std::string PdfDocument(const VectorFigure& fig, const FigureSize& size, const std::string& title) {
  std::string bytes;
  // A PDF point is 1/72 inch, a logical pixel 1/96 inch.
  const double pt_w = size.width.Pixels() * 0.75, pt_h = size.height.Pixels() * 0.75;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_pdf_surface_create_for_stream(Append, &bytes, pt_w, pt_h), cairo_surface_destroy);
  if (!title.empty())
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE,
                                   PlainText(title).c_str());  // plain text, markup resolved
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "formsim");
  // Cairo writes the wall-clock time as CreationDate unless told otherwise; a fixed date keeps
  // the same figure byte-identical from run to run (results are deterministic, so are files).
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, kPdfCreationDate);
  const cairo_status_t cs = DrawOnSurface(surface.get(), fig, pt_w, pt_h);
  cairo_surface_finish(surface.get());
  const cairo_status_t ss = cairo_surface_status(surface.get());
  if (cs != CAIRO_STATUS_SUCCESS || ss != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo could not draw the PDF: ") +
                             cairo_status_to_string(cs != CAIRO_STATUS_SUCCESS ? cs : ss));
  return bytes;
}

std::vector<std::uint8_t> RasterRgba(const VectorFigure& fig, int width, int height) {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height), cairo_surface_destroy);
  const cairo_status_t cs = DrawOnSurface(surface.get(), fig, width, height);
  cairo_surface_flush(surface.get());
  if (cs != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo could not draw the image: ") +
                             cairo_status_to_string(cs));
  // Cairo's ARGB32 is premultiplied, native-endian 32-bit words: un-premultiply into RGBA bytes.
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t px;
      std::memcpy(&px, data + y * stride + x * 4, 4);
      const unsigned a = px >> 24;
      std::uint8_t* o = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
      const unsigned c[3] = {(px >> 16) & 0xff, (px >> 8) & 0xff, px & 0xff};
      for (int k = 0; k < 3; ++k) o[k] = a == 0 ? 0 : static_cast<std::uint8_t>((c[k] * 255 + a / 2) / a);
      o[3] = static_cast<std::uint8_t>(a);
    }
  return rgba;
}

void WritePdf(const VectorFigure& fig, const FigureSize& size, const std::string& title,
              const std::string& path) {
  sim::WriteFileAtomic(path, PdfDocument(fig, size, title));
}

}  // namespace formsim::app
