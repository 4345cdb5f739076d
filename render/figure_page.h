// A vector figure as plain data (paths and text on a page, in points), and the one place that hands
// it to cairo for SVG or PDF. The frame figures (render/figure.h) and the time-series plots
// (render/series_plot.h) lay out a FigurePage; tests read the page (what is drawn, which labels)
// without parsing a file.
//
// Why cairo: Debian-packaged (libcairo2-dev), mature (the drawing library of GTK, Firefox's print
// path, poppler), one API for SVG and PDF, and text through its toy font API in a proper font
// (DejaVu Sans, fonts-dejavu-core) found by fontconfig.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace spinfold::render {

// The formats a picture can be written in: the GL frame as a PNG, or a vector figure.
enum class FigureFormat { png, svg, pdf };

std::optional<FigureFormat> parse_figure_format(std::string_view name);  // "png" | "svg" | "pdf"
std::string_view figure_format_name(FigureFormat format);
std::string_view figure_content_type(FigureFormat format);  // image/png, image/svg+xml, application/pdf
// The format a file name's extension says (.png, .svg, .pdf in any case), or nullopt.
std::optional<FigureFormat> figure_format_of_path(std::string_view path);

// A frame's pixel is this many points in a figure: 96 px to the inch (CSS), 72 pt to the inch; a
// 640×480 frame becomes a 480×360 pt figure (6.7 × 5 in), the width of a two-column page.
inline constexpr double kPointsPerPixel = 0.75;

// The font of every text [fontconfig family]; sizes below are in points.
inline constexpr const char* kFigureFont = "DejaVu Sans";

// One path: a polyline (open or closed) stroked, or a region filled. Points are page coordinates
// [pt, x right, y down from the top-left corner].
struct FigurePath {
  std::vector<glm::dvec2> points{};
  // A fill is the union of these polygons: `runs` splits `points` into closed polygons of the given
  // sizes (empty: one polygon of every point), filled with the non-zero rule. Ignored for strokes.
  std::vector<std::size_t> runs{};
  glm::dvec4 color{0, 0, 0, 1};  // RGBA in [0, 1]
  double width = 1.0;            // stroke width [pt]; fills ignore it
  bool filled = false;           // a filled region, else a stroked line
  bool closed = false;           // a stroke that returns to its first point
  std::vector<double> dash{};    // on/off lengths [pt]; empty: solid
  bool clip_to_picture = true;   // drawn inside FigurePage::picture only
  std::string role{};            // what it shows: "surface", "grid", "outline", "trail", "body", ...
};

enum class TextAlign { left, centre, right };

struct FigureText {
  glm::dvec2 at{0.0};  // the baseline's start, centre or end by `align` [pt]
  std::string text{};  // UTF-8
  double size = 9.0;   // [pt]
  bool bold = false;
  TextAlign align = TextAlign::left;
  double angle = 0.0;  // counter-clockwise about `at` [rad] (a y axis's label: π/2)
  glm::dvec4 color{0.1, 0.1, 0.1, 1};
  bool halo = false;   // a white outline under the glyphs, legible over lines
  std::string role{};  // "caption", "legend", "label", "tick", "axis", ...
};

struct FigurePage {
  double width = 0, height = 0;  // [pt]
  glm::dvec4 background{1, 1, 1, 1};
  // The picture's rectangle [pt], x, y of its top-left corner, its width and height: paths with
  // clip_to_picture are cut to it.
  glm::dvec4 picture{0, 0, 0, 0};
  std::vector<FigurePath> paths;  // painted in order, then the texts
  std::vector<FigureText> texts;
  std::string title;     // the file's title (SVG <title>, PDF Title)
  std::string metadata;  // the provenance (SVG <metadata>, PDF Subject)
};

// The width of a text in the figure's font [pt] (cairo's toy text extents).
double text_width(std::string_view text, double size, bool bold = false);
// Words of `text` in lines no wider than `width` [pt] (text_width's measure).
std::vector<std::string> wrap_text(const std::string& text, double size, bool bold, double width);

// The page as an SVG or a PDF file's bytes. Throws std::runtime_error when cairo fails and
// std::invalid_argument for FigureFormat::png.
std::vector<std::uint8_t> draw_figure(const FigurePage& page, FigureFormat format);

// The page as a PNG's bytes at `pixels_per_point` (cairo's image surface, then render/png_encoder.h
// with the title and the metadata as text chunks): a plot shown in a page (the work-precision plot in
// the UI). std::invalid_argument for a scale ≤ 0 or a side over 8192 pixels.
std::vector<std::uint8_t> raster_figure(const FigurePage& page, double pixels_per_point);

// XML's five escapes (&, <, >, ", ').
std::string xml_escape(std::string_view text);

// "Nice" axis ticks covering [lo, hi]: about `count` steps of 1, 2 or 5 × 10ᵏ (Heckbert's labels).
std::vector<double> nice_ticks(double lo, double hi, int count);

}  // namespace spinfold::render
