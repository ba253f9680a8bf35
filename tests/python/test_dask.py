"""facetlab.dask on a real LocalCluster of two worker processes: the sweep's rows equal
``facetlab sweep``'s CSV to the last digit, also when a worker is killed mid-run."""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path
from typing import Iterator, List, Union

import facetlab
import facetlab.dask
import pytest

from conftest import TINY, Cli

distributed = pytest.importorskip("distributed")
from distributed import Client, LocalCluster  # noqa: E402

AXES = ["crown_angle:32:34:1", "pavilion_angle:40:41:0.5", "table:0.55:0.56:0.01"]


@pytest.fixture(scope="module")
def client() -> Iterator[Client]:
    cluster = LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture()
def want(cli: Cli, tmp_path: Path) -> str:
    (tmp_path / "tiny.toml").write_text(TINY)
    args = ["--x", AXES[0], "--y", AXES[1], "--axis", AXES[2]]
    p = cli(tmp_path, "sweep", "tiny.toml", *args, "--out", "one", "--quiet")
    assert p.returncode == 0, p.stderr
    return (tmp_path / "one" / "sweep.csv").read_text()


def test_a_sweep_on_two_workers_is_the_command_lines_csv(
    client: Client, want: str, tmp_path: Path
) -> None:
    got = facetlab.dask.sweep_csv(client, str(tmp_path / "tiny.toml"), AXES, chunk=2)
    assert got == want
    # Both workers took tasks.
    assert len(client.scheduler_info()["workers"]) == 2


def test_a_worker_killed_mid_run_still_gives_the_same_rows(
    client: Client, want: str, tmp_path: Path
) -> None:
    killed = []

    def kill_a_busy_worker() -> None:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            busy = [w for w, tasks in client.processing().items() if tasks]
            if busy:
                try:
                    client.run(os._exit, 1, workers=[busy[0]], wait=False)
                except Exception:  # the worker's connection closes as it dies
                    pass
                killed.append(busy[0])
                return
            time.sleep(0.02)

    t = threading.Thread(target=kill_a_busy_worker)
    t.start()
    got = facetlab.dask.sweep_csv(client, str(tmp_path / "tiny.toml"), AXES, chunk=1)
    t.join()
    assert killed, "no worker was busy to kill"
    assert got == want


def test_score_many_on_the_cluster_is_the_local_one(client: Client) -> None:
    cuts = ["tolkowsky", "gia-reference", "tolkowsky"]
    got = facetlab.dask.score_many(client, cuts, chunk=1, polarization=False)
    assert got == [s.to_dict() for s in facetlab.score_many(cuts, polarization=False)]


def test_score_many_ships_cut_objects_the_workers_cannot_read(
    client: Client, tmp_path: Path
) -> None:
    # A design read from a file and re-angled, a family with parameters, a preset name: the
    # file is gone before the cluster scores, so the workers score the pickled cuts.
    facetlab.cut("tolkowsky").write(tmp_path / "t.asc")
    design = facetlab.cut(tmp_path / "t.asc").with_set({"pavilion-main": 41.2})
    (tmp_path / "t.asc").unlink()
    cuts: List[Union[facetlab.Cut, str]] = [
        design, facetlab.family("round-brilliant", table=0.6), "gia-reference"
    ]
    got = facetlab.dask.score_many(client, cuts, chunk=1, polarization=False)
    assert got == [s.to_dict() for s in facetlab.score_many(cuts, polarization=False)]
    assert [d["cut"] for d in got] == ["t", "round-brilliant", "GIA reference"]
