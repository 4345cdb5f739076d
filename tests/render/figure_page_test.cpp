// The page of a vector figure (render/figure_page.h): formats by name and extension, the ticks of
// an axis, text widths in the figure's font, and a page of each kind of path drawn by cairo into
// files that validate (xmllint, pdfinfo).
#include "render/figure_page.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/render/figure_tools.h"

namespace spinfold::render {
namespace {

TEST(FigurePage, FormatsByNameAndExtension) {
  EXPECT_EQ(parse_figure_format("svg"), FigureFormat::svg);
  EXPECT_EQ(parse_figure_format("jpg"), std::nullopt);
  EXPECT_EQ(figure_format_of_path("out/figure.PDF"), FigureFormat::pdf);
  EXPECT_EQ(figure_format_of_path("figure.png"), FigureFormat::png);
  EXPECT_EQ(figure_format_of_path("figure.jpg"), std::nullopt);
  EXPECT_EQ(figure_format_of_path("dir.svg/figure"), std::nullopt);
  EXPECT_EQ(figure_content_type(FigureFormat::svg), "image/svg+xml");
  EXPECT_EQ(figure_content_type(FigureFormat::pdf), "application/pdf");
  EXPECT_THROW(draw_figure(FigurePage{}, FigureFormat::png), std::invalid_argument);
}

TEST(FigurePage, NiceTicksAreRoundNumbersCoveringTheRange) {
  EXPECT_EQ(nice_ticks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(nice_ticks(-0.3, 0.3, 5), (std::vector<double>{-0.2, 0, 0.2}));  // steps of 0.2: 1, 2 or 5 × 10ᵏ
  const std::vector<double> tenths = nice_ticks(-0.3, 0.3, 6);
  ASSERT_EQ(tenths.size(), 7u);
  for (std::size_t i = 0; i < tenths.size(); ++i)
    EXPECT_NEAR(tenths[i], -0.3 + 0.1 * static_cast<double>(i), 1e-12);
  EXPECT_EQ(tenths[3], 0.0);  // an exact zero, never -2.8e-17
  const std::vector<double> small = nice_ticks(1e-12, 9e-12, 4);
  ASSERT_FALSE(small.empty());
  EXPECT_NEAR(small.front(), 2e-12, 1e-24);
  EXPECT_TRUE(nice_ticks(std::nan(""), 1.0, 5).empty());
}

TEST(FigurePage, TextWidthGrowsWithTheTextTheSizeAndTheWeight) {
  const double word = text_width("energy", 10.0);
  EXPECT_GT(word, 20.0);  // DejaVu Sans: about 0.6 em a letter
  EXPECT_LT(word, 50.0);
  EXPECT_NEAR(text_width("energy", 20.0), 2.0 * word, 1e-6 * word);  // unhinted: in proportion
  EXPECT_GT(text_width("energy error", 10.0), word);
  EXPECT_GT(text_width("energy", 10.0, true), word);
  EXPECT_EQ(text_width("", 10.0), 0.0);
}

TEST(FigurePage, XmlEscapes) {
  EXPECT_EQ(xml_escape("a < b & \"c\" > 'd'"), "a &lt; b &amp; &quot;c&quot; &gt; &apos;d&apos;");
}

// Every kind of path and text: a fill of two polygons (runs), a dashed closed stroke, a stroke cut
// to the picture, turned and centred text with a halo; both files validate and carry the title.
TEST(FigurePage, EveryKindOfPathDrawsIntoValidFiles) {
  FigurePage page;
  page.width = 200;
  page.height = 120;
  page.picture = {10, 10, 100, 100};
  page.title = "A <page> & its title";
  page.metadata = "{\"software\":\"spinfold\"}";
  page.paths.push_back({.points = {{0, 0}, {50, 0}, {0, 50}, {60, 60}, {90, 60}, {60, 90}},
                        .runs = {3, 3},
                        .color = {0.2, 0.4, 0.8, 0.5},
                        .filled = true});
  page.paths.push_back({.points = {{20, 20}, {80, 20}, {80, 80}},
                        .width = 1.5,
                        .closed = true,
                        .dash = {3.0, 2.0},
                        .clip_to_picture = false});
  page.paths.push_back({.points = {{-50, 50}, {250, 50}}, .width = 0.5});
  page.texts.push_back({.at = {100, 100}, .text = "r = 0.5 R", .align = TextAlign::centre, .halo = true});
  page.texts.push_back({.at = {8, 60}, .text = "energy_error \u00D710\u207B\u2077", .angle = M_PI / 2});
  const std::vector<std::uint8_t> svg = draw_figure(page, FigureFormat::svg);
  const std::vector<std::uint8_t> pdf = draw_figure(page, FigureFormat::pdf);
  const std::string text(svg.begin(), svg.end());
  EXPECT_NE(text.find("<title>A &lt;page&gt; &amp; its title</title>"), std::string::npos);
  EXPECT_NE(text.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(text.find("clip-path"), std::string::npos);        // the third path, cut to the picture
  EXPECT_NE(text.find("id=\"surface1\""), std::string::npos);  // cairo's counter renumbered
  if (!figure_test::have_tool("xmllint") || !figure_test::have_tool("pdfinfo"))
    GTEST_SKIP() << "xmllint or pdfinfo missing (Debian libxml2-utils, poppler-utils)";
  const std::string svg_path = figure_test::temporary_file(svg, ".svg");
  const std::string pdf_path = figure_test::temporary_file(pdf, ".pdf");
  const auto xml = figure_test::run_tool("xmllint --noout " + svg_path);
  EXPECT_EQ(xml.exit_code, 0) << xml.out;
  const auto info = figure_test::run_tool("pdfinfo " + pdf_path);
  EXPECT_EQ(info.exit_code, 0) << info.out;
  EXPECT_EQ(figure_test::pdfinfo_field(info.out, "Title"), page.title);
  EXPECT_EQ(figure_test::pdfinfo_field(info.out, "Page size"), "200 x 120 pts");
  std::filesystem::remove(svg_path);
  std::filesystem::remove(pdf_path);
}

}  // namespace
}  // namespace spinfold::render
