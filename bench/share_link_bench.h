// The time to open a share link: POST /api/v1/sessions with a scene, a timeline of 5 changes and
// `until`, which rebuilds the run from t = 0, against creating the bare session (same server, same
// run) and against the engine's replay alone.
#pragma once

namespace spinfold::bench {

int run_share_link_bench(int repeats, double until);

}  // namespace spinfold::bench
