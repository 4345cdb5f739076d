// Curves of points on log or linear axes (render/curves_plot.h), and a page drawn as a PNG
// (raster_figure): what is drawn where, read off the page and off the decoded pixels.
#include "render/curves_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "render/plot_axis.h"
#include "render/series_plot.h"
#include "tests/render/figure_tools.h"
#include "tests/render/frame_compare.h"

namespace spinfold::render {
namespace {

// Two methods: error falling with cost, one with a point that cannot be drawn on a log axis (0)
// and one outside the catalog (dashed).
CurvesPlot two_methods() {
  CurvesPlot plot{.x_title = "state error", .y_title = "cost [s]", .title = "work-precision: test"};
  plot.curves.push_back({"dop853", {{1e-4, 1e-6}, {1e-8, 3e-6}, {0.0, 5e-6}, {1e-12, 1e-5}}});
  plot.curves.push_back({"odeint", {{1e-3, 2e-6}, {1e-9, 2e-5}}, true});
  return plot;
}

std::vector<const FigurePath*> paths_of(const FigurePage& page, const std::string& role) {
  std::vector<const FigurePath*> out;
  for (const FigurePath& p : page.paths)
    if (p.role == role) out.push_back(&p);
  return out;
}

TEST(CurvesPlot, EachCurveAndMarkerWhereItsPointsAreWithGapsLeftOut) {
  const FigurePage page = curves_page(two_methods());
  // dop853's zero error splits its line in two runs (of 2 and 1 points: the single one has no line).
  const auto curves = paths_of(page, "curve");
  ASSERT_EQ(curves.size(), 2u);
  EXPECT_EQ(curves[0]->points.size(), 2u);
  EXPECT_TRUE(curves[0]->dash.empty());
  EXPECT_FALSE(curves[1]->dash.empty()) << "a method outside the catalog is dashed";
  EXPECT_EQ(paths_of(page, "marker").size(), 3u + 2u) << "a marker on every drawable point";
  EXPECT_NE(curves[0]->color, curves[1]->color);
  // The x axis is logarithmic from 10⁻¹² to 10⁻³: 1e-12 lies left of 1e-8, and decades are equally
  // spaced (1e-4 and 1e-8 as far apart as 1e-8 and 1e-12).
  const double a = curves[0]->points[0].x, b = curves[0]->points[1].x;
  EXPECT_LT(b, a);
  const auto markers = paths_of(page, "marker");
  const auto centre = [](const FigurePath* p) {
    glm::dvec2 c(0.0);
    for (const glm::dvec2 q : p->points) c += q;
    return c / static_cast<double>(p->points.size());
  };
  EXPECT_NEAR(centre(markers[0]).x - centre(markers[1]).x, centre(markers[1]).x - centre(markers[2]).x, 1e-9);
  // Ticks labelled as powers of ten; the legend names both methods; the titles are there.
  std::vector<std::string> texts;
  for (const FigureText& t : page.texts) texts.push_back(t.text);
  const auto has = [&](const std::string& s) { return std::ranges::find(texts, s) != texts.end(); };
  EXPECT_TRUE(has(power_of_ten(-8)));
  EXPECT_TRUE(has("dop853") && has("odeint") && has("state error") && has("cost [s]"));
  EXPECT_TRUE(has("work-precision: test"));
}

TEST(CurvesPlot, TheLegendBesideNarrowsThePlotAndAnEmptyPlotSaysSo) {
  CurvesPlot below = two_methods(), beside = two_methods();
  beside.legend_below = false;
  const auto right_edge = [](const FigurePage& page) { return paths_of(page, "axes").front()->points[1].x; };
  EXPECT_LT(right_edge(curves_page(beside)), right_edge(curves_page(below)));
  CurvesPlot empty = two_methods();
  for (Curve& c : empty.curves) c.points = {{0.0, 1.0}, {std::nan(""), 1.0}};
  const FigurePage page = curves_page(empty);
  EXPECT_TRUE(paths_of(page, "curve").empty());
  EXPECT_TRUE(std::ranges::any_of(page.texts,
                                  [](const FigureText& t) { return t.text.starts_with("nothing to plot"); }));
}

TEST(CurvesPlot, TwentyCurvesAreToldApartByColourOrMarker) {
  for (std::size_t i = 0; i < 20; ++i)
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_TRUE(curve_color(i) != curve_color(j) ||
                  curve_marker(i, {0, 0}, 1.0).size() != curve_marker(j, {0, 0}, 1.0).size() ||
                  curve_marker(i, {0, 0}, 1.0) != curve_marker(j, {0, 0}, 1.0))
          << i << " and " << j;
}

// The PNG of a page: its size is the page's at the scale, and its pixels are the page's colours
// where the page paints them (a filled square, the white background).
TEST(RasterFigure, ThePagesPixelsAtItsScale) {
  FigurePage page;
  page.width = 100, page.height = 50, page.picture = {0, 0, 100, 50};
  page.title = "a square";
  page.paths.push_back(
      {.points = {{10, 10}, {30, 10}, {30, 30}, {10, 30}}, .color = {0.8, 0.1, 0.2, 1}, .filled = true});
  const std::vector<std::uint8_t> png = raster_figure(page, 2.0);
  const auto image = test::decode_png(png);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 200);
  EXPECT_EQ(image->height, 100);
  const auto pixel = [&](int x, int y) {
    const std::uint8_t* p = &image->rgb[3 * (static_cast<std::size_t>(y) * image->width + x)];
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  const std::array<int, 3> inside = pixel(40, 40);  // the square is 20..60 px
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(inside[c], (255.0 * std::array{0.8, 0.1, 0.2}[c]), 1.0) << c;
  EXPECT_EQ(pixel(150, 80), (std::array<int, 3>{255, 255, 255}));
  EXPECT_EQ(raster_figure(page, 2.0), png) << "the same page, the same bytes";
  EXPECT_NE(std::string(png.begin(), png.end()).find("a square"), std::string::npos) << "the title as text";
  EXPECT_THROW(raster_figure(page, 0.0), std::invalid_argument);
  EXPECT_THROW(raster_figure(page, 100.0), std::invalid_argument);  // 10000 pixels wide
}

// The work-precision plot's files validate as SVG (xmllint) when the tool is there.
TEST(CurvesPlot, SvgValidates) {
  if (!figure_test::have_tool("xmllint")) GTEST_SKIP() << "xmllint missing (package libxml2-utils)";
  const std::vector<std::uint8_t> svg = draw_figure(curves_page(two_methods()), FigureFormat::svg);
  const std::string path = figure_test::temporary_file(svg, ".svg");
  const figure_test::ToolResult r = figure_test::run_tool("xmllint --noout " + path);
  std::remove(path.c_str());
  EXPECT_EQ(r.exit_code, 0) << r.out;
}

}  // namespace
}  // namespace spinfold::render
