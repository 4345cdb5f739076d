// A plot's axis, linear or logarithmic: the range shown, its ticks and their labels. Shared by the
// time-series plots (render/series_plot.h) and the curves plots (render/curves_plot.h).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/figure_page.h"

namespace spinfold::render {

// One axis, in its own coordinate (log10 of the value when logarithmic).
struct PlotAxis {
  double lo = 0, hi = 1;
  std::vector<double> ticks;
  std::vector<std::string> labels;
  std::string factor;  // "×10⁻¹²": the labels' common power of ten, shown with the title
  double to_unit(double v) const { return (v - lo) / (hi - lo); }  // 0 at lo, 1 at hi
};

// The axis over [lo, hi] (log: in decades, labelled 10ᵏ; fewer labels when there are many; a range
// under a decade gets plain numbers); a range of one value is widened; `pad` adds 5 % each side.
PlotAxis make_axis(double lo, double hi, bool log, bool pad);

// The plots' lettering and ink [pt].
inline constexpr double kPlotTickSize = 7.5, kPlotAxisSize = 8.5, kPlotTitleSize = 10.0;
inline constexpr double kPlotTick = 3.0;  // tick mark length [pt]
inline const glm::dvec4 kPlotInk{0.1, 0.1, 0.1, 1.0};
inline const glm::dvec4 kPlotGridInk{0.88, 0.88, 0.88, 1.0};

// A plotting area on the page [pt].
struct PlotBox {
  double left = 0, top = 0, right = 1, bottom = 1;
  double x_at(const PlotAxis& a, double v) const { return left + a.to_unit(v) * (right - left); }
  double y_at(const PlotAxis& a, double v) const { return bottom - a.to_unit(v) * (bottom - top); }
};

// Grid lines at both axes' ticks (drawn first, under the data).
void add_plot_grid(FigurePage& page, const PlotBox& box, const PlotAxis& x, const PlotAxis& y);
// The frame, the ticks and the y axis's labels; the x axis's labels too when `x_labels`.
void add_plot_frame(FigurePage& page, const PlotBox& box, const PlotAxis& x, const PlotAxis& y,
                    bool x_labels);

// A number as a tick label ("%.4g").
std::string tick_number(double v, const char* pattern = "%.4g");

}  // namespace spinfold::render
