#include "bench/soak.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <string_view>
#include <thread>
#include <vector>

#include "server/api.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::bench {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// VmRSS of a process [KiB], or -1.
long rss_kib(int pid) {
  std::ifstream status(pid ? "/proc/" + std::to_string(pid) + "/status" : std::string("/proc/self/status"));
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

struct Tally {
  std::mutex mutex;
  std::map<std::string, std::vector<double>> latency_ms;  // per operation
  std::map<std::string, long> errors, refused;            // refused: 429/503 with Retry-After
  void add(const std::string& op, double ms, int status) {
    const std::lock_guard lock(mutex);
    latency_ms[op].push_back(ms);
    if (status == 429 || status == 503)
      ++refused[op];
    else if (status < 200 || status >= 400)
      ++errors[op];
  }
};

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

// One client: a few sessions of its own, each operation chosen at random.
void client_loop(const std::string& host, int port, Clock::time_point until, unsigned seed, Tally& tally) {
  httplib::Client c(host, port);
  c.set_read_timeout(30, 0);
  std::mt19937 rng(seed);
  std::vector<std::string> ids;
  std::map<std::string, double> times;
  const char* presets[] = {"spinning_rigid_sphere", "deforming_spin_pseudosphere", "breathing_ellipse_sphere",
                           "degenerate_crossing", "separable_radial_abc"};
  const auto timed = [&](const std::string& op, auto&& request) {
    const auto start = Clock::now();
    httplib::Result res = request();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    tally.add(op, ms, res ? res->status : 0);
    return res;
  };
  while (Clock::now() < until) {
    const int pick = static_cast<int>(rng() % 100);
    if (ids.empty() || (pick < 5 && ids.size() < 3)) {
      const json body = {{"preset", presets[rng() % 5]}};
      auto res = timed("create", [&] { return c.Post("/api/v1/sessions", body.dump(), "application/json"); });
      if (res && res->status == 201) ids.push_back(json::parse(res->body)["id"]);
      continue;
    }
    const std::string id = ids[rng() % ids.size()];
    const std::string session = "/api/v1/sessions/" + id;
    if (pick < 8) {
      timed("delete", [&] { return c.Delete(session); });
      ids.erase(std::find(ids.begin(), ids.end(), id));
    } else if (pick < 35) {
      timed("state", [&] { return c.Get(session); });
    } else if (pick < 60) {
      timed("frame", [&] { return c.Get(session + "/frame.png?width=320&height=240"); });
    } else if (pick < 80) {
      times[id] += 0.5;
      const json body = {{"until", times[id]}};
      timed("advance", [&] { return c.Post(session + "/advance", body.dump(), "application/json"); });
    } else if (pick < 92) {
      const json body = {{"body", {{"mass", 0.5 + 0.01 * static_cast<double>(rng() % 150)}}}};
      timed("patch", [&] { return c.Patch(session, body.dump(), "application/merge-patch+json"); });
    } else {
      // An event stream held for ~0.3 s, then dropped by this client (httplib calls that an error):
      // counted as a success when it delivered a state; its time is the time held.
      const auto start = Clock::now();
      const auto stop = start + std::chrono::milliseconds(300);
      bool delivered = false;
      httplib::Result res = c.Get(session + "/events?rate=20", [&](const char* data, std::size_t length) {
        delivered =
            delivered || std::string_view(data, length).find("event: state") != std::string_view::npos;
        return Clock::now() < stop;
      });
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      tally.add("events", ms, res ? res->status : (delivered ? 200 : 0));
    }
  }
  for (const std::string& id : ids) c.Delete("/api/v1/sessions/" + id);
}

}  // namespace

int run_soak(const SoakOptions& options) {
  std::string host = "127.0.0.1";
  int port = 0;
  std::unique_ptr<server::ApiServer> api;
  std::thread serving;
  int pid = options.server_pid;
  if (options.url.empty()) {
    server::ServerOptions so;
    so.port = 0;
    so.data_dir = options.data_dir;
    so.limits.requests_per_second_per_client = 0.0;  // every client here is 127.0.0.1
    api = std::make_unique<server::ApiServer>(so);
    port = api->bind();
    serving = std::thread([&] { api->listen(); });
  } else {
    const auto scheme = options.url.find("://");
    const std::string rest = scheme == std::string::npos ? options.url : options.url.substr(scheme + 3);
    host = rest.substr(0, rest.find(':'));
    port = std::stoi(rest.substr(rest.find(':') + 1));
    if (!pid) pid = -1;  // not ours to read
  }
  const auto rss = [&] { return pid < 0 ? -1L : rss_kib(pid); };
  std::printf("soak: %g min, %d clients, %s:%d\n", options.minutes, options.clients, host.c_str(), port);
  const auto start = Clock::now();
  const auto until = start + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(options.minutes * 60.0));
  const long rss_start = rss();
  Tally tally;
  std::vector<std::thread> clients;
  for (int i = 0; i < options.clients; ++i)
    clients.emplace_back(client_loop, host, port, until, 1234u + static_cast<unsigned>(i), std::ref(tally));
  std::this_thread::sleep_until(start + (until - start) / 2);
  const long rss_middle = rss();
  for (std::thread& t : clients) t.join();
  const long rss_end = rss();
  std::printf("\n%-8s %9s %7s %8s %9s %9s %9s %9s\n", "op", "count", "errors", "refused", "p50 ms", "p90 ms",
              "p99 ms", "max ms");
  long total_errors = 0;
  for (auto& [op, v] : tally.latency_ms) {
    total_errors += tally.errors[op];
    const double max = v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    std::printf("%-8s %9zu %7ld %8ld %9.2f %9.2f %9.2f %9.2f\n", op.c_str(), v.size(), tally.errors[op],
                tally.refused[op], percentile(v, 0.5), percentile(v, 0.9), percentile(v, 0.99), max);
  }
  std::printf("\nserver RSS [MiB]: start %.1f, middle %.1f, end %.1f\n",
              static_cast<double>(rss_start) / 1024, static_cast<double>(rss_middle) / 1024,
              static_cast<double>(rss_end) / 1024);
  if (api) {
    api->stop();
    serving.join();
  }
  return total_errors == 0 ? 0 : 1;
}

}  // namespace spinfold::bench
