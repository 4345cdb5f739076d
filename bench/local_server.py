"""A `spinfold serve` of a benchmark's own on a free loopback port, with its RSS and a JSON client.

    with LocalServer("build/spinfold") as server:
        status, body = server.call("POST", "/sessions", {"preset": "spin_fan_sphere"})
        print(server.rss_mib())
"""
import json
import socket
import subprocess
import threading
import time
import urllib.error
import urllib.request


class LocalServer:
    def __init__(self, binary):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        self.process = subprocess.Popen(
            [binary, "serve", "--port", str(port), "--no-store", "--requests-per-second", "0"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.base = f"http://127.0.0.1:{port}/api/v1"
        for _ in range(200):
            try:
                self.call("GET", "/health")
                return
            except OSError:
                time.sleep(0.1)

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.process.terminate()
        self.process.wait()

    def rss_mib(self):
        """The server's resident memory [MiB]."""
        with open(f"/proc/{self.process.pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS"):
                    return int(line.split()[1]) / 1024
        return float("nan")

    def peak_mib(self, action):
        """(action's result, the server's RSS before it [MiB], its peak while it ran, sampled every 20 ms)."""
        before = self.rss_mib()
        peak = [before]
        done = threading.Event()

        def watch():
            while not done.is_set():
                peak[0] = max(peak[0], self.rss_mib())
                time.sleep(0.02)

        watcher = threading.Thread(target=watch)
        watcher.start()
        try:
            result = action()
        finally:
            done.set()
            watcher.join()
        return result, before, peak[0]

    def call(self, method, path, body=None):
        """(status, body bytes) of a request under /api/v1; a refusal is an answer, not an error."""
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.base + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=600) as answer:
                return answer.status, answer.read()
        except urllib.error.HTTPError as error:
            return error.code, error.read()
