// Vector figures of a frame (render/figure.h): what the page holds (outline, grid with its hidden
// half left out, trails, legend, labels or scale bar, caption), and that the SVG and PDF files are
// well formed (xmllint, pdfinfo, pdftotext).
#include "render/figure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/simulation.h"
#include "tests/render/figure_tools.h"
#include "tests/render/views/view_test_support.h"

namespace spinfold::render {
namespace {

using figure_test::have_tool;
using figure_test::run_tool;
using figure_test::temporary_file;

struct Figure {
  Snapshot snapshot;
  ViewOptions view;
  FigurePage page;
};

// The preset's frame at t in `kind` (default: the surface's view), aimed as the CLI aims it.
Figure figure_of(const Scene& scene, double t, std::optional<ViewKind> kind = std::nullopt) {
  Simulation run;
  Figure f;
  f.snapshot = snapshot_at(scene, t, true, std::nullopt, run);
  f.view.kind = kind.value_or(default_view(scene.surface.kind));
  f.view.scale = 0.25 * body_scale_length(f.view.kind, scene.surface);
  f.view.layers &= ~static_cast<unsigned>(kHud);
  aim_camera_at_body(f.view, f.snapshot);
  f.view.layers |= kHud;  // the caption
  f.page = figure_page(
      f.snapshot, f.view,
      {"Test scene", "A scene for the tests.", "version=test; scene_hash=0", "{\"software\":\"spinfold\"}"});
  return f;
}
Figure figure_of(const std::string& preset, double t, std::optional<ViewKind> kind = std::nullopt) {
  return figure_of(*parse_scene_text(find_preset(preset)->json).scene, t, kind);
}

std::vector<std::string> texts_of(const FigurePage& page, const std::string& role) {
  std::vector<std::string> texts;
  for (const FigureText& t : page.texts)
    if (t.role == role) texts.push_back(t.text);
  return texts;
}

std::size_t paths_of(const FigurePage& page, const std::string& role) {
  return static_cast<std::size_t>(std::count_if(page.paths.begin(), page.paths.end(),
                                                [&](const FigurePath& p) { return p.role == role; }));
}

double stroked_length(const FigurePage& page, const std::string& role) {
  double length = 0.0;
  for (const FigurePath& p : page.paths)
    if (p.role == role)
      for (std::size_t i = 1; i < p.points.size(); ++i) length += glm::distance(p.points[i - 1], p.points[i]);
  return length;
}

bool contains(const std::vector<std::string>& texts, const std::string& part) {
  return std::any_of(texts.begin(), texts.end(),
                     [&](const std::string& t) { return t.find(part) != std::string::npos; });
}

TEST(Figure, SphereFigureHasOutlineGridTrailsBodiesLegendAndCaption) {
  const Figure f = figure_of("spin_vs_geodesic_sphere", 6.0);
  EXPECT_DOUBLE_EQ(f.page.width, 640 * kPointsPerPixel);
  EXPECT_GT(f.page.height, 480 * kPointsPerPixel + 40.0);  // the caption beneath the picture
  EXPECT_GE(paths_of(f.page, "outline"), 1u);
  EXPECT_GE(paths_of(f.page, "grid"), 10u);
  EXPECT_GE(paths_of(f.page, "body"), 2u);  // two ellipses (fills and outlines) and arrows
  // The main body's trail is one solid path; the geodesic companion's is dashed into many.
  EXPECT_GE(paths_of(f.page, "trail"), 3u);
  const std::vector<std::string> legend = texts_of(f.page, "legend");
  ASSERT_EQ(legend.size(), 3u);  // the two bodies, and the bending layer's key to the main trail
  EXPECT_EQ(legend[0], "body 1");
  EXPECT_EQ(legend[1], f.snapshot.bodies[1].label);
  EXPECT_EQ(legend[2], "path bends left / right");
  const std::vector<std::string> caption = texts_of(f.page, "caption");
  EXPECT_EQ(caption.front(), "Test scene");
  EXPECT_EQ(caption[1], "A scene for the tests.");
  EXPECT_TRUE(contains(caption, "t = 6.000"));
  EXPECT_TRUE(contains(caption, "energy error = "));
  EXPECT_TRUE(contains(caption, "integrator: "));
  EXPECT_TRUE(contains(caption, "scene_hash=0"));
  EXPECT_TRUE(contains(caption, "Grid: parallels every 15 degrees"));
  // No HUD text and no labels over a 3-D picture.
  EXPECT_TRUE(texts_of(f.page, "label").empty());
}

// The sphere's far side is hidden: of its grid, about half is drawn (every line is drawn in full
// when nothing is hidden).
TEST(Figure, SphereGridBehindTheSurfaceIsLeftOut) {
  const Figure f = figure_of("spinning_rigid_sphere", 1.0);
  ViewOptions view = f.view;
  const FrameScene scene = build_scene(f.snapshot, view);
  ASSERT_NE(scene.statics, nullptr);
  double all = 0.0;
  for (std::size_t i = 0; i + 1 < scene.statics->grid.size(); i += 2) {
    const auto a = pixel_position(scene, view, glm::dvec3(scene.statics->grid[i].position));
    const auto b = pixel_position(scene, view, glm::dvec3(scene.statics->grid[i + 1].position));
    if (a && b) all += glm::distance(*a, *b) * kPointsPerPixel;
  }
  const double drawn = stroked_length(f.page, "grid");
  EXPECT_GT(drawn, 0.3 * all);
  EXPECT_LT(drawn, 0.7 * all);
}

TEST(Figure, FlatViewsOfH2LabelTheirGeodesicCircles) {
  for (const ViewKind kind : {ViewKind::disk, ViewKind::klein, ViewKind::halfplane}) {
    const Figure f = figure_of("spin_vs_geodesic_pseudosphere", 4.0, kind);
    const std::vector<std::string> labels = texts_of(f.page, "label");
    EXPECT_GE(labels.size(), 2u) << view_name(kind);
    for (const std::string& label : labels)
      EXPECT_TRUE(label.starts_with("r = ") && label.ends_with(" R")) << label;
    EXPECT_GE(paths_of(f.page, "outline"), 1u) << view_name(kind);  // the rim, or y = 0
    EXPECT_TRUE(contains(texts_of(f.page, "caption"), "geodesic circles about the pole")) << view_name(kind);
  }
  const Figure disk = figure_of("spin_vs_geodesic_pseudosphere", 4.0, ViewKind::disk);
  EXPECT_TRUE(contains(texts_of(disk.page, "label"), "r = 0.5 R"));
}

TEST(Figure, StereographicDiskOfTheSphereLabelsItsParallelsAsFractionsOfPi) {
  const Figure f = figure_of("spinning_rigid_sphere", 1.0, ViewKind::disk);
  const std::vector<std::string> labels = texts_of(f.page, "label");
  ASSERT_GE(labels.size(), 2u);
  EXPECT_TRUE(contains(labels, "\u03C0R"));
}

TEST(Figure, PlaneAndConformalViewsHaveAScaleBarInLengths) {
  const Figure plane = figure_of("spinning_rigid_plane", 2.0);
  ASSERT_EQ(plane.view.kind, ViewKind::plane);
  EXPECT_EQ(paths_of(plane.page, "scale_bar"), 1u);
  const std::vector<std::string> bar = texts_of(plane.page, "scale_bar");
  ASSERT_EQ(bar.size(), 1u);
  EXPECT_TRUE(bar[0].find("length unit") != std::string::npos) << bar[0];
  EXPECT_TRUE(bar[0].find("centre") == std::string::npos) << bar[0];  // true everywhere on the plane
  const Figure conformal = figure_of("spinning_rigid_sphere", 2.0, ViewKind::conformal);
  const std::vector<std::string> conformal_bar = texts_of(conformal.page, "scale_bar");
  ASSERT_EQ(conformal_bar.size(), 1u);
  EXPECT_TRUE(conformal_bar[0].find("(at the centre)") != std::string::npos) << conformal_bar[0];
}

// Without the hud layer the page is the picture and the legend: a bare figure for a paper's own
// caption (the provenance stays in the file's metadata).
// A main body off what the view draws gets the view's own note in the caption, as in the frame's
// HUD (the figure had the tractricoid's words for every view): a slow spinner's body beyond the
// catenoid's drawn piece at t = 15, still drawn there with its outline.
TEST(Figure, TheCaptionSaysWhereABodyOffTheDrawnPieceIs) {
  const Figure f = figure_of(testing::escaping_catenoid(), 15.0);
  ASSERT_EQ(f.view.kind, ViewKind::revolution);
  const std::vector<std::string> caption = texts_of(f.page, "caption");
  EXPECT_TRUE(contains(caption, "beyond the surface drawn")) << "the revolution view's note";
  EXPECT_FALSE(contains(caption, "beyond the rim"));
  EXPECT_GT(paths_of(f.page, "body"), 0u);
}

TEST(Figure, WithoutTheHudLayerThereIsNoCaption) {
  const Figure f = figure_of("spin_vs_geodesic_sphere", 2.0);
  ViewOptions bare = f.view;
  bare.layers &= ~static_cast<unsigned>(kHud);
  const FigurePage page = figure_page(f.snapshot, bare, {"Test scene", "", "version=test", "{}"});
  EXPECT_TRUE(texts_of(page, "caption").empty());
  EXPECT_EQ(texts_of(page, "legend").size(), 3u);
  EXPECT_LT(page.height, f.page.height);
  EXPECT_EQ(page.title, "Test scene");
}

TEST(Figure, ScaleBarLengthIsOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(scale_bar_length(1.0), 1.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(1.9), 1.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(4.99), 2.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(7.0), 5.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(0.03), 0.02);
  EXPECT_EQ(scale_bar_length(0.0), 0.0);
}

TEST(Figure, CircleLabels) {
  EXPECT_EQ(circle_label(0.5, false), "r = 0.5 R");
  EXPECT_EQ(circle_label(2.0, false), "r = 2 R");
  EXPECT_EQ(circle_label(std::numbers::pi / 12, true), "r = \u03C0R/12");
  EXPECT_EQ(circle_label(std::numbers::pi / 4, true), "r = \u03C0R/4");
  EXPECT_EQ(circle_label(std::numbers::pi * 2 / 3, true), "r = 2\u03C0R/3");
  EXPECT_EQ(circle_label(std::numbers::pi / 2, true), "r = \u03C0R/2");
}

TEST(Figure, SvgIsWellFormedXmlWithTitleAndMetadata) {
  const Figure f = figure_of("spin_vs_geodesic_sphere", 3.0);
  const std::vector<std::uint8_t> svg = draw_figure(f.page, FigureFormat::svg);
  const std::string text(svg.begin(), svg.end());
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("<title>Test scene</title>"), std::string::npos);
  EXPECT_NE(text.find("<metadata>{&quot;software&quot;:&quot;spinfold&quot;}</metadata>"), std::string::npos);
  EXPECT_NE(text.find("width=\"480pt\""), std::string::npos);
  if (!have_tool("xmllint")) GTEST_SKIP() << "xmllint missing (Debian libxml2-utils)";
  const std::string path = temporary_file(svg, ".svg");
  const auto check = run_tool("xmllint --noout " + path);
  EXPECT_EQ(check.exit_code, 0) << check.out;
  std::filesystem::remove(path);
}

TEST(Figure, PdfHasOnePageOfTheFiguresSizeAndItsText) {
  const Figure f = figure_of("spin_vs_geodesic_pseudosphere", 3.0, ViewKind::disk);
  const std::vector<std::uint8_t> pdf = draw_figure(f.page, FigureFormat::pdf);
  ASSERT_GT(pdf.size(), 1000u);
  EXPECT_EQ(std::string(pdf.begin(), pdf.begin() + 5), "%PDF-");
  if (!have_tool("pdfinfo") || !have_tool("pdftotext"))
    GTEST_SKIP() << "pdfinfo missing (Debian poppler-utils)";
  const std::string path = temporary_file(pdf, ".pdf");
  const auto info = run_tool("pdfinfo " + path);
  EXPECT_EQ(info.exit_code, 0) << info.out;
  EXPECT_EQ(figure_test::pdfinfo_field(info.out, "Pages"), "1") << info.out;
  EXPECT_EQ(figure_test::pdfinfo_field(info.out, "Title"), "Test scene") << info.out;
  EXPECT_TRUE(figure_test::pdfinfo_field(info.out, "Page size").starts_with("480 x ")) << info.out;
  const auto text = run_tool("pdftotext " + path + " -");
  EXPECT_EQ(text.exit_code, 0) << text.out;
  EXPECT_NE(text.out.find("body 1"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("energy error"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("r = 0.5 R"), std::string::npos) << text.out;
  std::filesystem::remove(path);
}

// Nothing in a figure depends on the clock (no PDF creation date) or on what was drawn before.
TEST(Figure, TheSameFigureGivesTheSameBytes) {
  const Figure f = figure_of("spinning_rigid_sphere", 2.0);
  for (const FigureFormat format : {FigureFormat::svg, FigureFormat::pdf}) {
    const std::vector<std::uint8_t> first = draw_figure(f.page, format);
    draw_figure(figure_of("spin_vs_geodesic_pseudosphere", 1.0).page, format);
    EXPECT_TRUE(first == draw_figure(f.page, format)) << figure_format_name(format);
  }
  const std::vector<std::uint8_t> pdf = draw_figure(f.page, FigureFormat::pdf);
  EXPECT_EQ(std::string(pdf.begin(), pdf.end()).find("/CreationDate"), std::string::npos);
}

}  // namespace
}  // namespace spinfold::render
