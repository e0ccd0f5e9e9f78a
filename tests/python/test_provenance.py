"""Where a result came from: summary.json's `provenance` against what the test finds itself (git, /proc/cpuinfo,
the environment it gives the run, the MUMPS header), and `nodus --version`."""

import json
import os
import pathlib
import re
import shutil
import subprocess

import pytest

from conftest import NODUS_BINARY, SOURCE_DIR, run_cli

# A cantilever of 4 elements bent by a tip load in 2 steps: no contact, a symmetric tangent.
CANTILEVER = """\
materials:
  - {name: steel, young_modulus: 200000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: steel, radius: 0.1, length: 10, elements: 4, start: [0, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
conditions:
  - {name: wall, type: clamp, beam: rod, at: start}
  - {name: tip, type: load, beam: rod, at: end, force: [0, 0, -0.01]}
stages:
  - {name: bend, steps: 2}
solver:
  linear_solver: %s
"""


def run_with(tmp_path, solver, threads):
    scenario = tmp_path / f"{solver}.yaml"
    scenario.write_text(CANTILEVER % solver)
    out = tmp_path / f"{solver}_{threads}"
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    p = subprocess.run([str(NODUS_BINARY), "run", str(scenario), "--out", str(out),
                        "--quiet"], capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 0, p.stderr
    return json.loads((out / "summary.json").read_text())["provenance"]


def git_head():
    """`git describe --always --abbrev=12` of the source tree, or None outside a git checkout."""
    if shutil.which("git") is None or not (SOURCE_DIR / ".git").exists():
        return None
    p = subprocess.run(["git", "-C", str(SOURCE_DIR), "describe", "--always", "--abbrev=12"],
                       capture_output=True, text=True)
    return p.stdout.strip() if p.returncode == 0 else None


def first_model_name():
    for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name") and ":" in line:
            return line.split(":", 1)[1].strip()
    return "unknown"


@pytest.mark.parametrize("threads", [1, 2])
def test_the_summary_says_which_nodus_machine_threads_and_solver(tmp_path, threads):
    p = run_with(tmp_path, "cholmod", threads)
    assert p["nodus"] == re.search(r"project\(nodus VERSION ([0-9.]+)",
                                   (SOURCE_DIR / "CMakeLists.txt").read_text()).group(1)
    head = git_head()
    if head is not None:
        # -dirty where the tree had uncommitted changes when built: the commit is the same.
        assert p["commit"].removesuffix("-dirty") == head
    assert p["processor"] == first_model_name()
    assert p["hardware_threads"] == os.cpu_count()
    assert p["threads"] == threads
    assert p["mpi_ranks"] == 1
    assert len(p["linear_solvers"]) == 1
    assert re.fullmatch(r"cholmod: SuiteSparse CHOLMOD \d+\.\d+\.\d+", p["linear_solvers"][0])


def test_the_summary_names_the_mumps_version_of_its_header(tmp_path):
    header = pathlib.Path("/usr/include/dmumps_c.h")
    if not header.exists():
        pytest.skip("no /usr/include/dmumps_c.h to read the MUMPS version from")
    version = re.search(r'#define MUMPS_VERSION "([^"]+)"', header.read_text()).group(1)
    assert run_with(tmp_path, "mumps", 1)["linear_solvers"] == [f"mumps_ldlt: MUMPS {version}"]


def test_version_flag_gives_the_summary_s_version_and_commit(tmp_path):
    p = run_with(tmp_path, "cholmod", 1)
    out = run_cli("--version", check_status=0).stdout.strip()
    assert out == f"nodus {p['nodus']} (commit {p['commit']})"
