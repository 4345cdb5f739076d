#include "render/curves_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/plot_axis.h"
#include "render/series_plot.h"

namespace spinfold::render {

namespace {

constexpr double kLeft = 52.0, kRight = 12.0, kTop = 8.0;  // margins [pt]
constexpr double kMarker = 2.6;                            // a marker's half size [pt]
constexpr double kLegendLine = 18.0;                       // a legend entry's sample line [pt]

// A point in the axes' coordinates (log10 on a log axis), or NaN where it cannot be drawn.
glm::dvec2 axis_point(const CurvesPlot& plot, glm::dvec2 p) {
  const auto coordinate = [](double v, bool log) {
    if (!std::isfinite(v) || (log && v <= 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return log ? std::log10(v) : v;
  };
  return {coordinate(p.x, plot.x_log), coordinate(p.y, plot.y_log)};
}

bool drawable(glm::dvec2 p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

}  // namespace

glm::dvec4 curve_color(std::size_t k) {
  static const glm::dvec4 kColors[] = {
      {0.122, 0.467, 0.706, 1}, {1.000, 0.498, 0.055, 1}, {0.173, 0.627, 0.173, 1}, {0.839, 0.153, 0.157, 1},
      {0.580, 0.404, 0.741, 1}, {0.549, 0.337, 0.294, 1}, {0.890, 0.467, 0.761, 1}, {0.498, 0.498, 0.498, 1},
      {0.737, 0.741, 0.133, 1}, {0.090, 0.745, 0.812, 1}};
  return kColors[k % std::size(kColors)];
}

std::vector<glm::dvec2> curve_marker(std::size_t k, glm::dvec2 at, double size) {
  std::vector<glm::dvec2> polygon;
  switch (k % 4) {
    case 0:  // circle
      for (int i = 0; i < 12; ++i)
        polygon.push_back(
            at + size * glm::dvec2(std::cos(i * 0.5235987755982988), std::sin(i * 0.5235987755982988)));
      break;
    case 1:  // square
      for (const glm::dvec2 c : {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)})
        polygon.push_back(at + 0.85 * size * c);
      break;
    case 2:  // triangle, point up (page y runs down)
      for (const glm::dvec2 c : {glm::dvec2(0, -1.25), glm::dvec2(1.1, 0.75), glm::dvec2(-1.1, 0.75)})
        polygon.push_back(at + size * c);
      break;
    default:  // diamond
      for (const glm::dvec2 c :
           {glm::dvec2(0, -1.2), glm::dvec2(1.2, 0), glm::dvec2(0, 1.2), glm::dvec2(-1.2, 0)})
        polygon.push_back(at + size * c);
  }
  return polygon;
}

FigurePage curves_page(const CurvesPlot& plot) {
  FigurePage page;
  page.width = plot.width;
  page.title = plot.title;
  page.metadata = plot.metadata;
  const double legend_width = plot.legend_below ? 0.0 : [&] {
    double widest = 0.0;
    for (const Curve& c : plot.curves) widest = std::max(widest, text_width(c.label, kPlotTickSize));
    return kLegendLine + 6.0 + widest + 8.0;
  }();
  const double left = kLeft, right = plot.width - kRight - legend_width;
  double y = kTop;
  for (const std::string& line : wrap_text(plot.title, kPlotTitleSize, true, plot.width - 2 * kRight)) {
    y += kPlotTitleSize * 1.3;
    page.texts.push_back(
        {.at = {kRight, y}, .text = line, .size = kPlotTitleSize, .bold = true, .role = "title"});
  }
  y += 8.0;
  const PlotBox box{left, y, right, y + plot.plot_height};

  // The axes cover every drawable point.
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const Curve& c : plot.curves)
    for (const glm::dvec2 p : c.points)
      if (const glm::dvec2 a = axis_point(plot, p); drawable(a)) lo = glm::min(lo, a), hi = glm::max(hi, a);
  const bool empty = !std::isfinite(lo.x);
  const PlotAxis x_axis = make_axis(empty ? 0.0 : lo.x, empty ? 1.0 : hi.x, plot.x_log, true);
  const PlotAxis y_axis = make_axis(empty ? 0.0 : lo.y, empty ? 1.0 : hi.y, plot.y_log, true);
  const auto at = [&](glm::dvec2 a) { return glm::dvec2(box.x_at(x_axis, a.x), box.y_at(y_axis, a.y)); };

  add_plot_grid(page, box, x_axis, y_axis);
  for (std::size_t k = 0; k < plot.curves.size(); ++k) {
    const Curve& curve = plot.curves[k];
    const glm::dvec4 color = curve_color(k);
    FigurePath run{.color = color,
                   .width = 1.1,
                   .dash = curve.dashed ? std::vector<double>{4.0, 2.5} : std::vector<double>{},
                   .clip_to_picture = false,
                   .role = "curve"};
    const auto flush = [&] {
      if (run.points.size() >= 2) page.paths.push_back(run);
      run.points.clear();
    };
    std::vector<glm::dvec2> marks;
    for (const glm::dvec2 p : curve.points) {
      const glm::dvec2 a = axis_point(plot, p);
      if (!drawable(a)) {
        flush();
        continue;
      }
      run.points.push_back(at(a));
      marks.push_back(at(a));
    }
    flush();
    for (const glm::dvec2 m : marks)
      page.paths.push_back({.points = curve_marker(k, m, kMarker),
                            .color = color,
                            .filled = true,
                            .clip_to_picture = false,
                            .role = "marker"});
  }
  add_plot_frame(page, box, x_axis, y_axis, true);
  if (empty)
    page.texts.push_back({.at = {0.5 * (box.left + box.right), 0.5 * (box.top + box.bottom)},
                          .text = "nothing to plot: no finite point",
                          .size = kPlotAxisSize,
                          .align = TextAlign::centre,
                          .role = "axis"});
  page.texts.push_back({.at = {12.0, 0.5 * (box.top + box.bottom)},
                        .text = plot.y_title,
                        .size = kPlotAxisSize,
                        .align = TextAlign::centre,
                        .angle = 1.5707963267948966,
                        .role = "axis"});
  y = box.bottom + kPlotTick + 2.0 + kPlotTickSize + 6.0 + kPlotAxisSize;
  page.texts.push_back({.at = {0.5 * (box.left + box.right), y},
                        .text = plot.x_title,
                        .size = kPlotAxisSize,
                        .align = TextAlign::centre,
                        .role = "axis"});

  // The legend: a sample of each curve's line and marker, then its label; in rows under the plot
  // (wrapped to the page) or in a column right of it.
  const auto entry = [&](std::size_t k, double x, double baseline) {
    const double mid = baseline - 0.35 * kPlotTickSize;
    page.paths.push_back(
        {.points = {{x, mid}, {x + kLegendLine, mid}},
         .color = curve_color(k),
         .width = 1.1,
         .dash = plot.curves[k].dashed ? std::vector<double>{4.0, 2.5} : std::vector<double>{},
         .clip_to_picture = false,
         .role = "legend"});
    page.paths.push_back({.points = curve_marker(k, {x + 0.5 * kLegendLine, mid}, kMarker),
                          .color = curve_color(k),
                          .filled = true,
                          .clip_to_picture = false,
                          .role = "legend"});
    page.texts.push_back({.at = {x + kLegendLine + 4.0, baseline},
                          .text = plot.curves[k].label,
                          .size = kPlotTickSize,
                          .role = "legend"});
  };
  if (plot.legend_below) {
    y += kPlotTickSize * 2.0;
    double x = left;
    for (std::size_t k = 0; k < plot.curves.size(); ++k) {
      const double w = kLegendLine + 4.0 + text_width(plot.curves[k].label, kPlotTickSize) + 12.0;
      if (x > left && x + w > plot.width - kRight) x = left, y += kPlotTickSize * 1.6;
      entry(k, x, y);
      x += w;
    }
  } else {
    for (std::size_t k = 0; k < plot.curves.size(); ++k)
      entry(k, right + 10.0, box.top + kPlotTickSize * (1.0 + 1.6 * static_cast<double>(k)));
  }
  page.height = std::max(y, box.bottom) + 10.0;
  page.picture = {0, 0, page.width, page.height};
  return page;
}

}  // namespace spinfold::render
