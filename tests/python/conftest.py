"""Shared fixtures: the CLI binary (SPINFOLD_BINARY, set by ctest) and a server it serves."""

import json
import os
import re
import subprocess
import time

import pytest


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("SPINFOLD_BINARY")
    if not path or not os.path.exists(path):
        pytest.fail("SPINFOLD_BINARY must name the spinfold binary (ctest sets it)")
    return path


def cli_samples(binary, *args):
    """The samples `spinfold simulate ARGS` prints, after its provenance record."""
    out = subprocess.run([binary, "simulate", *args], check=True, capture_output=True, text=True).stdout
    lines = out.splitlines()
    assert json.loads(lines[0])["provenance"]["software"] == "spinfold"
    return [json.loads(line) for line in lines[1:]]


@pytest.fixture(scope="session")
def server(binary):
    """`spinfold serve` on a free port with sessions in memory; its base URL."""
    process = subprocess.Popen([binary, "serve", "--port", "0", "--no-store", "--requests-per-second", "0"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    url = None
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        line = process.stdout.readline()
        match = re.search(r"serving on (http://[^/\s]+)/", line)
        if match:
            url = match.group(1)
            break
        if process.poll() is not None:
            break
    if url is None:
        process.kill()
        pytest.fail("the server did not start: " + process.stderr.read())
    yield url
    process.terminate()
    process.wait(timeout=30)
