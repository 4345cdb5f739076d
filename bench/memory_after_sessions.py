"""What a server holds after its sessions are gone (docs/deployment.md, sizing).

Starts `spinfold serve`, opens 15 sessions of 15 presets, advances each to t = 60, asks each for four
frames (the default size, two at 1280x720, one at 320x240), deletes them all, then waits a minute
for the heap trim and the render threads' idle release, printing the server's RSS at each stage.

    /usr/bin/python3 bench/memory_after_sessions.py build/spinfold [WAIT_SECONDS]
"""
import json
import sys
import time

from local_server import LocalServer

FRAMES = ["frame.png", "frame.png?width=1280&height=720", "frame.jpg?width=1280&height=720",
          "frame.png?width=320&height=240"]


def main():
    binary = sys.argv[1]
    wait = float(sys.argv[2]) if len(sys.argv) > 2 else 70.0
    with LocalServer(binary) as server:
        time.sleep(2)  # the render threads' start
        start = server.rss_mib()
        presets = [p["name"] for p in json.loads(server.call("GET", "/scenes")[1])]
        ids = []
        for i in range(15):
            status, body = server.call("POST", "/sessions", {"preset": presets[i % len(presets)]})
            assert status == 201, body
            ids.append(json.loads(body)["id"])
            server.call("POST", f"/sessions/{ids[-1]}/advance", {"until": 60})
            for frame in FRAMES:
                status, _ = server.call("GET", f"/sessions/{ids[-1]}/{frame}")
                assert status == 200, (frame, status)
        used = server.rss_mib()
        for session in ids:
            server.call("DELETE", f"/sessions/{session}")
        deleted = server.rss_mib()
        time.sleep(wait)
        print(f"RSS MiB: start {start:.0f}, 15 sessions used {used:.0f}, deleted {deleted:.0f}, "
              f"{wait:.0f} s later {server.rss_mib():.0f}")


if __name__ == "__main__":
    main()
