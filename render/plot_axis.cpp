#include "render/plot_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/figure_page.h"
#include "render/series_plot.h"

namespace spinfold::render {

std::string tick_number(double v, const char* pattern) {
  char text[48];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

PlotAxis make_axis(double lo, double hi, bool log, bool pad) {
  PlotAxis a;
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
      for (const double k : a.ticks) a.labels.push_back(tick_number(std::pow(10.0, k), "%.3g"));
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
  for (const double t : a.ticks) a.labels.push_back(tick_number(t / scale));
  return a;
}

void add_plot_grid(FigurePage& page, const PlotBox& box, const PlotAxis& x, const PlotAxis& y) {
  for (const double t : y.ticks)
    page.paths.push_back({.points = {{box.left, box.y_at(y, t)}, {box.right, box.y_at(y, t)}},
                          .color = kPlotGridInk,
                          .width = 0.5,
                          .clip_to_picture = false,
                          .role = "grid"});
  for (const double t : x.ticks)
    page.paths.push_back({.points = {{box.x_at(x, t), box.top}, {box.x_at(x, t), box.bottom}},
                          .color = kPlotGridInk,
                          .width = 0.5,
                          .clip_to_picture = false,
                          .role = "grid"});
}

void add_plot_frame(FigurePage& page, const PlotBox& box, const PlotAxis& x, const PlotAxis& y,
                    bool x_labels) {
  page.paths.push_back(
      {.points = {{box.left, box.top}, {box.right, box.top}, {box.right, box.bottom}, {box.left, box.bottom}},
       .color = kPlotInk,
       .width = 0.75,
       .closed = true,
       .clip_to_picture = false,
       .role = "axes"});
  for (std::size_t i = 0; i < y.ticks.size(); ++i) {
    const double ty = box.y_at(y, y.ticks[i]);
    page.paths.push_back({.points = {{box.left - kPlotTick, ty}, {box.left, ty}},
                          .color = kPlotInk,
                          .width = 0.75,
                          .clip_to_picture = false,
                          .role = "tick"});
    page.texts.push_back({.at = {box.left - kPlotTick - 2.0, ty + 0.35 * kPlotTickSize},
                          .text = y.labels[i],
                          .size = kPlotTickSize,
                          .align = TextAlign::right,
                          .role = "tick"});
  }
  for (std::size_t i = 0; i < x.ticks.size(); ++i) {
    const double tx = box.x_at(x, x.ticks[i]);
    page.paths.push_back({.points = {{tx, box.bottom}, {tx, box.bottom + kPlotTick}},
                          .color = kPlotInk,
                          .width = 0.75,
                          .clip_to_picture = false,
                          .role = "tick"});
    if (x_labels)
      page.texts.push_back({.at = {tx, box.bottom + kPlotTick + 2.0 + kPlotTickSize},
                            .text = x.labels[i],
                            .size = kPlotTickSize,
                            .align = TextAlign::centre,
                            .role = "tick"});
  }
}

}  // namespace spinfold::render
