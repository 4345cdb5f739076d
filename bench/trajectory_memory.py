"""One trajectory request's cost to the server: its answer's size, time and the server's RSS peak.

Starts `spinfold serve`, opens a session of PRESET, advances it to T, asks for its trajectory every
EVERY in FORMAT (json or csv) with FIELDS (all when absent) and prints the status, the bytes, the
seconds and the server's RSS before, at its peak (sampled every 20 ms) and after. A request past
`max_trajectory_bytes` prints the 422's reason instead (README "Tables and provenance").

    /usr/bin/python3 bench/trajectory_memory.py build/spinfold spin_fan_sphere 1000 0.2 json [FIELDS]
"""
import json
import sys
import time

from local_server import LocalServer


def main():
    binary, preset, t_end, every, fmt = sys.argv[1:6]
    fields = sys.argv[6] if len(sys.argv) > 6 else ""
    with LocalServer(binary) as server:
        status, body = server.call("POST", "/sessions", {"preset": preset})
        assert status == 201, body
        session = json.loads(body)["id"]
        status, body = server.call("POST", f"/sessions/{session}/advance", {"until": float(t_end)})
        assert status == 200, body
        query = f"every={every}&format={fmt}" + (f"&fields={fields}" if fields else "")
        started = time.time()
        (status, body), before, peak = server.peak_mib(
            lambda: server.call("GET", f"/sessions/{session}/trajectory?{query}"))
        seconds = time.time() - started
        print(f"status {status}, {len(body)} bytes in {seconds:.1f} s; server RSS {before:.0f} MiB before, "
              f"{peak:.0f} at its peak (+{peak - before:.0f}), {server.rss_mib():.0f} after")
        if status != 200:
            print(json.loads(body)["errors"][0]["reason"])


if __name__ == "__main__":
    main()
