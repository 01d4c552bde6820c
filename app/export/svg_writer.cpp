#include "app/export/svg_writer.hpp"

#include <cmath>
#include <map>

#include "app/render/label_markup.hpp"
#include "app/render/vector_fonts.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"

namespace formsim::app {
namespace {

// Coordinates to 1/100 pixel, without trailing zeros.
std::string Num(double v) {
  return sim::FormatFixed(v, 2, /*trim=*/true);
}

std::string SvgHex(sim::Color c) {
  auto byte = [](float v) {
    return static_cast<int>(std::lround(std::fmin(1.f, std::fmax(0.f, v)) * 255));
  };
  return sim::Sprintf("#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
}

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        // Control characters are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t') out += c;
    }
  }
  return out;
}

// fill="#rrggbb" with fill-opacity when translucent (same for stroke).
std::string Paint(const char* what, sim::Color c) {
  std::string s = std::string(" ") + what + "=\"" + SvgHex(c) + "\"";
  if (c.a < 0.999f) s += std::string(" ") + what + "-opacity=\"" + Num(c.a) + "\"";
  return s;
}

std::string PathData(const std::vector<ImVec2>& pts, bool closed) {
  std::string d;
  for (std::size_t i = 0; i < pts.size(); ++i)
    d += (i == 0 ? "M" : " L") + Num(pts[i].x) + " " + Num(pts[i].y);
  if (closed) d += " Z";
  return d;
}

std::string Dash(const LineDash& dash) {
  if (dash.solid()) return "";
  std::string s = " stroke-dasharray=\"";
  for (int k = 0; k < dash.count; ++k) s += (k ? "," : "") + Num(dash.lengths[k]);
  return s + "\"";
}

std::string Rect(const VectorOp& op, float inset) {
  const ImVec2 a = op.pts[0], b = op.pts[1];
  std::string s = "<rect x=\"" + Num(a.x + inset) + "\" y=\"" + Num(a.y + inset) + "\" width=\"" +
                  Num(std::fmax(0.f, b.x - a.x - 2 * inset)) + "\" height=\"" +
                  Num(std::fmax(0.f, b.y - a.y - 2 * inset)) + "\"";
  if (op.size > 0) s += " rx=\"" + Num(op.size) + "\"";
  return s;
}

// A text element's content: the text, or for markup its runs, scripts as <tspan>s with a
// baseline shift and a smaller font size (the text stays editable text).
std::string TextContent(const VectorOp& op, float em) {
  if (!op.markup) return Escape(op.text);
  std::string out;
  for (const MarkupRun& run : ParseMarkup(op.text).runs) {
    if (run.kind == ScriptKind::kNormal) {
      out += Escape(run.text);
      continue;
    }
    out += std::string("<tspan baseline-shift=\"") +
           (run.kind == ScriptKind::kSub ? "sub" : "super") + "\" font-size=\"" +
           Num(PlacementOf(run.kind).scale * em) + "\">" + Escape(run.text) + "</tspan>";
  }
  return out;
}

}  // namespace

std::string XmlId(const std::string& raw) {
  // XML 1.0 Name characters in ASCII: letters, digits, '-', '_', '.'; a letter or '_' first.
  std::string out;
  for (char c : raw) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_' || c == '.';
    out += ok ? c : '_';
  }
  if (out.empty() ||
      !((out[0] >= 'a' && out[0] <= 'z') || (out[0] >= 'A' && out[0] <= 'Z') || out[0] == '_'))
    out.insert(out.begin(), '_');
  return out;
}

std::string SvgDocument(const VectorFigure& fig, const FigureSize& size, const std::string& title) {
  const VectorFonts& fonts = VectorFonts::Get();
  std::string out;
  out.reserve(64 * 1024);
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + size.width.Text() +
         "\" height=\"" + size.height.Text() + "\" viewBox=\"0 0 " + Num(fig.width) + " " +
         Num(fig.height) + "\" xml:space=\"preserve\">\n";
  // The document title is plain text: the figure title's drawn form (markup resolved).
  if (!title.empty()) out += "<title>" + Escape(PlainText(title)) + "</title>\n";
  out += "<desc>formsim figure</desc>\n";
  int clip_id = 0, open_groups = 0;
  std::map<std::string, int> ids;
  for (const VectorOp& op : fig.ops) {
    switch (op.kind) {
      case VectorOp::Kind::kFillRect:
        out += Rect(op, 0) + Paint("fill", op.color) + "/>\n";
        break;
      case VectorOp::Kind::kStrokeRect:
        out += Rect(op, 0.5f * op.width) + " fill=\"none\"" + Paint("stroke", op.color) +
               " stroke-width=\"" + Num(op.width) + "\"/>\n";
        break;
      case VectorOp::Kind::kPath:
        out += "<path d=\"" + PathData(op.pts, op.closed) + "\" fill=\"none\"" +
               Paint("stroke", op.color) + " stroke-width=\"" + Num(op.width) +
               "\" stroke-linejoin=\"round\"" + Dash(op.dash) + "/>\n";
        break;
      case VectorOp::Kind::kFillPath:
        out += "<path" + (op.cls.empty() ? "" : " class=\"" + Escape(op.cls) + "\"") + " d=\"" +
               PathData(op.pts, true) + "\"" + Paint("fill", op.color) + "/>\n";
        break;
      case VectorOp::Kind::kFillCircle:
        out += "<circle cx=\"" + Num(op.pts[0].x) + "\" cy=\"" + Num(op.pts[0].y) + "\" r=\"" +
               Num(op.size) + "\"" + Paint("fill", op.color) + "/>\n";
        break;
      case VectorOp::Kind::kStrokeCircle:
        out += "<circle cx=\"" + Num(op.pts[0].x) + "\" cy=\"" + Num(op.pts[0].y) + "\" r=\"" +
               Num(op.size) + "\" fill=\"none\"" + Paint("stroke", op.color) + " stroke-width=\"" +
               Num(op.width) + "\"/>\n";
        break;
      case VectorOp::Kind::kText: {
        const FontSpec& spec = FontSpecOf(op.font);
        out += "<text x=\"" + Num(op.pts[0].x) + "\" y=\"" + Num(op.pts[0].y) +
               "\" font-family=\"" + spec.family + ", sans-serif\" font-size=\"" +
               Num(fonts.EmSize(op.font)) + "\"";
        if (spec.bold) out += " font-weight=\"bold\"";
        if (op.vertical)
          out += " transform=\"rotate(-90 " + Num(op.pts[1].x) + " " + Num(op.pts[1].y) + ")\"";
        out += Paint("fill", op.color) + ">" + TextContent(op, fonts.EmSize(op.font)) + "</text>\n";
        break;
      }
      case VectorOp::Kind::kPushClip: {
        const std::string id = "clip" + std::to_string(++clip_id);
        const ImVec2 a = op.pts[0], b = op.pts[1];
        out += "<clipPath id=\"" + id + "\"><rect x=\"" + Num(a.x) + "\" y=\"" + Num(a.y) +
               "\" width=\"" + Num(std::fmax(0.f, b.x - a.x)) + "\" height=\"" +
               Num(std::fmax(0.f, b.y - a.y)) + "\"/></clipPath>\n<g clip-path=\"url(#" + id +
               ")\">\n";
        ++open_groups;
        break;
      }
      case VectorOp::Kind::kBeginGroup: {
        // Ids unique in the document: a second "robot-R1" becomes "robot-R1-2".
        std::string id = XmlId(op.text);
        const int seen = ++ids[id];
        if (seen > 1) id += "-" + std::to_string(seen);
        out += "<g id=\"" + id + "\"";
        if (!op.cls.empty()) out += " class=\"" + Escape(op.cls) + "\"";
        out += ">\n";
        ++open_groups;
        break;
      }
      case VectorOp::Kind::kEndGroup:
      case VectorOp::Kind::kPopClip:
        if (open_groups > 0) {
          out += "</g>\n";
          --open_groups;
        }
        break;
    }
  }
  while (open_groups-- > 0) out += "</g>\n";
  out += "</svg>\n";
  return out;
}

void WriteSvg(const VectorFigure& fig, const FigureSize& size, const std::string& title,
              const std::string& path) {
  sim::WriteFileAtomic(path, SvgDocument(fig, size, title));
}

}  // namespace formsim::app
