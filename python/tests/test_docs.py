# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs every ```python block of docs/python.md, in order and in one namespace, in a folder of
small generated inputs (ctest python.docs)."""
import importlib.util
import os
import re
import tempfile
import unittest

import sample_data

DOC = os.path.join(os.environ.get("CONSTRICT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                   "docs", "python.md")


def python_blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


class DocsExamples(unittest.TestCase):
    def test_every_python_block_runs(self):
        with open(DOC, encoding="utf-8") as f:
            blocks = python_blocks(f.read())
        self.assertGreaterEqual(len(blocks), 5)
        has_distributed = importlib.util.find_spec("distributed") is not None
        cwd = os.getcwd()
        with tempfile.TemporaryDirectory() as tmp:
            sample_data.write_folder(tmp)
            os.chdir(tmp)
            try:
                ns = {"__name__": "__docs__"}
                for i, code in enumerate(blocks):
                    if "distributed" in code and not has_distributed:
                        print(f"block {i}: skipped (python3-distributed not installed)")
                        continue
                    with self.subTest(block=i):
                        exec(compile(code, f"{DOC}:block{i}", "exec"), ns)
            finally:
                os.chdir(cwd)


if __name__ == "__main__":
    unittest.main()
