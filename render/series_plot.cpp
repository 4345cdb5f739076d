#include "render/series_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace spinfold::render {

namespace {

constexpr double kLeft = 64.0, kRight = 14.0, kTop = 10.0, kGap = 16.0;                       // margins [pt]
constexpr double kTickSize = 7.5, kAxisSize = 8.5, kTitleSize = 10.0, kProvenanceSize = 6.0;  // [pt]
constexpr double kTick = 3.0;  // tick mark length [pt]
const glm::dvec4 kInk{0.1, 0.1, 0.1, 1.0};
const glm::dvec4 kGridInk{0.88, 0.88, 0.88, 1.0};

std::string number(double v, const char* pattern = "%.4g") {
  char text[48];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

// One axis: the range shown and its ticks, in the axis's own coordinate (log10|y| when log).
struct Axis {
  double lo = 0, hi = 1;
  std::vector<double> ticks;
  std::vector<std::string> labels;
  std::string factor;  // "×10⁻¹²": the labels' common power of ten, shown with the title
  double to_unit(double v) const { return (v - lo) / (hi - lo); }  // 0 at lo, 1 at hi
};

Axis make_axis(double lo, double hi, bool log, bool pad) {
  Axis a;
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;
  if (hi - lo <= 1e-300 || (hi - lo) <= 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
    const double half = log ? 0.5 : (lo == 0.0 ? 1.0 : 0.1 * std::abs(lo));
    lo -= half, hi += half;
  }
  if (pad) {
    const double margin = 0.05 * (hi - lo);
    lo -= margin, hi += margin;
  }
  a.lo = lo, a.hi = hi;
  if (log) {
    for (double k = std::ceil(lo); k <= hi; ++k) a.ticks.push_back(k);
    if (a.ticks.size() > 8) {  // every second or more decade
      const int every = static_cast<int>(std::ceil(a.ticks.size() / 6.0));
      std::vector<double> fewer;
      for (const double k : a.ticks)
        if (static_cast<long>(k) % every == 0) fewer.push_back(k);
      a.ticks = fewer;
    }
    if (a.ticks.size() < 2) {
      a.ticks = nice_ticks(lo, hi, 4);
      for (const double k : a.ticks) a.labels.push_back(number(std::pow(10.0, k), "%.3g"));
      return a;
    }
    for (const double k : a.ticks) a.labels.push_back(power_of_ten(static_cast<int>(k)));
    return a;
  }
  a.ticks = nice_ticks(lo, hi, 5);
  double largest = 0.0;
  for (const double t : a.ticks) largest = std::max(largest, std::abs(t));
  const int exponent = largest > 0.0 ? static_cast<int>(std::floor(std::log10(largest))) : 0;
  const bool factored = exponent < -2 || exponent > 3;
  const double scale = factored ? std::pow(10.0, exponent) : 1.0;
  if (factored) a.factor = "\u00D7" + power_of_ten(exponent);
  for (const double t : a.ticks) a.labels.push_back(number(t / scale));
  return a;
}

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
  const Axis x_axis =
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
    const Axis y_axis = make_axis(empty ? 0.0 : lo, empty ? 1.0 : hi, panel.log, !panel.log);
    const auto y_at = [&](double v) { return bottom - y_axis.to_unit(v) * plot.panel_height; };

    // Grid lines at the ticks, then the lines, then the frame, ticks and labels over them.
    for (const double t : y_axis.ticks)
      page.paths.push_back({.points = {{left, y_at(t)}, {right, y_at(t)}},
                            .color = kGridInk,
                            .width = 0.5,
                            .clip_to_picture = false,
                            .role = "grid"});
    for (const double t : x_axis.ticks)
      page.paths.push_back({.points = {{x_at(t), top}, {x_at(t), bottom}},
                            .color = kGridInk,
                            .width = 0.5,
                            .clip_to_picture = false,
                            .role = "grid"});
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
    page.paths.push_back({.points = {{left, top}, {right, top}, {right, bottom}, {left, bottom}},
                          .color = kInk,
                          .width = 0.75,
                          .closed = true,
                          .clip_to_picture = false,
                          .role = "axes"});
    for (std::size_t i = 0; i < y_axis.ticks.size(); ++i) {
      const double ty = y_at(y_axis.ticks[i]);
      page.paths.push_back({.points = {{left - kTick, ty}, {left, ty}},
                            .color = kInk,
                            .width = 0.75,
                            .clip_to_picture = false,
                            .role = "tick"});
      page.texts.push_back({.at = {left - kTick - 2.0, ty + 0.35 * kTickSize},
                            .text = y_axis.labels[i],
                            .size = kTickSize,
                            .align = TextAlign::right,
                            .role = "tick"});
    }
    for (std::size_t i = 0; i < x_axis.ticks.size(); ++i) {
      const double tx = x_at(x_axis.ticks[i]);
      page.paths.push_back({.points = {{tx, bottom}, {tx, bottom + kTick}},
                            .color = kInk,
                            .width = 0.75,
                            .clip_to_picture = false,
                            .role = "tick"});
      if (p + 1 == plot.panels.size())
        page.texts.push_back({.at = {tx, bottom + kTick + 2.0 + kTickSize},
                              .text = x_axis.labels[i],
                              .size = kTickSize,
                              .align = TextAlign::centre,
                              .role = "tick"});
    }
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
    std::string line;
    std::size_t i = 0;
    const std::string& text = plot.provenance;
    const auto emit = [&](const std::string& l) {
      y += kProvenanceSize * 1.35;
      page.texts.push_back({.at = {8.0, y},
                            .text = l,
                            .size = kProvenanceSize,
                            .color = {0.4, 0.4, 0.4, 1},
                            .role = "caption"});
    };
    while (i < text.size()) {
      std::size_t j = text.find(' ', i);
      if (j == std::string::npos) j = text.size();
      const std::string word = text.substr(i, j - i);
      const std::string longer = line.empty() ? word : line + " " + word;
      if (!line.empty() && text_width(longer, kProvenanceSize) > plot.width - 16.0) {
        emit(line);
        line = word;
      } else {
        line = longer;
      }
      i = j + 1;
    }
    if (!line.empty()) emit(line);
  }
  page.height = y + 8.0;
  page.picture = {0, 0, page.width, page.height};
  return page;
}

}  // namespace spinfold::render
