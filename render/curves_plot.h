// Curves of points (x, y), each with its own points, on linear or logarithmic axes, as a vector
// figure (render/figure_page.h): lines through the points with a marker at each, a legend below
// or beside the plot, the title above. The work-precision plot (workprecision/) is one: a method's
// error against its cost.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/figure_page.h"

namespace spinfold::render {

struct Curve {
  std::string label{};               // the legend's text
  std::vector<glm::dvec2> points{};  // in order; a point with a coordinate NaN or ≤ 0 on a log axis is a gap
  bool dashed = false;               // drawn dashed (e.g. a method outside the catalog)
};

struct CurvesPlot {
  std::string x_title{}, y_title{};  // the axes' titles, units included
  bool x_log = true, y_log = true;
  std::vector<Curve> curves{};  // coloured and marked in turn (curve_color, curve_marker)
  std::string title{};          // above the plot (bold; the file's title)
  std::string metadata{};       // written into the file
  double width = 360;           // of the page [pt]
  double plot_height = 240;     // of the plotting area [pt]
  bool legend_below = true;     // else in a column on the right
};

// The page; an empty plot says "nothing to plot" where its curves would be.
FigurePage curves_page(const CurvesPlot& plot);

// Curve k's colour and marker: 10 colours (Tableau's, told apart in print and by most colour-blind
// readers) in turn, and 4 markers (circle, square, triangle, diamond) in turn: 20 curves differ.
glm::dvec4 curve_color(std::size_t k);
std::vector<glm::dvec2> curve_marker(std::size_t k, glm::dvec2 at, double size);

}  // namespace spinfold::render
