"""What a server holds after its sessions are gone (docs/deployment.md, sizing).

Starts `spinfold serve`, opens 15 sessions of 15 presets, advances each to t = 60, asks each for four
frames (the default size, two at 1280x720, one at 320x240), deletes them all, then waits a minute
for the heap trim and the render threads' idle release, printing the server's RSS at each stage.

    /usr/bin/python3 bench/memory_after_sessions.py build/spinfold [WAIT_SECONDS]
"""
import json
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request

FRAMES = ["frame.png", "frame.png?width=1280&height=720", "frame.jpg?width=1280&height=720",
          "frame.png?width=320&height=240"]


def main():
    binary = sys.argv[1]
    wait = float(sys.argv[2]) if len(sys.argv) > 2 else 70.0
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    server = subprocess.Popen([binary, "serve", "--port", str(port), "--no-store", "--requests-per-second", "0"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    base = f"http://127.0.0.1:{port}/api/v1"

    def rss_mib():
        with open(f"/proc/{server.pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS"):
                    return int(line.split()[1]) / 1024
        return float("nan")

    def call(method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(base + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=600) as answer:
                return answer.status, answer.read()
        except urllib.error.HTTPError as error:
            return error.code, error.read()

    try:
        for _ in range(200):
            try:
                call("GET", "/health")
                break
            except OSError:
                time.sleep(0.1)
        time.sleep(2)  # the render threads' start
        start = rss_mib()
        presets = [p["name"] for p in json.loads(call("GET", "/scenes")[1])]
        ids = []
        for i in range(15):
            status, body = call("POST", "/sessions", {"preset": presets[i % len(presets)]})
            assert status == 201, body
            ids.append(json.loads(body)["id"])
            call("POST", f"/sessions/{ids[-1]}/advance", {"until": 60})
            for frame in FRAMES:
                status, _ = call("GET", f"/sessions/{ids[-1]}/{frame}")
                assert status == 200, (frame, status)
        used = rss_mib()
        for session in ids:
            call("DELETE", f"/sessions/{session}")
        deleted = rss_mib()
        time.sleep(wait)
        print(f"RSS MiB: start {start:.0f}, 15 sessions used {used:.0f}, deleted {deleted:.0f}, "
              f"{wait:.0f} s later {rss_mib():.0f}")
    finally:
        server.terminate()
        server.wait()


if __name__ == "__main__":
    main()
