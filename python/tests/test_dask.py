"""The Python API inside Dask distributed workers: one task per file, on a
LocalCluster of two worker processes (the recipe of the README)."""

import numpy as np
import pytest

import holey

distributed = pytest.importorskip("distributed", reason="SKIP: dask.distributed is not installed")


def info_of(path):
    import holey

    return str(path), holey.info(*holey.read(path))


def union_of(path_a, path_b, out):
    import holey

    V, F = holey.union(*holey.read(path_a), *holey.read(path_b))
    holey.write(out, V, F)
    return holey.volume(V, F)


def test_local_cluster_maps_info_and_unions_over_files(tmp_path):
    paths = []
    for i, (name, args) in enumerate([("cube", ()), ("torus", ()), ("sphere", (2,)), ("tetrahedron", ())]):
        path = tmp_path / f"{i}_{name}.ply"
        holey.write(path, *holey.primitive(name, *args))
        paths.append(path)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        results = dict(client.gather(client.map(info_of, paths)))
        assert len(client.scheduler_info()["workers"]) == 2
        cube = tmp_path / "0_cube.ply"
        moved = tmp_path / "moved.ply"
        V, F = holey.read(cube)
        holey.write(moved, V + 0.5, F)
        volume = client.submit(union_of, cube, moved, tmp_path / "union.ply").result()
    for path in paths:
        assert results[str(path)] == holey.info(*holey.read(path))
    assert results[str(paths[1])]["genus"] == 1
    assert volume == pytest.approx(16.0 - 1.5**3, rel=1e-12)
    assert holey.volume(*holey.read(tmp_path / "union.ply")) == pytest.approx(volume, rel=1e-15)
    assert np.isfinite(volume)
