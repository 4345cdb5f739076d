// Time-series figures (render/series_plot.h): one panel per quantity over a shared x axis, with
// titles, units, ticks, a factored power of ten, a logarithmic axis, gaps for undefined values and
// a legend where lines are told apart; the files well formed.
#include "render/series_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/render/figure_tools.h"

namespace spinfold::render {
namespace {

SeriesPlot two_panels() {
  SeriesPlot plot;
  plot.title = "A run";
  plot.provenance = "version=test; scene_hash=0";
  for (int i = 0; i <= 100; ++i) plot.x.push_back(0.1 * i);
  PlotPanel error{"energy_error", "", false, {}};
  PlotPanel r{"r", "length", false, {}};
  PlotLine e1{"body 1", {0, 0, 1, 1}, {}}, r1{"body 1", {0, 0, 1, 1}, {}}, r2{"geodesic", {1, 0, 0, 1}, {}};
  for (const double t : plot.x) {
    e1.y.push_back(3e-12 * std::sin(t));
    r1.y.push_back(1.0 + 0.5 * std::cos(t));
    r2.y.push_back(t > 4.0 && t < 5.0 ? std::nan("") : 1.2);  // undefined for a while: a gap
  }
  error.lines.push_back(e1);
  r.lines = {r1, r2};
  plot.panels = {error, r};
  return plot;
}

std::vector<const FigureText*> texts_of(const FigurePage& page, const std::string& role) {
  std::vector<const FigureText*> out;
  for (const FigureText& t : page.texts)
    if (t.role == role) out.push_back(&t);
  return out;
}

bool has_text(const FigurePage& page, const std::string& role, const std::string& text) {
  const auto texts = texts_of(page, role);
  return std::any_of(texts.begin(), texts.end(), [&](const FigureText* t) { return t->text == text; });
}

TEST(SeriesPlot, PanelsHaveAxisTitlesWithUnitsTicksAndOneLegend) {
  const FigurePage page = series_page(two_panels());
  EXPECT_DOUBLE_EQ(page.width, 480.0);
  EXPECT_GT(page.height, 2 * 120.0);
  EXPECT_TRUE(has_text(page, "axis", "t [time]"));
  EXPECT_TRUE(has_text(page, "axis", "r [length]"));
  // ±3e-12: ticks in units of 10⁻¹², the power with the axis's title.
  EXPECT_TRUE(has_text(page, "axis", "energy_error  \u00D710\u207B\u00B9\u00B2"));
  EXPECT_TRUE(has_text(page, "tick", "2"));
  EXPECT_TRUE(has_text(page, "tick", "-2"));
  EXPECT_TRUE(has_text(page, "tick", "10"));  // the x axis ends at t = 10
  // One legend for the panels: the two lines told apart.
  const auto legend = texts_of(page, "legend");
  ASSERT_EQ(legend.size(), 2u);
  EXPECT_EQ(legend[0]->text, "body 1");
  EXPECT_EQ(legend[1]->text, "geodesic");
  // One path for each unbroken line, two for the one with a gap.
  const auto series = std::count_if(page.paths.begin(), page.paths.end(),
                                    [](const FigurePath& p) { return p.role == "series"; });
  EXPECT_EQ(series, 4);
  EXPECT_TRUE(has_text(page, "title", "A run"));
  EXPECT_FALSE(texts_of(page, "caption").empty());
}

TEST(SeriesPlot, LogarithmicAxisShowsDecadesOfTheMagnitude) {
  SeriesPlot plot;
  plot.x = {0, 1, 2, 3};
  plot.panels = {{"energy_error", "", true, {{"body 1", {0, 0, 0, 1}, {1e-14, -1e-12, 0.0, 1e-10}}}}};
  const FigurePage page = series_page(plot);
  EXPECT_TRUE(has_text(page, "axis", "|energy_error|"));
  EXPECT_TRUE(has_text(page, "tick", "10\u207B\u00B9\u00B2"));
  EXPECT_TRUE(has_text(page, "tick", "10\u207B\u00B9\u2070"));
  // The zero is left out: a gap between the two pieces.
  const auto series = std::count_if(page.paths.begin(), page.paths.end(),
                                    [](const FigurePath& p) { return p.role == "series"; });
  EXPECT_EQ(series, 1);  // (0, 1) then a lone point at t = 3: one path of two points
}

TEST(SeriesPlot, MismatchedLengthsAndNoPanelAreRefused) {
  SeriesPlot plot = two_panels();
  plot.panels[0].lines[0].y.pop_back();
  EXPECT_THROW(series_page(plot), std::invalid_argument);
  EXPECT_THROW(series_page(SeriesPlot{}), std::invalid_argument);
}

TEST(SeriesPlot, PowersOfTenAndTitles) {
  EXPECT_EQ(power_of_ten(-12), "10\u207B\u00B9\u00B2");
  EXPECT_EQ(power_of_ten(3), "10\u00B3");
  EXPECT_EQ(axis_title("r", "length"), "r [length]");
  EXPECT_EQ(axis_title("energy_error", ""), "energy_error");
}

TEST(SeriesPlot, SvgAndPdfFilesValidate) {
  const FigurePage page = series_page(two_panels());
  const std::vector<std::uint8_t> svg = draw_figure(page, FigureFormat::svg);
  const std::vector<std::uint8_t> pdf = draw_figure(page, FigureFormat::pdf);
  if (!figure_test::have_tool("xmllint") || !figure_test::have_tool("pdfinfo"))
    GTEST_SKIP() << "xmllint or pdfinfo missing (Debian libxml2-utils, poppler-utils)";
  const std::string svg_path = figure_test::temporary_file(svg, ".svg");
  const std::string pdf_path = figure_test::temporary_file(pdf, ".pdf");
  const auto xml = figure_test::run_tool("xmllint --noout " + svg_path);
  EXPECT_EQ(xml.exit_code, 0) << xml.out;
  const auto info = figure_test::run_tool("pdfinfo " + pdf_path);
  EXPECT_EQ(info.exit_code, 0) << info.out;
  EXPECT_EQ(figure_test::pdfinfo_field(info.out, "Title"), "A run") << info.out;
  std::filesystem::remove(svg_path);
  std::filesystem::remove(pdf_path);
}

}  // namespace
}  // namespace spinfold::render
