// Time series as a vector figure for a paper (render/figure_page.h): one panel per quantity,
// stacked over a shared x axis, each with its own y axis (label, unit, ticks; linear, or
// logarithmic in |y|), one legend above them where there is more than one line (the body and its
// companions), and the provenance beneath. `spinfold plot` (cli/figure_command.h) fills it from a run.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/figure_page.h"

namespace spinfold::render {

struct PlotLine {
  std::string label;             // the legend's text ("body 1", a companion's label)
  glm::dvec4 color{0, 0, 0, 1};  // RGBA in [0, 1]
  std::vector<double> y;         // one per SeriesPlot::x; NaN (undefined): a gap
};

struct PlotPanel {
  std::string quantity;  // the column's name (codec/sample_table.h), e.g. "energy_error"
  std::string unit;      // "time", "length", … ; "" for a pure number
  bool log = false;      // a logarithmic axis of |y| (zeros and gaps left out)
  std::vector<PlotLine> lines;
};

struct SeriesPlot {
  std::string x_quantity = "t";
  std::string x_unit = "time";
  std::vector<double> x;
  std::vector<PlotPanel> panels;
  std::string title;          // the scene's name, above the panels (bold; the file's title)
  std::string description;    // the scene's one line, under the title
  std::string provenance;     // one line beneath (codec/provenance.h's provenance_header)
  std::string metadata;       // written into the file (the provenance JSON)
  double width = 480;         // of the page [pt]
  double panel_height = 120;  // of each panel's plotting area [pt]
};

// The page; std::invalid_argument when a line's length differs from x's or there is no panel.
FigurePage series_page(const SeriesPlot& plot);

// An axis's title: "energy_error", "r [length]".
std::string axis_title(const std::string& quantity, const std::string& unit);

// A power of ten as text with superscript digits: "10⁻¹²".
std::string power_of_ten(int exponent);

}  // namespace spinfold::render
