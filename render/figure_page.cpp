#include "render/figure_page.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>

#include "render/png_encoder.h"

namespace spinfold::render {

std::optional<FigureFormat> parse_figure_format(std::string_view name) {
  if (name == "png") return FigureFormat::png;
  if (name == "svg") return FigureFormat::svg;
  if (name == "pdf") return FigureFormat::pdf;
  return std::nullopt;
}

std::string_view figure_format_name(FigureFormat format) {
  switch (format) {
    case FigureFormat::png: return "png";
    case FigureFormat::svg: return "svg";
    case FigureFormat::pdf: return "pdf";
  }
  return "png";
}

std::string_view figure_content_type(FigureFormat format) {
  switch (format) {
    case FigureFormat::png: return "image/png";
    case FigureFormat::svg: return "image/svg+xml";
    case FigureFormat::pdf: return "application/pdf";
  }
  return "image/png";
}

std::optional<FigureFormat> figure_format_of_path(std::string_view path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return std::nullopt;
  std::string extension(path.substr(dot + 1));
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return parse_figure_format(extension);
}

namespace {

struct CairoDeleter {
  void operator()(cairo_t* cr) const { cairo_destroy(cr); }
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
using Context = std::unique_ptr<cairo_t, CairoDeleter>;
using Surface = std::unique_ptr<cairo_surface_t, CairoDeleter>;

void select_font(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, kFigureFont, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

void set_color(cairo_t* cr, const glm::dvec4& c) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a);
}

void paint_path(cairo_t* cr, const FigurePath& path) {
  if (path.points.size() < 2) return;
  cairo_new_path(cr);
  if (path.filled) {
    std::size_t start = 0;
    const std::vector<std::size_t> whole{path.points.size()};
    for (const std::size_t n : path.runs.empty() ? whole : path.runs) {
      for (std::size_t i = start; i < start + n && i < path.points.size(); ++i)
        (i == start ? cairo_move_to : cairo_line_to)(cr, path.points[i].x, path.points[i].y);
      cairo_close_path(cr);
      start += n;
    }
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
    set_color(cr, path.color);
    cairo_fill(cr);
    return;
  }
  cairo_move_to(cr, path.points.front().x, path.points.front().y);
  for (std::size_t i = 1; i < path.points.size(); ++i) cairo_line_to(cr, path.points[i].x, path.points[i].y);
  if (path.closed) cairo_close_path(cr);
  cairo_set_line_width(cr, path.width);
  cairo_set_dash(cr, path.dash.data(), static_cast<int>(path.dash.size()), 0.0);
  set_color(cr, path.color);
  cairo_stroke(cr);
}

void paint_text(cairo_t* cr, const FigureText& t) {
  select_font(cr, t.size, t.bold);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, t.text.c_str(), &extents);
  const double shift = t.align == TextAlign::left     ? 0.0
                       : t.align == TextAlign::centre ? -0.5 * extents.x_advance
                                                      : -extents.x_advance;
  cairo_save(cr);
  cairo_translate(cr, t.at.x, t.at.y);
  cairo_rotate(cr, -t.angle);
  if (t.halo) {  // the glyphs' outline in white, under them
    cairo_move_to(cr, shift, 0.0);
    cairo_text_path(cr, t.text.c_str());
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_set_line_width(cr, 0.25 * t.size);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke(cr);
  }
  cairo_move_to(cr, shift, 0.0);
  set_color(cr, t.color);
  cairo_show_text(cr, t.text.c_str());
  cairo_restore(cr);
}

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  auto* bytes = static_cast<std::vector<std::uint8_t>*>(closure);
  bytes->insert(bytes->end(), data, data + length);
  return CAIRO_STATUS_SUCCESS;
}

// cairo numbers an SVG's surfaces ("surface6") with a counter of the process: renumbered in the
// order they appear, so that the same figure gives the same bytes in any process.
std::string renumber_surfaces(const std::string& text) {
  std::string out;
  std::map<std::string, std::string> numbers;
  std::size_t from = 0;
  for (std::size_t at; (at = text.find("surface", from)) != std::string::npos;) {
    std::size_t end = at + 7;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    const bool id = at > 0 && (text[at - 1] == '"' || text[at - 1] == '#') && end > at + 7;
    out.append(text, from, end - from);
    if (id) {
      const std::string number = text.substr(at + 7, end - at - 7);
      const auto [it, fresh] = numbers.try_emplace(number, std::to_string(numbers.size() + 1));
      out.replace(out.size() - number.size(), number.size(), it->second);
    }
    from = end;
  }
  out.append(text, from, std::string::npos);
  return out;
}

// cairo writes no title or metadata into an SVG: they go in after the opening <svg> tag.
void add_svg_metadata(std::vector<std::uint8_t>& svg, const FigurePage& page) {
  const std::string text = renumber_surfaces(std::string(svg.begin(), svg.end()));
  svg.assign(text.begin(), text.end());
  const std::size_t open = text.find("<svg");
  const std::size_t end = open == std::string::npos ? open : text.find('>', open);
  if (end == std::string::npos) throw std::runtime_error("cairo wrote an SVG without an <svg> element");
  const std::string inserted = "\n<title>" + xml_escape(page.title) + "</title>\n<metadata>" +
                               xml_escape(page.metadata) + "</metadata>";
  svg.insert(svg.begin() + static_cast<std::ptrdiff_t>(end + 1), inserted.begin(), inserted.end());
}

}  // namespace

double text_width(std::string_view text, double size, bool bold) {
  const Surface surface(cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1));
  const Context cr(cairo_create(surface.get()));
  // Unhinted metrics, as the SVG and PDF surfaces use (an image surface rounds advances to pixels).
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_NONE);
  cairo_set_font_options(cr.get(), options);
  cairo_font_options_destroy(options);
  select_font(cr.get(), size, bold);
  cairo_text_extents_t extents;
  cairo_text_extents(cr.get(), std::string(text).c_str(), &extents);
  return extents.x_advance;
}

namespace {

// The page's paths, then its texts, on a cairo surface in points; std::runtime_error when cairo fails.
void paint_page(cairo_surface_t* surface, const FigurePage& page, double scale) {
  const Context cr(cairo_create(surface));
  cairo_t* c = cr.get();
  cairo_scale(c, scale, scale);
  set_color(c, page.background);
  cairo_paint(c);
  cairo_set_line_cap(c, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(c, CAIRO_LINE_JOIN_ROUND);
  for (const FigurePath& path : page.paths) {
    cairo_save(c);
    if (path.clip_to_picture) {
      cairo_rectangle(c, page.picture.x, page.picture.y, page.picture.z, page.picture.w);
      cairo_clip(c);
    }
    paint_path(c, path);
    cairo_restore(c);
  }
  for (const FigureText& text : page.texts) paint_text(c, text);
  if (cairo_status(c) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo: ") + cairo_status_to_string(cairo_status(c)));
}

void finish(cairo_surface_t* surface) {
  cairo_surface_finish(surface);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo: ") + cairo_status_to_string(cairo_surface_status(surface)));
}

}  // namespace

std::vector<std::uint8_t> draw_figure(const FigurePage& page, FigureFormat format) {
  std::vector<std::uint8_t> bytes;
  Surface surface;
  if (format == FigureFormat::svg) {
    surface.reset(cairo_svg_surface_create_for_stream(append_bytes, &bytes, page.width, page.height));
    cairo_svg_surface_restrict_to_version(surface.get(), CAIRO_SVG_VERSION_1_1);
  } else if (format == FigureFormat::pdf) {
    surface.reset(cairo_pdf_surface_create_for_stream(append_bytes, &bytes, page.width, page.height));
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, page.title.c_str());
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_SUBJECT, page.metadata.c_str());
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "spinfold");
    // No creation date (cairo writes the clock's unless it is given one it cannot read): the same
    // figure gives the same bytes, as every output's provenance promises (codec/provenance.h).
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
  } else {
    throw std::invalid_argument("draw_figure: a vector format (svg or pdf) is needed");
  }
  paint_page(surface.get(), page, 1.0);
  finish(surface.get());
  surface.reset();
  if (format == FigureFormat::svg) add_svg_metadata(bytes, page);
  return bytes;
}

std::vector<std::uint8_t> raster_figure(const FigurePage& page, double pixels_per_point) {
  if (!(pixels_per_point > 0.0) || page.width * pixels_per_point > 8192 ||
      page.height * pixels_per_point > 8192)
    throw std::invalid_argument("raster_figure: a page of at most 8192 pixels a side, at a scale > 0");
  const int width = std::max(1, static_cast<int>(std::ceil(page.width * pixels_per_point)));
  const int height = std::max(1, static_cast<int>(std::ceil(page.height * pixels_per_point)));
  const Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
  paint_page(surface.get(), page, pixels_per_point);
  cairo_surface_flush(surface.get());
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo: ") +
                             cairo_status_to_string(cairo_surface_status(surface.get())));
  // cairo's ARGB32 is premultiplied, native-endian 32-bit words; the page's background is opaque,
  // so each pixel's colour is its own.
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t argb;
      std::memcpy(&argb, data + static_cast<std::size_t>(y) * stride + 4 * static_cast<std::size_t>(x), 4);
      std::uint8_t* p = &rgba[4 * (static_cast<std::size_t>(y) * width + x)];
      p[0] = static_cast<std::uint8_t>(argb >> 16), p[1] = static_cast<std::uint8_t>(argb >> 8);
      p[2] = static_cast<std::uint8_t>(argb), p[3] = static_cast<std::uint8_t>(argb >> 24);
    }
  std::vector<PngText> texts;
  if (!page.title.empty()) texts.emplace_back("Title", page.title);
  if (!page.metadata.empty()) texts.emplace_back("Source", page.metadata);
  return encode_png(rgba.data(), width, height, texts);
}

std::string xml_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int count) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || count < 1) return {};
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {lo};
  // The step: the range over `count`, rounded up to 1, 2 or 5 times a power of ten.
  const double raw = (hi - lo) / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double step = (fraction <= 1.0 ? 1.0 : fraction <= 2.0 ? 2.0 : fraction <= 5.0 ? 5.0 : 10.0) * power;
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step && ticks.size() < 100; ++k)
    ticks.push_back(std::abs(k) < 0.5 ? 0.0 : k * step);
  return ticks;
}

std::vector<std::string> wrap_text(const std::string& text, double size, bool bold, double width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t j = text.find(' ', i);
    if (j == std::string::npos) j = text.size();
    const std::string word = text.substr(i, j - i);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(longer, size, bold) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
    i = j + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace spinfold::render
