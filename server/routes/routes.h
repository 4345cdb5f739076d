// The routes room: the API's table (one file per resource, each listing its rows) and its
// registration on the HTTP server. The machinery of a row (Route, Query, OpenAPI) is
// server/http/route_table.h.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "server/http/route_table.h"
#include "server/options.h"

namespace httplib {
class Server;
}

namespace spinfold::server {

struct ServerContext;

// Every route of the API, with the limits of this server in its parameters' ranges.
std::vector<Route> route_table(const Limits& limits);

// Each resource's rows (server/routes/: catalog.cpp, sessions.cpp, frames.cpp, events.cpp, live.cpp,
// recordings.cpp, work_precision.cpp, drag.cpp).
std::vector<Route> catalog_routes(const Limits& limits);
std::vector<Route> session_routes(const Limits& limits);
std::vector<Route> frame_routes(const Limits& limits);
std::vector<Route> event_routes(const Limits& limits);
std::vector<Route> live_routes(const Limits& limits);
std::vector<Route> recording_routes(const Limits& limits);
std::vector<Route> work_precision_routes(const Limits& limits);
std::vector<Route> drag_routes(const Limits& limits);

// GET /api/v1/view-parameters: the view parameters (a side at most limits.max_image_side), the
// layers and the recording formats, from their tables.
nlohmann::ordered_json view_parameters_json(const Limits& limits);

// Registers every route, and 405 (with `Allow`) for a known path asked with another method.
void register_routes(httplib::Server& http, ServerContext& server, const std::vector<Route>& routes);

// The Allow of a request path: the methods of the route it matches, then OPTIONS (every known path
// answers it); "" for a path no route has. For the methods the router cannot register (TRACE, …).
std::string allow_at(const std::vector<Route>& routes, const std::string& path);

}  // namespace spinfold::server
