// Server-Sent Events: a session's state whenever it changed, checked `rate` times a second.
#include <chrono>
#include <thread>

#include "server/context.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"
#include "server/sessions/session.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

void get_events(ServerContext& server, const Call& call, httplib::Response& res) {
  const std::string id = call.id;
  find_session(server, id);
  const double hz = *call.query.number("rate");
  auto slot = open_stream(server, call.client);
  const auto interval = std::chrono::duration<double>(1.0 / hz);
  std::uint64_t sent = ~std::uint64_t{0};
  res.set_header("Cache-Control", "no-cache");
  res.set_chunked_content_provider(
      "text/event-stream", [&server, id, interval, slot, sent](std::size_t, httplib::DataSink& sink) mutable {
        if (server.stopping) return false;
        const auto s = server.sessions.find(id);
        if (!s) {
          sink.done();  // the session is gone: end the stream
          return true;
        }
        std::string event = ":\n\n";  // a comment keeps the connection checked
        {
          const std::lock_guard lock(s->mutex);
          if (s->version != sent) {
            event = "event: state\ndata: " + session_sample(*s).dump() + "\n\n";
            sent = s->version;
          }
        }
        if (!sink.write(event.data(), event.size())) return false;  // the client left
        std::this_thread::sleep_for(interval);
        return true;
      });
}

}  // namespace

std::vector<Route> event_routes(const Limits& limits) {
  return {
      {.method = "GET",
       .path = "/api/v1/sessions/{id}/events",
       .operation_id = "stream_events",
       .handler = get_events,
       .summary = "Server-Sent Events: `event: state` with the state whenever it changed; at most " +
                  std::to_string(limits.max_streams) + " open streams",
       .query = {{.name = "rate",
                  .type = ParamType::number,
                  .unit = "Hz",
                  .minimum = 0.5,
                  .maximum = 60.0,
                  .default_value = 10.0,
                  .description = "how often the state is checked for a change"}},
       .responses = {{200, "text/event-stream"},
                     {429, "stream limit (of the server or the client); Retry-After"}}},
  };
}

}  // namespace spinfold::server
