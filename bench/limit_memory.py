"""What one request at a documented limit costs the server in memory: README "What one request may
cost". Each case runs on a server of its own (`spinfold serve`, no store): the RSS before the request,
at its peak (sampled every 20 ms until the answer, or until a job is done) and the seconds.

    /usr/bin/python3 bench/limit_memory.py build/spinfold [CASE ...]

Cases: frame (a 4096×4096 PNG, the largest image), trajectory (spin_fan_sphere's samples just under
max_trajectory_bytes), trajectory-9-bodies (the same with 8 companions: every multiplier), gif, webm, mp4, png-zip (recordings at 1920×1080, the largest frame; FRAMES
frames, 300 by default: SPINFOLD_LIMIT_FRAMES), work-precision (a preset at its default, 20 periods).
"""
import json
import os
import sys
import time

from local_server import LocalServer

FRAMES = int(os.environ.get("SPINFOLD_LIMIT_FRAMES", "300"))


def session(server, preset, until=None):
    status, body = server.call("POST", "/sessions", {"preset": preset})
    assert status == 201, body
    sid = json.loads(body)["id"]
    if until:
        status, body = server.call("POST", f"/sessions/{sid}/advance", {"until": until})
        assert status == 200, body
    return sid


def poll(server, path):
    """Waits for a job (recording or work-precision) to end; its last status."""
    while True:
        status, body = server.call("GET", path)
        job = json.loads(body)
        if job["status"] not in ("queued", "running"):
            return job
        time.sleep(0.2)


def frame(server):
    sid = session(server, "spinning_rigid_sphere", 5)
    status, body = server.call("GET", f"/sessions/{sid}/frame.png?width=4096&height=4096")
    return f"{status}, {len(body) / 2**20:.1f} MiB PNG"


def trajectory(server):
    sid = session(server, "spin_fan_sphere", 1000)
    status, body = server.call("GET", f"/sessions/{sid}/trajectory?every=0.21&format=json")
    return f"{status}, {len(body) / 2**20:.1f} MiB of JSON"


def trajectory_nine_bodies(server):
    """The trajectory at its byte limit with the most bodies a scene holds (8 companions, 9 bodies:
    every multiplier at once, rows x bodies x columns), just under max_trajectory_bytes."""
    companions = [{"label": f"s = {0.25 * i}", "initial": {"spin": 0.25 * i}} for i in range(8)]
    scene = {"surface": {"kind": "sphere", "radius": 1.0},
             "initial": {"r": 0.5, "speed": 0.5, "heading": 1.0, "spin": 1.0}, "companions": companions}
    status, body = server.call("POST", "/sessions", scene)
    assert status == 201, body
    sid = json.loads(body)["id"]
    status, body = server.call("POST", f"/sessions/{sid}/advance", {"until": 1000})
    assert status == 200, body
    status, body = server.call("GET", f"/sessions/{sid}/trajectory?every=0.34&format=json")
    return f"{status}, {len(body) / 2**20:.1f} MiB of JSON, 9 bodies"


def recording(fmt):
    def run(server):
        sid = session(server, "spinning_rigid_sphere")
        status, body = server.call("POST", f"/sessions/{sid}/recordings",
                                   {"t_end": FRAMES / 30.0, "fps": 30, "width": 1920, "height": 1080,
                                    "format": fmt})
        assert status == 202, body
        job = poll(server, f"/recordings/{json.loads(body)['id']}")
        return f"{job['status']}, {FRAMES} frames, {job.get('bytes', 0) / 2**20:.1f} MiB file"
    return run


def work_precision(server):
    status, body = server.call("POST", "/work-precision", {"preset": "spinning_rigid_sphere"})
    assert status == 202, body
    job = poll(server, f"/work-precision/{json.loads(body)['id']}")
    return f"{job['status']}, {len(job.get('result', {}).get('points', []))} points"


CASES = {"frame": frame, "trajectory": trajectory, "trajectory-9-bodies": trajectory_nine_bodies, "gif": recording("gif"), "webm": recording("webm"),
         "mp4": recording("mp4"), "png-zip": recording("png-zip"), "work-precision": work_precision}


def measure(binary, name):
    with LocalServer(binary) as server:
        started = time.time()
        what, before, peak = server.peak_mib(lambda: CASES[name](server))
        print(f"{name:15s} {what}; {time.time() - started:.1f} s; RSS {before:.0f} MiB before, "
              f"peak +{peak - before:.0f} MiB", flush=True)


def main():
    binary = sys.argv[1]
    for name in sys.argv[2:] or CASES:
        measure(binary, name)


if __name__ == "__main__":
    main()
