"""What a drag costs the server: GET handles and GET drop (render/drag.h's pick), each against an
uncached frame.png of the same picture in the same run (the baseline: the page asks one per drop).

    python3 bench/drag_bench.py build/spinfold [repeats]

Prints, per preset in its own view at 1280x727 after t = 5: the median time of `repeats` handles
and drops (each drop 20 px from the body towards the frame's centre) and of as many frames, each made anew (a new `scale`
per request keeps the frame cache out of it), and the ratios.
"""
import json
import statistics
import sys
import time

from local_server import LocalServer

PRESETS = ["spinning_rigid_sphere", "spin_vs_geodesic_pseudosphere", "spin_vs_geodesic_torus",
           "trapped_spin_bump", "spin_vs_geodesic_catenoid", "spinning_rigid_plane"]


def timed(server, path):
    start = time.perf_counter()
    status, body = server.call("GET", path)
    elapsed = time.perf_counter() - start
    if status != 200:
        raise SystemExit(f"{path}: {status} {body[:200]}")
    return elapsed, body


def main():
    binary = sys.argv[1]
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 15
    view = "width=1280&height=727"
    print(f"{'preset':34} {'handles ms':>10} {'drop ms':>8} {'frame ms':>9} {'drop/frame':>10}")
    with LocalServer(binary) as server:
        for preset in PRESETS:
            status, body = server.call("POST", "/sessions", {"preset": preset})
            session = "/sessions/" + json.loads(body)["id"]
            server.call("POST", session + "/advance", {"until": 5})
            handles, drops, frames = [], [], []
            for k in range(repeats):
                elapsed, body = timed(server, f"{session}/handles?{view}")
                handles.append(elapsed)
                place = json.loads(body)["body"]
                # 20 px from the body towards the frame's centre (the body can be at the surface's edge).
                x, y = place["x"], place["y"]
                d = max(1e-9, ((640 - x) ** 2 + (363 - y) ** 2) ** 0.5)
                x, y = x + 20 * (640 - x) / d, y + 20 * (363 - y) / d
                drops.append(timed(server, f"{session}/drop?{view}&x={x:.2f}&y={y:.2f}")[0])
                frames.append(timed(server, f"{session}/frame.png?{view}&scale={0.25 + 1e-4 * k}")[0])
            h, d, f = (1000 * statistics.median(v) for v in (handles, drops, frames))
            print(f"{preset:34} {h:10.2f} {d:8.2f} {f:9.1f} {d / f:10.3f}")


if __name__ == "__main__":
    main()
