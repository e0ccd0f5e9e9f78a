"""Shared fixtures and helpers of the tests of the Python module (tests/python/).

Run by CTest (test `python`) with PYTHONPATH set to BUILD/python, NODUS_BINARY to the command-line
executable and NODUS_SOURCE_DIR to the repository; by hand:

    PYTHONPATH=build/release/python /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python

Every test writes only under its tmp_path. The references are the command line (`nodus run`, `nodus check`),
the scenario files as text, and invariances of the API (stepping versus running, resumed versus not).
"""

import json
import os
import pathlib
import re
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("NODUS_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
NODUS_BINARY = pathlib.Path(os.environ.get("NODUS_BINARY", SOURCE_DIR / "build" / "release" / "nodus"))
EXAMPLES = SOURCE_DIR / "examples"

# tool_drag with 20 and 2 elements and fewer steps, plus two branches from the end of `drag`: the scenario
# kDrag + kBranches of tests/app/cli_test_support.hpp (the C++ tests of run()), 11 main steps.
DRAG_WITH_BRANCHES = """\
materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: nylon, radius: 0.1, length: 10, elements: 20, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: tool, material: nylon, radius: 0.2, length: 2, elements: 2, start: [0, -1, 0.31],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: left, type: clamp, beam: beam, at: start, dofs: [position, g1z]}
  - {name: right, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: press, type: rigid, beam: tool}
stages:
  - name: press
    steps: 3
    motions:
      press: {translation: [0, 0, -0.1]}
  - name: drag
    steps: 4
    motions:
      press: {translation: [0, 0.3, -0.1]}
  - name: back
    steps: 3
    motions:
      press: {translation: [0, 0.1, -0.1]}
  - name: lift
    steps: 1
    contact_off: [tool]
contact:
  self_contact: false
  friction: 0.3
output:
  vtk_every: 2
  contact_csv: true
branches:
  - name: same
    from: drag
    stages:
      - name: back
        steps: 3
        motions:
          press: {translation: [0, 0.1, -0.1]}
      - name: lift
        steps: 1
        contact_off: [tool]
  - name: mu_0.1
    from: drag
    contact: {friction: 0.1}
    stages:
      - name: back
        steps: 3
        motions:
          press: {translation: [0, 0.1, -0.1]}
"""


@pytest.fixture(scope="session")
def nodus_binary():
    assert NODUS_BINARY.is_file(), f"no nodus executable at {NODUS_BINARY} (set NODUS_BINARY)"
    return NODUS_BINARY


def run_cli(*args, check_status=None):
    """`nodus ARGS...`: the CompletedProcess (text); asserts the exit status when check_status is given."""
    p = subprocess.run([str(NODUS_BINARY), *map(str, args)], capture_output=True, text=True, timeout=300)
    if check_status is not None:
        assert p.returncode == check_status, f"nodus {' '.join(map(str, args))}: {p.returncode}\n{p.stderr}"
    return p


def yaml_names(path, section):
    """The `name:` of each item of the top-level list `section` of a scenario file, read from its text (the
    files of examples/ write items as `  - {name: X, ...}` or `  - name: X`)."""
    names, inside = [], False
    for line in pathlib.Path(path).read_text(encoding="utf-8").splitlines():
        if re.match(r"^[A-Za-z_]+:", line):
            inside = line.startswith(section + ":")
            continue
        m = re.match(r"^  - \{?name: *([^,}\s]+)", line)
        if inside and m:
            names.append(m.group(1))
    return names


def _without_seconds(value):
    # `analyses` counts the linear solver's analyses, which a resumed process does again for its first step:
    # in a stage without contact (analysed once at the stage start) it counts one more than a run never
    # stopped, as its wall times differ (docs/output.md). `provenance` describes the process that wrote the
    # file (its threads, the solvers it used), not the result.
    if isinstance(value, dict):
        return {k: _without_seconds(v) for k, v in value.items()
                if not k.endswith("_seconds") and k not in ("analyses", "provenance")}
    if isinstance(value, list):
        return [_without_seconds(v) for v in value]
    return value


# The root attributes of result.h5 that describe the process that wrote it, not the result (docs/output.md).
PROVENANCE_ATTRIBUTES = {"nodus", "commit", "processor", "hardware_threads", "threads", "mpi_ranks",
                         "linear_solvers"}


def h5_content(path):
    """Every dataset and attribute of the HDF5 file `path` but the provenance, as a dict of path -> repr of the
    values (external links as their target)."""
    import h5py
    import numpy as np
    content = {}
    with h5py.File(path, "r") as f:
        content["@"] = {k: repr(v) for k, v in f.attrs.items() if k not in PROVENANCE_ATTRIBUTES}

        def visit(group, at):
            for key in group:
                name = f"{at}/{key}"
                link = group.get(key, getlink=True)
                if isinstance(link, h5py.ExternalLink):
                    content[name] = ("external", link.filename, link.path)
                    continue
                obj = group[key]
                attrs = {k: repr(v) for k, v in obj.attrs.items()}
                if isinstance(obj, h5py.Dataset):
                    value = obj[()]
                    content[name] = (obj.shape, repr(value) if obj.dtype.kind == "O" else
                                     np.asarray(value).tobytes(), attrs)
                else:
                    content[name] = ("group", attrs)
                    visit(obj, name)
        visit(f, "")
    return content


def assert_same_outputs(reference, folder):
    """Every file of the two output folders equal byte for byte, except summary.json (compared as JSON
    without its wall-clock `*_seconds` values, its count of analyses and its provenance), timing.csv (compared without its
    last column, wall_seconds) and the checkpoints (they hold the times too: the same file names only)."""
    reference, folder = pathlib.Path(reference), pathlib.Path(folder)
    files_a = sorted(p.relative_to(reference).as_posix() for p in reference.rglob("*") if p.is_file())
    files_b = sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file())
    assert files_a == files_b
    assert any(name.endswith("summary.json") for name in files_a)
    for name in files_a:
        a, b = reference / name, folder / name
        if "checkpoints/" in name:
            continue
        if name.endswith("summary.json"):
            ja = _without_seconds(json.loads(a.read_text()))
            jb = _without_seconds(json.loads(b.read_text()))
            assert ja == jb, name
        elif name.endswith("result.h5"):
            # By content: HDF5 places what a resumed run rewrites elsewhere in the file.
            assert h5_content(a) == h5_content(b), f"{name} differs"
        elif name.endswith("timing.csv"):
            ta = [line.rsplit(",", 1)[0] for line in a.read_text().splitlines()]
            tb = [line.rsplit(",", 1)[0] for line in b.read_text().splitlines()]
            assert ta == tb, f"{name} differs"
        else:
            assert a.read_bytes() == b.read_bytes(), f"{name} differs"
