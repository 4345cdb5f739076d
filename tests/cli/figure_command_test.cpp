// `spinfold render --format png|svg|pdf` and `spinfold plot` (cli/figure_command.h) as a user runs
// them: the format by the extension, a name that disagrees refused with exit 2 before any work, the
// files well formed (xmllint, pdfinfo) and holding what they should.
#include "cli/figure_command.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/cli/run_spinfold.h"
#include "tests/render/figure_tools.h"

namespace spinfold::cli {
namespace {

using cli_test::run_spinfold;

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("spinfold_fig_" + std::to_string(getpid()) + "_" + name))
      .string();
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(CliFigure, RenderWritesAnSvgByTheExtension) {
  const std::string out = temp("frame.svg");
  const auto r = run_spinfold("render --scene spin_vs_geodesic_sphere --t 3 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = read(out);
  EXPECT_TRUE(svg.starts_with("<?xml")) << svg.substr(0, 40);
  EXPECT_NE(svg.find("<title>spin_vs_geodesic_sphere"), std::string::npos);
  EXPECT_NE(svg.find("scene_hash"), std::string::npos);  // the provenance in <metadata>
  if (figure_test::have_tool("xmllint")) {
    const auto check = figure_test::run_tool("xmllint --noout " + out);
    EXPECT_EQ(check.exit_code, 0) << check.out;
  }
  std::filesystem::remove(out);
}

TEST(CliFigure, RenderWritesAPdfWithTheCaption) {
  const std::string out = temp("frame.pdf");
  const auto r = run_spinfold(
      "render --scene spin_vs_geodesic_pseudosphere --view halfplane --t 2 --format pdf --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(read(out).starts_with("%PDF-"));
  if (!figure_test::have_tool("pdfinfo") || !figure_test::have_tool("pdftotext"))
    GTEST_SKIP() << "pdfinfo missing (Debian poppler-utils)";
  const auto info = figure_test::run_tool("pdfinfo " + out);
  EXPECT_EQ(info.exit_code, 0) << info.out;
  const auto text = figure_test::run_tool("pdftotext " + out + " -");
  EXPECT_NE(text.out.find("t = 2.000"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("integrator:"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("r = 0.5 R"), std::string::npos) << text.out;  // a labelled geodesic circle
  std::filesystem::remove(out);
}

TEST(CliFigure, PngStaysTheDefault) {
  const std::string out = temp("frame");  // no extension: a PNG, as before
  const auto r = run_spinfold("render --scene spinning_rigid_sphere --width 160 --height 120 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read(out).substr(1, 3), "PNG");
  std::filesystem::remove(out);
}

TEST(CliFigure, AnExtensionThatDisagreesIsRefusedWithExitTwo) {
  const std::string png = temp("mismatch.png");
  auto r = run_spinfold("render --scene spinning_rigid_sphere --format svg --out " + png);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ends in .png but --format is svg"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(png));
  r = run_spinfold("render --scene spinning_rigid_sphere --out " + temp("figure.jpg"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("names no format"), std::string::npos) << r.err;
  r = run_spinfold("render --scene spinning_rigid_sphere --format eps --out " + temp("figure.eps"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--format: must be png, svg or pdf (got 'eps')"), std::string::npos) << r.err;
}

TEST(CliFigure, RenderFormatFollowsTheExtensionAndTheOption) {
  EXPECT_EQ(render_format("", "a.svg"), render::FigureFormat::svg);
  EXPECT_EQ(render_format("", "a.PDF"), render::FigureFormat::pdf);
  EXPECT_EQ(render_format("", "a"), render::FigureFormat::png);
  EXPECT_EQ(render_format("pdf", "dir.d/a"), render::FigureFormat::pdf);
  EXPECT_EQ(render_format("svg", "a.svg"), render::FigureFormat::svg);
  EXPECT_THROW(render_format("png", "a.pdf"), FigureInputError);
  EXPECT_THROW(render_format("", "a.tiff"), FigureInputError);
}

TEST(CliFigure, PlotDrawsTheFieldsAgainstTime) {
  const std::string svg = temp("series.svg"), pdf = temp("series.pdf");
  auto r = run_spinfold(
      "plot --scene spin_vs_geodesic_sphere --fields t,energy_error,r --log energy_error "
      "--t-end 4 --out " +
      svg);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(read(svg).starts_with("<?xml"));
  r = run_spinfold(
      "plot --scene spin_vs_geodesic_sphere --fields t,energy_error,r --t-end 4 --every 0.05 --out " + pdf);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  if (figure_test::have_tool("xmllint")) {
    const auto check = figure_test::run_tool("xmllint --noout " + svg);
    EXPECT_EQ(check.exit_code, 0) << check.out;
  }
  if (figure_test::have_tool("pdftotext")) {
    const auto text = figure_test::run_tool("pdftotext " + pdf + " -");
    EXPECT_NE(text.out.find("t [time]"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("r [length]"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("body 1"), std::string::npos) << text.out;  // the legend: body and companion
  }
  std::filesystem::remove(svg);
  std::filesystem::remove(pdf);
}

TEST(CliFigure, PlotRefusesBadInputWithExitTwo) {
  const std::string out = temp("bad.svg");
  struct Case {
    std::string args, message;
  };
  for (const Case& c : {Case{"--fields t,nonsense --out " + out, "'nonsense' is not a numeric column"},
                        Case{"--fields t --out " + out, "--fields: an x axis and at least one quantity"},
                        Case{"--fields t,r --log energy_error --out " + out, "--log: 'energy_error'"},
                        Case{"--fields t,r --out " + temp("bad.png"), "plot writes svg or pdf"},
                        Case{"--fields t,r --t-end -1 --out " + out, "--t-end"},
                        Case{"--scene nosuch --out " + out, "no preset named 'nosuch'"}}) {
    const auto r = run_spinfold("plot " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
  }
}

// A paper's figure (issue 35): the axes say symbols and units from the column table ("|ΔH/H₀|",
// "λ", "t [time]"), not the raw names, and --no-footer leaves the provenance line out of the page
// (it stays in the file's metadata).
TEST(CliFigure, PlotLabelsAxesWithSymbolsAndUnitsAndCanDropItsFooter) {
  if (!figure_test::have_tool("pdftotext")) GTEST_SKIP() << "pdftotext missing (Debian poppler-utils)";
  const std::string pdf = temp("paper.pdf"), bare = temp("bare.pdf");
  const std::string args =
      "plot --scene separable_radial_abc --fields t,energy_error,lambda --log energy_error --t-end 2 --out ";
  auto r = run_spinfold(args + pdf);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = figure_test::run_tool("pdftotext " + pdf + " -").out;
  EXPECT_NE(text.find("|\u0394H/H\u2080|"), std::string::npos) << text;
  EXPECT_NE(text.find("t [time]"), std::string::npos) << text;
  EXPECT_EQ(text.find("|energy_error|"), std::string::npos) << text;  // (the footer's command has the name)
  EXPECT_NE(text.find("scene_hash="), std::string::npos) << text;     // the footer
  r = run_spinfold(args + bare + " --no-footer");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(figure_test::run_tool("pdftotext " + bare + " -").out.find("scene_hash="), std::string::npos);
  EXPECT_NE(figure_test::run_tool("pdfinfo " + bare).out.find("scene_hash"), std::string::npos);  // metadata
  std::filesystem::remove(pdf);
  std::filesystem::remove(bare);
}

}  // namespace
}  // namespace spinfold::cli
