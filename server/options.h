// The server's options and limits: what `spinfold serve` sets and every room below reads.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace spinfold::server {

struct Limits {
  std::size_t max_body_bytes = 64 * 1024;  // request bodies [bytes]
  std::size_t max_sessions = 64;
  std::chrono::seconds idle_expiry{1800};  // sessions unused this long are dropped
  long max_steps = 1000000;                // step attempts per advance request (and fixed steps)
  long max_play_steps = 20000;             // step attempts per session per player tick (120 Hz)
  double max_advance_time = 1e6;           // simulated time per advance request
  // Work per advance request [s of wall clock]: past it the request answers "complete": false with
  // the progress kept (a formula surface's step costs more than a chart's: 10⁶ attempts took 4 s).
  double max_advance_seconds = 2.0;
  int max_image_side = 4096;  // [pixels]
  // A frame's width × height (frame.png, frame.jpg, the live view) [pixels]: 4K UHD. The memory a frame
  // takes grows with it, ~28 bytes a pixel (targets, readback, the PNG): 232 MiB at this size, 443 at
  // 4096 × 4096 (bench/limit_memory.py). Vector figures (frame.svg, frame.pdf) have no such bound.
  long long max_image_pixels = 3840LL * 2160;
  // A trajectory's answer (GET …/trajectory), built in memory before it is sent: a request whose
  // rows would pass it is refused (422 naming `every`) before the replay, or when it does [bytes].
  std::size_t max_trajectory_bytes = 64 << 20;
  // Encoded frames kept for the next ask (server/frames/frame_cache.h), least recently used dropped.
  std::size_t frame_cache_frames = 128;
  std::size_t frame_cache_bytes = 32 << 20;  // [bytes]
  // Open event and live streams (each holds a worker thread): 32 viewers with an event stream and
  // a live stream each, and room for more.
  int max_streams = 96;
  double max_play_rate = 1000.0;  // simulated time per second while playing

  // Per client address (server/http/quota.h): the socket's peer, or X-Forwarded-For's first address when
  // the peer is ServerOptions::trusted_proxy. A whole classroom often shares one address (NAT), so
  // these stop one runaway client, not a class: 30 students with 1-2 tabs each (each tab a session
  // and, while playing, one event stream) fit, while one address cannot take every session or stream
  // from the others (max_sessions, max_streams). Over a quota: 429 with Retry-After naming it.
  int max_sessions_per_client = 48;  // sessions created from one address and not yet deleted or expired
  int max_streams_per_client = 64;   // event and live streams open from one address
  // Requests from one address: a token bucket refilled at this rate [requests/s] holding at most
  // the burst [requests]. A playing tab's frames and states come over two streams (two requests); a
  // drag steers its live stream once per round trip (one PATCH in flight, retried after a 429); a
  // page load is about 50 requests (its files, the catalogs, 10 thumbnails of 4 requests each). So
  // a class of 30 opening the page at once fits the burst plus a few seconds of refill. 0: unlimited
  // (benchmarks from one address: spinfold serve --requests-per-second 0).
  double requests_per_second_per_client = 300.0;
  double request_burst_per_client = 600.0;

  // Recordings (POST …/recordings; server/jobs/recordings.h). A refused size or length is 422 naming the
  // field; a refused job over a count or the disk space is 429 naming the limit.
  long long max_recording_frames = 3600;           // frames per recording (2 min at 30 frames/s)
  long long max_recording_pixels = 1920 * 1080;    // width × height of a recording's frames [pixels]
  int max_recordings_per_client = 2;               // queued or running recordings of one address
  int max_recordings = 32;                         // recordings kept (any status), all clients
  long long max_recording_disk_bytes = 1LL << 30;  // the files of every recording kept [bytes]
  std::chrono::seconds recording_max_age{3600};    // a finished recording is deleted after this
  int recording_threads = 1;                       // recordings encoded at once (the rest wait, queued)
  // With a store: a queued or running recording whose replica has not written its row for this long
  // is failed (the replica was lost); each replica touches its rows every recording_heartbeat.
  std::chrono::milliseconds recording_heartbeat{5000};
  std::chrono::seconds recording_owner_lost{30};

  // Work-precision jobs (POST /api/v1/work-precision; server/jobs/work_precision_jobs.h), measured one at
  // a time on one background thread. A refused horizon is 422 naming t_end; a refused job is 429.
  double max_work_precision_periods = 20.0;     // T in characteristic periods of the scene
  double max_work_precision_t_end = 1000.0;     // T [time], also for scenes whose motion has no period
  double work_precision_seconds_per_run = 0.5;  // a method stops refining once one run takes longer [s]
  long long work_precision_steps_per_run = 2'000'000;  // step attempts of one run (past them: not reached)
  int max_work_precision_jobs_per_client = 1;          // queued or running jobs of one address
  int max_work_precision_jobs = 16;                    // jobs kept (any status), all clients
  std::chrono::seconds work_precision_max_age{3600};   // a finished job's result is dropped after this

  // Slow and idle connections (each holds a worker thread while open; ServerOptions::threads).
  std::chrono::seconds read_timeout{3};        // the longest wait for the next bytes of a request
  std::chrono::seconds keep_alive_timeout{3};  // an idle keep-alive connection is closed after this
  int keep_alive_max_requests = 100;           // requests per connection before it is closed
};

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port
  // HTTP worker threads: one per open connection, idle or not (cpp-httplib 0.11), so the pool is sized
  // for max_streams streams plus 64 idle, slow or busy connections: 32 idle or trickling connections
  // then leave the API answering at once (docs/performance.md).
  int threads = 160;
  // Render threads, each with its own GL context (server/frames/render_pool.h); 0: one per core.
  int render_threads = 0;
  // The address of a reverse proxy (the front, scripts/front.sh) whose X-Forwarded-For names the
  // client; "": never trust the header (the socket's peer is the client).
  std::string trusted_proxy;
  // Who may show the UI in an iframe (CSP frame-ancestors): "'none'" (default), or origins such as
  // "https://lms.example.edu https://slides.example.org" for `?embed=1` in slides or an LMS.
  std::string frame_ancestors = "'none'";
  std::string data_dir;  // the durable session store (DIR/sessions.db, SQLite); "": memory only
  // A PostgreSQL URL (postgresql://…): the store instead of data_dir, for replicas on several hosts
  // (server/store/postgres_store.h).
  std::string store;
  Limits limits;
};

}  // namespace spinfold::server
