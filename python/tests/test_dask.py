# SPDX-License-Identifier: GPL-3.0-or-later
"""Dask (ctest python.dask): a LocalCluster of two worker processes on loopback maps
constrict.reconstruct over a folder of small files; the results equal the sequential ones.
Skipped when python3-distributed is not installed."""
import tempfile
import time
import unittest

import constrict
import sample_data

try:
    from distributed import Client, LocalCluster
except ImportError:  # pragma: no cover - depends on the machine
    LocalCluster = None


@unittest.skipIf(LocalCluster is None, "python3-distributed is not installed")
class DaskCluster(unittest.TestCase):
    def test_map_over_files_equals_sequential(self):
        with tempfile.TemporaryDirectory() as tmp:
            files = sample_data.write_folder(tmp)
            sequential = [constrict.reconstruct(f) for f in files]
            sequential_paper = [constrict.reconstruct(f, refine=False) for f in files]
            t0 = time.perf_counter()
            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                              host="127.0.0.1") as cluster, Client(cluster) as client:
                remote = client.gather(client.map(constrict.reconstruct, files))
                # Options travel as keywords; results come back pickled.
                paper = client.gather(client.map(constrict.reconstruct, files, refine=False))
            print(f"cluster: {len(files)} files twice in {time.perf_counter() - t0:.1f} s")
        self.assertEqual(len(remote), len(files))
        for f, a, b in zip(files, sequential, remote):
            self.assertIs(type(a), type(b), f)
            self.assertTrue(b.valid, f)
            self.assertEqual(a, b, f)
        self.assertEqual(paper, sequential_paper)


if __name__ == "__main__":
    unittest.main()
