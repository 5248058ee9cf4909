# Shared fixtures: the command-line tool (for comparisons), when the test run knows where it is.
import json
import os
import subprocess

import pytest


@pytest.fixture
def cli():
    """Runs `coxmesh ARGS... --json`-style commands and returns the parsed JSON output."""
    path = os.environ.get("COXMESH")
    if not path:
        pytest.skip("COXMESH (the command-line tool) is not set; ctest sets it")

    def run(*args):
        out = subprocess.run([path, *args], check=True, capture_output=True, text=True).stdout
        return json.loads(out)

    run.path = path
    return run
