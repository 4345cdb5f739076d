// `spinfold serve`: the HTTP API (server/) with a session on the default scene, until SIGTERM or
// SIGINT.
#include <pthread.h>

#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include "cli/commands/command.h"
#include "cli/commands/gl_option.h"
#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/scene_json.h"
#include "server/api.h"
#include "server/store/store.h"

namespace spinfold::cli {

namespace {

struct ServeOptions {
  server::ServerOptions server;
  std::string gl;
  bool no_store = false;
};

// Serves until SIGTERM or SIGINT: a thread waits for them (sigwait; blocked in every thread, so
// no handler runs in the middle of anything) and stops the server, which ends the event streams and
// stores the time of playing sessions.
int serve(const server::ServerOptions& options) {
  if (options.port < 0 || options.port > 65535) throw BadInput{"--port: must be 0..65535"};
  if (options.threads < 2 || options.threads > 256) throw BadInput{"--threads: must be 2..256"};
  if (options.frame_ancestors.empty() || options.frame_ancestors.find_first_of(";,\r\n") != std::string::npos)
    throw BadInput{"--frame-ancestors: 'none' or space-separated origins (no ';', ',' or line breaks)"};
  if (options.render_threads < 0 || options.render_threads > 64)
    throw BadInput{"--render-threads: must be 0..64"};
  const double rate = options.limits.requests_per_second_per_client;
  if (!std::isfinite(rate) || rate < 0.0)
    throw BadInput{"--requests-per-second: must be a finite number >= 0 (0: unlimited)"};
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts: they inherit it
  std::unique_ptr<server::ApiServer> api;
  try {
    api = std::make_unique<server::ApiServer>(options);
  } catch (const server::StoreError& e) {
    throw BadInput{std::string("the session store: ") + e.what()};
  }
  const int port = api->bind();
  if (port < 0) {
    std::cerr << "spinfold: cannot listen on " << options.host << ":" << options.port << "\n";
    return 1;
  }
  const std::string id = api->create_session(*parse_scene_text(find_preset(kDefaultPreset)->json).scene);
  const std::string base = "http://" + options.host + ":" + std::to_string(port);
  std::cout << "Spinfold " << version_line() << " serving on " << base << "/\n"
            << "  default scene '" << kDefaultPreset << "': " << base << "/api/v1/sessions/" << id << "\n"
            << "  its frame:  " << base << "/api/v1/sessions/" << id << "/frame.png\n"
            << "  sessions: "
            << (!options.store.empty()     ? "stored in " + server::store_url_for_messages(options.store)
                : options.data_dir.empty() ? "in memory only"
                                           : "stored in " + options.data_dir + "/sessions.db")
            << std::endl;
  std::atomic<bool> signalled{false};
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    signalled = true;
    api->stop();
  });
  const bool served = api->listen();
  if (!signalled) pthread_kill(waiter.native_handle(), SIGTERM);  // listen failed: end the waiter
  waiter.join();
  api.reset();  // joins the player and the render thread before the exit code is returned
  return served || signalled ? 0 : 1;
}
}  // namespace

Command register_serve(CLI::App& app) {
  auto options = std::make_shared<ServeOptions>();
  server::ServerOptions serve_opt;
  CLI::App* serve_cmd = app.add_subcommand("serve", "Serve the HTTP API with a session on the default scene");
  serve_cmd->add_option("--host", options->server.host, "Address to bind")->capture_default_str();
  serve_cmd->add_option("--port", options->server.port, "Port (0: any free port)")->capture_default_str();
  add_gl_option(serve_cmd, options->gl);
  serve_cmd->add_option("--threads", options->server.threads, "HTTP worker threads (one per open connection)")
      ->capture_default_str();
  serve_cmd
      ->add_option("--render-threads", options->server.render_threads,
                   "Render threads, each with its own GL context (0: one per core)")
      ->capture_default_str();
  serve_cmd
      ->add_option("--frame-ancestors", options->server.frame_ancestors,
                   "Origins that may show the UI in an iframe (?embed=1), space-separated; 'none': nobody")
      ->capture_default_str();
  serve_cmd
      ->add_option("--trusted-proxy", options->server.trusted_proxy,
                   "Address (or IPv4 network a.b.c.d/n) of the reverse proxy whose X-Forwarded-For names the "
                   "client ('' never trusts it)")
      ->capture_default_str();
  serve_cmd
      ->add_option("--requests-per-second", options->server.limits.requests_per_second_per_client,
                   "Requests a second per client address (token bucket; 0: unlimited)")
      ->capture_default_str();
  options->server.data_dir = server::default_data_dir();
  serve_cmd
      ->add_option("--data-dir", options->server.data_dir,
                   "Directory of the session store (sessions.db, SQLite); '' keeps sessions in memory only")
      ->capture_default_str();
  serve_cmd
      ->add_option("--store", options->server.store,
                   "PostgreSQL URL of a session store shared by replicas on several hosts "
                   "(postgresql://user:password@host:port/db); instead of --data-dir")
      ->envname("SPINFOLD_STORE");
  serve_cmd->add_flag("--no-store", options->no_store, "Keep sessions in memory only (as --data-dir '')");
  return {serve_cmd, [options](int, char**) {
            apply_gl_choice(options->gl);
            if (options->no_store) options->server.data_dir.clear(), options->server.store.clear();
            return serve(options->server);
          }};
}

}  // namespace spinfold::cli
