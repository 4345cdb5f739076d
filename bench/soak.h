// Mixed load for a long time (state, frames, advance, PATCH, event streams opening and closing,
// sessions created and deleted) against an in-process server or a running one (the front):
// errors, latency percentiles per operation, and the server's resident memory over time.
#pragma once

#include <string>

namespace spinfold::bench {

struct SoakOptions {
  double minutes = 10.0;
  int clients = 8;       // concurrent client threads
  std::string url;       // "": an in-process server on loopback
  int server_pid = 0;    // with url: whose RSS to read (0: none)
  std::string data_dir;  // the in-process server's session store ("": memory only)
};

int run_soak(const SoakOptions& options);

}  // namespace spinfold::bench
