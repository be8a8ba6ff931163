"""Batch bakes on a LocalCluster of 2 worker processes over a generated folder of 200 meshes, 5 of
them broken: outputs byte-identical to `chamfer bake`'s, the broken ones reported by name, re-runs
skip everything unchanged, and a worker killed mid-batch changes nothing in the result."""

import json
import logging
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

import chamfer
import meshgen
from chamfer.dask import bake_folder

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=logging.ERROR
    )
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


@pytest.fixture(scope="module")
def library(tmp_path_factory, cli):
    """The generated folder, its broken files, and `chamfer bake`'s outputs for it."""
    src = tmp_path_factory.mktemp("library")
    broken = meshgen.write_library(src)
    expected = tmp_path_factory.mktemp("cli")
    result = cli.run("bake", src, "-o", expected, check=False)
    assert result.returncode != 0 and "5 of 200 inputs failed" in result.stderr, result.stderr
    return src, broken, expected


def outputs(folder):
    return sorted(str(p.relative_to(folder)) for p in Path(folder).rglob("*") if p.is_file())


def check_against_cli(report, src, broken, expected, dst):
    assert len(report.results) == 200
    assert len({r.input for r in report.results}) == 200, "each input reported once"
    failed = {Path(r.input).name: r for r in report.failed}
    assert sorted(failed) == sorted(broken)
    for name, failure in failed.items():
        assert failure.error == broken[name]
        assert name in failure.reason, failure.reason
    cli_assets = [p for p in outputs(expected)]
    assert len(cli_assets) == 195
    # Every output present, valid, the CLI's bytes, once; beside each its key; nothing else.
    assert outputs(dst) == sorted(cli_assets + [a + ".key" for a in cli_assets])
    for asset in cli_assets:
        data = (Path(dst) / asset).read_bytes()
        assert data == (Path(expected) / asset).read_bytes(), asset
        chamfer.decode(data, name=asset)


def test_a_folder_bakes_as_the_cli_bakes_it_and_a_rerun_skips_it(client, library, tmp_path):
    src, broken, expected = library
    dst = tmp_path / "out"
    seen = []
    report = bake_folder(src, dst, client, files_per_task=8, progress=lambda done, total: seen.append((done, total)))
    check_against_cli(report, src, broken, expected, dst)
    assert (len(report.baked), len(report.skipped)) == (195, 0)
    assert report.workers == 2 and report.tasks == 25
    assert seen[-1] == (200, 200)
    assert "195 baked, 0 skipped (up to date), 5 failed" in report.summary()

    # A temporary file a killed worker left is removed at the end. The client is the current one.
    orphan = dst / "props" / ".chamfer-KILLED.tmp"
    orphan.write_bytes(b"half an asset")
    again = bake_folder(src, dst)
    assert (len(again.baked), len(again.skipped), len(again.failed)) == (0, 195, 5)
    assert again.orphans_removed == 1 and not orphan.exists()
    check_against_cli(again, src, broken, expected, dst)

    # A changed input, or changed options, bake again (in a copy: the library is the other tests').
    # The keys are of the contents, so the copy's unchanged files are up to date.
    copy = tmp_path / "copy"
    shutil.copytree(src, copy)
    changed = sorted(copy.glob("mesh-*.obj"))[0]
    changed.write_text(meshgen.obj_text(*meshgen.box((1.0, 2.0, 3.0))))
    once_more = bake_folder(copy, dst, client)
    assert [Path(r.input).name for r in once_more.baked] == [changed.name]
    assert chamfer.load(dst / (changed.stem + ".chamfer")).encode() == chamfer.bake(changed).encode()
    with_options = bake_folder(copy, dst, client, crease_deg=45.0)
    assert len(with_options.baked) == 195
    assert chamfer.load(dst / (changed.stem + ".chamfer")).settings["crease_deg"] == "45"
    with pytest.raises(chamfer.OptionsError):
        bake_folder(src, dst, client, crease_deg=-1.0)


def test_a_worker_killed_mid_batch_changes_nothing(client, library, tmp_path):
    src, broken, expected = library
    dst = tmp_path / "out"
    victims = []

    def kill_a_worker(done, total):
        if victims or done < 40:
            return
        busy = {w: keys for w, keys in client.processing().items() if keys}
        worker = sorted(busy)[0]
        pid = client.run(os.getpid, workers=[worker])[worker]
        os.kill(pid, signal.SIGKILL)
        victims.append((worker, pid, busy[worker]))

    report = bake_folder(src, dst, client, files_per_task=4, progress=kill_a_worker)
    assert victims, "the batch ended before a worker was killed"
    worker, pid, tasks = victims[0]
    assert tasks, "the killed worker was baking"
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)
    check_against_cli(report, src, broken, expected, dst)
    assert len(report.baked) + len(report.skipped) == 195
    print(f"\nkilled {worker} (pid {pid}) while it had {len(tasks)} tasks; {len(report.skipped)} files found up to "
          f"date when their task ran again, {report.orphans_removed} temporary files removed")
    client.wait_for_workers(2, timeout=60)


def test_the_command_line_reports_failures_and_writes_a_report(client, library, cli, tmp_path):
    src = tmp_path / "few"
    src.mkdir()
    for name in ["mesh-001.ply", "mesh-002.ply", "mesh-003.ply.gz", "mesh-004.glb", "broken-nan.obj"]:
        (src / name).write_bytes((library[0] / name).read_bytes())
    dst, report_path = tmp_path / "out", tmp_path / "report.json"
    command = [sys.executable, "-m", "chamfer.dask", str(src), str(dst), "--scheduler", client.scheduler.address,
               "--crease-deg", "40", "--radius-rel", "0.01", "--report", str(report_path)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert result.returncode == 1, result.stderr
    assert "broken-nan.obj" in result.stderr and "non-finite" in result.stderr
    assert "4 baked, 0 skipped (up to date), 1 failed" in result.stdout
    report = json.loads(report_path.read_text())
    assert [Path(r["input"]).name for r in report["results"] if r["status"] == "failed"] == ["broken-nan.obj"]
    expected = tmp_path / "cli"
    cli.run("bake", src, "-o", expected, "--crease-deg", "40", "--radius-rel", "0.01", check=False)
    for asset in outputs(expected):
        assert (dst / asset).read_bytes() == (expected / asset).read_bytes()
    help_text = subprocess.run([sys.executable, "-m", "chamfer.dask", "--help"], capture_output=True, text=True).stdout
    for name, _, _ in chamfer.OPTIONS:
        assert "--" + name.replace("_", "-") in help_text
