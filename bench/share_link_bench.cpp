#include "bench/share_link_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "bench/timing.h"
#include "codec/scene_json.h"
#include "engine/timeline.h"
#include "server/api.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::bench {

namespace {

using nlohmann::json;

// A deforming, spinning affine body on the sphere; `integrator` picks dop853 or the closed form
// (abc potential, no radial term: `exact` applies).
json bench_scene(const char* integrator) {
  return {{"surface", {{"kind", "sphere"}, {"radius", 1.0}}},
          {"body", {{"mass", 1.0}, {"inertia", 0.2}, {"model", "affine"}}},
          {"potential", {{"deformation", {{"kind", "abc"}, {"A", 0.0}, {"B", 0.0}, {"C", 0.5}}}}},
          {"initial", {{"r", 1.2}, {"lambda", 1.3}, {"mu", 0.7}, {"phi_dot", 0.3}, {"alpha_dot", 0.8}}},
          {"integrator", {{"name", integrator}, {"dt", 0.01}, {"tolerance", 1e-10}}}};
}

// Five changes spread over [0, until): mass, inertia, the potential, the radius, the mass again.
json bench_timeline(double until) {
  json t = json::array();
  t.push_back({{"t", 0.1 * until}, {"patch", {{"body", {{"mass", 1.5}}}}}});
  t.push_back({{"t", 0.3 * until}, {"patch", {{"body", {{"inertia", 0.3}}}}}});
  t.push_back({{"t", 0.5 * until}, {"patch", {{"potential", {{"deformation", {{"C", 0.3}}}}}}}});
  t.push_back({{"t", 0.7 * until}, {"patch", {{"surface", {{"radius", 1.3}}}}}});
  t.push_back({{"t", 0.9 * until}, {"patch", {{"body", {{"mass", 1.0}}}}}});
  return t;
}

}  // namespace

int run_share_link_bench(int repeats, double until) {
  server::ServerOptions options;
  options.port = 0;
  options.limits.requests_per_second_per_client = 0.0;  // one client measuring, not a class
  options.limits.max_sessions_per_client = static_cast<int>(options.limits.max_sessions);
  server::ApiServer api(options);
  const int port = api.bind();
  if (port < 0) {
    std::fprintf(stderr, "share-link: cannot bind\n");
    return 1;
  }
  std::thread serving([&api] { api.listen(); });
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(120, 0);
  const auto post = [&client](const json& body) {
    auto res = client.Post("/api/v1/sessions", body.dump(), "application/json");
    if (!res || res->status != 201) {
      std::fprintf(stderr, "share-link: POST failed (%d): %s\n", res ? res->status : -1,
                   res ? res->body.c_str() : "no answer");
      std::exit(1);
    }
    client.Delete(("/api/v1/sessions/" + json::parse(res->body)["id"].get<std::string>()).c_str());
  };
  std::printf("Opening a share link: POST /api/v1/sessions {scene, timeline of 5 changes, until = %g}\n",
              until);
  std::printf("median of %d, ms; baseline: POST of the bare scene (t = 0) in the same run\n\n", repeats);
  std::printf("%-10s %12s %13s %14s %16s %10s\n", "integrator", "share link", "bare session", "engine replay",
              "replay no trail", "link/bare");
  for (const char* integrator : {"dop853", "exact"}) {
    const json scene = bench_scene(integrator);
    const json link = {{"scene", scene}, {"timeline", bench_timeline(until)}, {"until", until}};
    // The engine alone: the same replay without HTTP and JSON.
    const Scene parsed = *parse_scene(scene).scene;
    std::vector<ParameterChange> changes;
    json current = scene;
    for (const json& change : bench_timeline(until)) {
      current.merge_patch(change["patch"]);
      changes.push_back({change["t"].get<double>(), *parse_scene(current).scene});
    }
    post(link);  // warm up
    const double bare = median_ms(repeats, [&] { post(scene); });
    const double shared = median_ms(repeats, [&] { post(link); });
    const double engine = median_ms(repeats, [&] {
      Simulation run;
      Trail trail;
      replay(parsed, changes, until, run, trail);
    });
    // The same without trail samples: what the trail's sampling costs.
    const double bare_engine = median_ms(repeats, [&] {
      Simulation run = start_simulation(parsed);
      for (const ParameterChange& change : changes) {
        advance_to(run, change.t);
        retune(run, change.scene);
      }
      advance_to(run, until);
    });
    std::printf("%-10s %12.2f %13.2f %14.2f %16.2f %9.1fx\n", integrator, shared, bare, engine, bare_engine,
                shared / bare);
  }
  api.stop();
  serving.join();
  return 0;
}

}  // namespace spinfold::bench
