#include "render/series_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/plot_axis.h"

namespace spinfold::render {

namespace {

constexpr double kLeft = 64.0, kRight = 14.0, kTop = 10.0, kGap = 16.0;  // margins [pt]
constexpr double kTickSize = kPlotTickSize, kAxisSize = kPlotAxisSize, kTitleSize = kPlotTitleSize;  // [pt]
constexpr double kProvenanceSize = 6.0;                                                              // [pt]

// The finite values of a panel in the axis's coordinate.
std::vector<double> axis_values(const std::vector<double>& y, bool log) {
  std::vector<double> out(y.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < y.size(); ++i)
    if (std::isfinite(y[i]) && (!log || y[i] != 0.0)) out[i] = log ? std::log10(std::abs(y[i])) : y[i];
  return out;
}

}  // namespace

std::string axis_title(const std::string& quantity, const std::string& unit) {
  return unit.empty() ? quantity : quantity + " [" + unit + "]";
}

std::string power_of_ten(int exponent) {
  static const char* const kDigits[] = {"\u2070", "\u00B9", "\u00B2", "\u00B3", "\u2074",
                                        "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string text = "10";
  if (exponent < 0) text += "\u207B";
  const std::string digits = std::to_string(std::abs(exponent));
  for (const char d : digits) text += kDigits[d - '0'];
  return text;
}

FigurePage series_page(const SeriesPlot& plot) {
  if (plot.panels.empty()) throw std::invalid_argument("series_page: no quantity to plot");
  for (const PlotPanel& panel : plot.panels)
    for (const PlotLine& line : panel.lines)
      if (line.y.size() != plot.x.size())
        throw std::invalid_argument("series_page: " + panel.quantity + " has " +
                                    std::to_string(line.y.size()) + " values for " +
                                    std::to_string(plot.x.size()) + " times");
  FigurePage page;
  page.width = plot.width;
  page.title = plot.title;
  page.metadata = plot.metadata;
  const double left = kLeft, right = plot.width - kRight, plot_width = right - left;
  double y = kTop;
  for (const std::string& line : wrap_text(plot.title, kTitleSize, true, right - left)) {
    y += kTitleSize * 1.3;
    page.texts.push_back({.at = {left, y}, .text = line, .size = kTitleSize, .bold = true, .role = "title"});
  }
  for (const std::string& line : wrap_text(plot.description, kAxisSize, false, right - left)) {
    y += kAxisSize * 1.35;
    page.texts.push_back({.at = {left, y}, .text = line, .size = kAxisSize, .role = "title"});
  }
  // One legend for every panel (each shows the same bodies), in a row above them, when there is
  // more than one line to tell apart.
  std::vector<const PlotLine*> named;
  for (const PlotPanel& panel : plot.panels)
    for (const PlotLine& line : panel.lines)
      if (std::none_of(named.begin(), named.end(), [&](const PlotLine* n) { return n->label == line.label; }))
        named.push_back(&line);
  if (named.size() > 1) {
    y += kTickSize * 1.6;
    double x = left;
    for (const PlotLine* line : named) {
      const double width = 22.0 + text_width(line->label, kTickSize) + 14.0;
      if (x > left && x + width > right) x = left, y += kTickSize * 1.5;
      page.paths.push_back({.points = {{x, y - 0.35 * kTickSize}, {x + 16.0, y - 0.35 * kTickSize}},
                            .color = line->color,
                            .width = 1.5,
                            .clip_to_picture = false,
                            .role = "legend"});
      page.texts.push_back({.at = {x + 20.0, y}, .text = line->label, .size = kTickSize, .role = "legend"});
      x += width;
    }
  }
  y += 8.0;

  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (const double x : plot.x)
    if (std::isfinite(x)) x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
  const PlotAxis x_axis =
      make_axis(std::isfinite(x_lo) ? x_lo : 0.0, std::isfinite(x_hi) ? x_hi : 1.0, false, false);
  const auto x_at = [&](double x) { return left + x_axis.to_unit(x) * plot_width; };

  for (std::size_t p = 0; p < plot.panels.size(); ++p) {
    const PlotPanel& panel = plot.panels[p];
    const double top = y, bottom = y + plot.panel_height;
    std::vector<std::vector<double>> values;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const PlotLine& line : panel.lines) {
      values.push_back(axis_values(line.y, panel.log));
      for (const double v : values.back())
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    const bool empty = !std::isfinite(lo);
    // Padded, logarithmic or not: no line runs along the frame (the log axis's largest value did).
    const PlotAxis y_axis = make_axis(empty ? 0.0 : lo, empty ? 1.0 : hi, panel.log, true);
    const auto y_at = [&](double v) { return bottom - y_axis.to_unit(v) * plot.panel_height; };

    // Grid lines at the ticks, then the lines, then the frame, ticks and labels over them.
    const PlotBox box{left, top, right, bottom};
    add_plot_grid(page, box, x_axis, y_axis);
    for (std::size_t l = 0; l < panel.lines.size(); ++l) {
      FigurePath run{.color = panel.lines[l].color, .width = 1.0, .clip_to_picture = false, .role = "series"};
      const auto flush = [&] {
        if (run.points.size() >= 2) page.paths.push_back(run);
        run.points.clear();
      };
      for (std::size_t i = 0; i < plot.x.size(); ++i) {
        const double v = values[l][i];
        if (!std::isfinite(v) || !std::isfinite(plot.x[i])) {
          flush();
          continue;
        }
        run.points.push_back({x_at(plot.x[i]), y_at(v)});
      }
      flush();
    }
    add_plot_frame(page, box, x_axis, y_axis, p + 1 == plot.panels.size());
    // The y axis's title, turned, left of the tick labels; its power of ten beside it.
    std::string title = axis_title(panel.log ? "|" + panel.quantity + "|" : panel.quantity, panel.unit);
    if (!y_axis.factor.empty()) title += "  " + y_axis.factor;
    page.texts.push_back({.at = {12.0, 0.5 * (top + bottom)},
                          .text = title,
                          .size = kAxisSize,
                          .align = TextAlign::centre,
                          .angle = 1.5707963267948966,
                          .role = "axis"});
    if (empty)
      page.texts.push_back({.at = {0.5 * (left + right), 0.5 * (top + bottom)},
                            .text = panel.log ? "nothing to plot: every value zero or undefined"
                                              : "nothing to plot: every value undefined",
                            .size = kAxisSize,
                            .align = TextAlign::centre,
                            .role = "axis"});
    y = bottom + kGap;
  }
  // The x axis's title under the last panel's tick labels.
  y += kTickSize;
  std::string x_title = axis_title(plot.x_quantity, plot.x_unit);
  if (!x_axis.factor.empty()) x_title += "  " + x_axis.factor;
  page.texts.push_back({.at = {0.5 * (left + right), y},
                        .text = x_title,
                        .size = kAxisSize,
                        .align = TextAlign::centre,
                        .role = "axis"});
  y += 6.0;
  if (!plot.provenance.empty()) {
    // The provenance, wrapped to the page.
    for (const std::string& line : wrap_text(plot.provenance, kProvenanceSize, false, plot.width - 16.0)) {
      y += kProvenanceSize * 1.35;
      page.texts.push_back({.at = {8.0, y},
                            .text = line,
                            .size = kProvenanceSize,
                            .color = {0.4, 0.4, 0.4, 1},
                            .role = "caption"});
    }
  }
  page.height = y + 8.0;
  page.picture = {0, 0, page.width, page.height};
  return page;
}

}  // namespace spinfold::render
