# The scripts of examples/python_*.py run and print what docs/python.md says they print.
import os
import pathlib
import subprocess
import sys

import pytest

import coxmesh

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("name,expected", [
    ("python_sphere.py", "Betti numbers [1, 0, 1]"),
    ("python_so3.py", "the built-in preset gives the same cells: True"),
    ("python_locate.py", "1000000 points located"),
    ("python_quality.py", "thickest in d = 4: A"),
])
def test_example_runs(tmp_path, name, expected):
    env = dict(os.environ, PYTHONPATH=os.path.dirname(coxmesh.__file__))  # (run elsewhere: tmp_path)
    out = subprocess.run([sys.executable, str(EXAMPLES / name)], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert expected in out.stdout
    if name == "python_so3.py":
        assert "[1, 1, 1, 1]" in out.stdout
