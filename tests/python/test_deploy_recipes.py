"""The Kubernetes recipe (deploy/kubernetes/) as a user fills it in: envsubst with the documented
variables, then the manifests checked for what a cluster needs (a storage class, a pushed image, the
shard count once, per-index retries, non-root pods, finished Jobs removed), and the pods' own shell
commands run here, shard by shard and then the merge, giving the rows of one process."""

import os
import pathlib
import re
import shutil
import subprocess

import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
VARS = "$IMAGE $STORAGE_CLASS $SHARDS $SWEEP_ARGS"
ENV = {"IMAGE": "registry.example.org/lab/spinfold-compute:0a1b2c3", "STORAGE_CLASS": "nfs-client",
       "SHARDS": "3", "SWEEP_ARGS": "spinning_rigid_sphere --set initial.r=0.4:1.6:5 --t-end 2 --every 1"}


def filled(name):
    if not shutil.which("envsubst"):
        pytest.fail("envsubst missing (Debian gettext-base, scripts/setup.sh)")
    text = (ROOT / "deploy" / "kubernetes" / name).read_text()
    out = subprocess.run(["envsubst", VARS], input=text, capture_output=True, text=True, check=True,
                         env={**os.environ, **ENV}).stdout
    return [doc for doc in yaml.safe_load_all(out) if doc]


def pod_command(job):
    container = job["spec"]["template"]["spec"]["containers"][0]
    assert container["command"] == ["/bin/sh", "-c"]
    return container["args"][0]


def test_the_manifests_have_what_a_cluster_needs():
    claim, job = filled("sweep-job.yaml")
    (merge,) = filled("sweep-merge-job.yaml")
    assert claim["kind"] == "PersistentVolumeClaim" and claim["spec"]["storageClassName"] == "nfs-client"
    assert claim["spec"]["accessModes"] == ["ReadWriteMany"]
    spec = job["spec"]
    assert spec["completionMode"] == "Indexed"
    assert spec["completions"] == spec["parallelism"] == 3  # SHARDS, written once
    assert spec["backoffLimitPerIndex"] >= 1 and "backoffLimit" not in spec
    assert re.search(r'--shard "\$\{JOB_COMPLETION_INDEX\}/3"', pod_command(job))
    for j in (job, merge):
        assert j["spec"]["ttlSecondsAfterFinished"] > 0
        pod = j["spec"]["template"]["spec"]
        assert pod["securityContext"]["runAsNonRoot"] is True and pod["securityContext"]["runAsUser"] != 0
        container = pod["containers"][0]
        assert container["image"] == ENV["IMAGE"] and not container["image"].endswith(":latest")
        assert container["securityContext"]["allowPrivilegeEscalation"] is False
        assert container["securityContext"]["capabilities"]["drop"] == ["ALL"]


def test_the_pods_commands_give_the_rows_of_one_process(binary, tmp_path):
    (_, job) = filled("sweep-job.yaml")
    (merge,) = filled("sweep-merge-job.yaml")
    results = tmp_path / "results"
    results.mkdir()
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "spinfold").symlink_to(binary)
    env = {**os.environ, "PATH": f"{bin_dir}:{os.environ['PATH']}"}

    def run(command, **extra):
        return subprocess.run(["/bin/sh", "-c", command.replace("/results", str(results))],
                              env={**env, **extra}, capture_output=True, text=True)

    for index in range(3):
        done = run(pod_command(job), JOB_COMPLETION_INDEX=str(index))
        assert done.returncode == 0, done.stderr
    # A shard missing: the merge fails naming it.
    (results / "shard-1.csv").rename(tmp_path / "kept.csv")
    failed = run(pod_command(merge))
    assert failed.returncode != 0 and "shard-1.csv" in failed.stderr
    (tmp_path / "kept.csv").rename(results / "shard-1.csv")
    merged = run(pod_command(merge))
    assert merged.returncode == 0, merged.stderr
    single = tmp_path / "single.csv"
    subprocess.run([binary, "sweep", *ENV["SWEEP_ARGS"].split(), "--quiet", "--out", str(single)], check=True)

    def rows(path):  # all but the seconds column and the command lines
        return [re.sub(r",[^,]*$", "", line) for line in path.read_text().splitlines()
                if not line.startswith(("# command:", "# merge:"))]

    assert rows(results / "sweep.csv") == rows(single)
