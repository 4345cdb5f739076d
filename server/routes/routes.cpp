#include "server/routes/routes.h"

#include <algorithm>
#include <regex>
#include <set>

#include "server/context.h"
#include "server/http/problem.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

// "GET, PATCH, DELETE, OPTIONS": the table's methods for a route path, and OPTIONS.
std::string allow_of(const std::vector<Route>& routes, const std::string& route_path) {
  std::string allow;
  for (const std::string& m : methods_of(routes, route_path)) allow += (allow.empty() ? "" : ", ") + m;
  return allow + ", OPTIONS";
}

}  // namespace

std::string allow_at(const std::vector<Route>& routes, const std::string& path) {
  for (const Route& r : routes)
    if (std::regex_match(path, std::regex(path_regex(r.path)))) return allow_of(routes, r.path);
  return "";
}

std::vector<Route> route_table(const Limits& limits) {
  std::vector<Route> routes;
  for (auto part :
       {catalog_routes(limits), session_routes(limits), frame_routes(limits), drag_routes(limits),
        event_routes(limits), live_routes(limits), recording_routes(limits), work_precision_routes(limits)})
    for (Route& r : part) routes.push_back(std::move(r));
  return routes;
}

void register_routes(httplib::Server& http, ServerContext& server, const std::vector<Route>& routes) {
  // Runs a handler on the parsed query and the body (when the method has one), mapping ApiError
  // to problem+json; every response carries the version. The client's request rate is checked
  // first (server/http/quota.h).
  const auto run = [&server](const Route& route, const httplib::Request& req, httplib::Response& res,
                             const httplib::ContentReader* reader) {
    res.set_header("X-Spinfold-Version", server_version());
    try {
      std::string client = client_address(req, server.options.trusted_proxy);
      server.quotas.admit_request(client);
      std::string body = reader ? bounded_body(req, *reader, server.options.limits.max_body_bytes, res) : "";
      const std::string id = route.path.find("{id}") != std::string::npos ? req.matches[1].str() : "";
      const Call call{req, route, id, std::move(client), parse_query(route, req), std::move(body)};
      route.handler(server, call, res);
    } catch (const ApiError& e) {
      send_error(res, e);
    }
    if (route.method != "GET") server.changes.notify();  // wakes the live streams
  };
  const auto add = [&http, run](const std::string& method, const std::string& pattern, const Route& route) {
    if (method == "GET") {
      http.Get(pattern, [run, route](const httplib::Request& req, httplib::Response& res) {
        run(route, req, res, nullptr);
      });
      return;
    }
    const httplib::Server::HandlerWithContentReader h =
        [run, route](const httplib::Request& req, httplib::Response& res,
                     const httplib::ContentReader& reader) { run(route, req, res, &reader); };
    if (method == "POST") http.Post(pattern, h);
    if (method == "PATCH") http.Patch(pattern, h);
    if (method == "DELETE") http.Delete(pattern, h);
    if (method == "PUT") http.Put(pattern, h);
  };
  const auto add_refusal = [&http](const std::string& method, const std::string& pattern,
                                   httplib::Server::Handler h) {
    if (method == "GET") http.Get(pattern, std::move(h));
    if (method == "POST") http.Post(pattern, std::move(h));
    if (method == "PATCH") http.Patch(pattern, std::move(h));
    if (method == "DELETE") http.Delete(pattern, std::move(h));
    if (method == "PUT") http.Put(pattern, std::move(h));
  };
  std::set<std::string> paths_done;
  for (const Route& route : routes) {
    add(route.method, path_regex(route.path), route);
    if (!paths_done.insert(route.path).second) continue;
    // A known path asked with a method it does not have: 405 with Allow, not the router's 404.
    // Every known path answers OPTIONS too (204 with Allow, RFC 9110 §9.3.7), so Allow names it.
    const std::vector<std::string> allowed = methods_of(routes, route.path);
    const std::string allow = allow_of(routes, route.path);
    http.Options(path_regex(route.path), [allow](const httplib::Request& req, httplib::Response& res) {
      res.set_header("X-Spinfold-Version", server_version());
      try {
        refuse_malformed_chunks(req, res);
      } catch (const ApiError& e) {
        send_error(res, e);
        return;
      }
      res.set_header("Allow", allow);
      res.status = 204;
    });
    const auto refuse = [allow](const httplib::Request& req, httplib::Response& res) {
      res.set_header("X-Spinfold-Version", server_version());
      try {
        refuse_malformed_chunks(req, res);  // ambiguous framing first: 400, not 405 (RFC 9112)
      } catch (const ApiError& e) {
        send_error(res, e);
        return;
      }
      res.set_header("Allow", allow);
      send_error(res, bad(405, "Method not allowed", "method", req.method, "this path allows " + allow));
    };
    for (const char* method : {"GET", "POST", "PATCH", "DELETE", "PUT"})
      if (std::find(allowed.begin(), allowed.end(), method) == allowed.end())
        add_refusal(method, path_regex(route.path), refuse);
  }
}

}  // namespace spinfold::server
