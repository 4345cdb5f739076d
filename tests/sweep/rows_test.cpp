// The sweep's row writer: formats, columns, the header and one line per row.
#include "sweep/rows.h"

#include <gtest/gtest.h>

#include "codec/presets.h"

namespace spinfold::sweep {
namespace {

Plan plan() {
  Definition def;
  def.base_text = std::string(find_preset("spinning_rigid_sphere")->json);
  def.axes.push_back(axis_from_spec("integrator.name", "auto,dop853", "--set integrator.name"));
  def.fields = "t,r";
  return make_plan(std::move(def));
}

TEST(SweepRows, FormatsFromThePath) {
  EXPECT_EQ(format_of(""), Format::csv);
  EXPECT_EQ(format_of("-"), Format::csv);
  EXPECT_EQ(format_of("a.csv"), Format::csv);
  EXPECT_EQ(format_of("a.jsonl"), Format::jsonl);
  EXPECT_THROW(format_of("rows.txt"), SweepError);
}

TEST(SweepRows, ColumnsHeaderAndRows) {
  const Plan p = plan();
  EXPECT_EQ(column_names(p), (std::vector<std::string>{"index", "integrator.name", "t", "r", "events",
                                                       "status", "detail", "steps", "seconds"}));
  const std::string csv = header_text(p, Format::csv, {1, 2}, "spinfold sweep x");
  // The names first, dots written '_' (numpy.genfromtxt(names=True, comments="#") reads them as they
  // are), then the provenance as comment lines.
  EXPECT_TRUE(
      csv.starts_with("index,integrator_name,t,r,events,status,detail,steps,seconds\n# spinfold sweep "))
      << csv;
  EXPECT_NE(csv.find("\n# command: spinfold sweep x\n# runs: 2\n# definition: " + definition_hash(p) +
                     "\n# shard: 1/2\n"),
            std::string::npos);
  EXPECT_TRUE(csv.ends_with("}\n")) << csv;  // the base's provenance is the last line
  const auto jsonl = nlohmann::json::parse(header_text(p, Format::jsonl, {}, "c"));
  EXPECT_EQ(jsonl["sweep"]["runs"], 2);
  EXPECT_EQ(jsonl["sweep"]["shard"], "0/1");
  Row row{.index = 7,
          .cells = {{"integrator.name", "auto"}, {"r", 0.5}, {"detail", "a, b"}, {"x", nullptr}},
          .ok = true};
  EXPECT_EQ(row_text(row, Format::csv), "7,auto,0.5,\"a, b\",\n");
  EXPECT_EQ(row_text(row, Format::jsonl),
            "{\"index\":7,\"integrator.name\":\"auto\",\"r\":0.5,\"detail\":\"a, b\",\"x\":null}\n");
}

TEST(SweepRows, TheDefinitionHashIsWhatMakesTheRows) {
  const Plan a = plan();
  Plan b = plan();
  EXPECT_EQ(definition_hash(a), definition_hash(b));
  b.def.t_end = 11.0;
  EXPECT_NE(definition_hash(a), definition_hash(b));
}

}  // namespace
}  // namespace spinfold::sweep
