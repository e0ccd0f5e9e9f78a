"""The module and the interpreter it is built for: an interpreter that cannot import numpy is told at configure
time in one message, and one that imports a module built for another is told which."""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import nodus
from conftest import SOURCE_DIR

PACKAGE = pathlib.Path(nodus.__file__).resolve().parent


def test_another_interpreter_is_told_which_one_nodus_was_built_for(tmp_path):
    copy = tmp_path / "nodus"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    (copy / "_build.py").write_text('executable = "/opt/other/bin/python3"\npython = "3.99"\n')
    # -S: without the site packages, where Debian's numpy is: an interpreter without numpy.
    p = subprocess.run([sys.executable, "-S", "-c", "import nodus"], capture_output=True, text=True,
                       env=dict(os.environ, PYTHONPATH=str(tmp_path)))
    assert p.returncode != 0
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: nodus was built for /opt/other/bin/python3 (Python 3.99); this is "
                           f"{sys.executable} (Python {sys.version_info[0]}.{sys.version_info[1]}), which "
                           "cannot import numpy"), last
    assert f"cmake -DPython3_EXECUTABLE={sys.executable}" in last


def test_the_interpreter_it_was_built_for_imports_it():
    from nodus import _build
    assert os.path.realpath(_build.executable) == os.path.realpath(sys.executable)
    assert _build.python == f"{sys.version_info[0]}.{sys.version_info[1]}"


def python_without_numpy(folder):
    """An interpreter that cannot import numpy: this one without the site packages, where Debian's numpy is."""
    folder.mkdir()
    fake = folder / "python3"
    fake.write_text(f'#!/bin/sh\nexec {sys.executable} -S "$@"\n')
    fake.chmod(0o755)
    return fake


def configure(build, *options, env=None):
    """CMake's configure step of nodus (no tests, no benchmarks, no PETSc: the quickest) into `build`."""
    p = subprocess.run(["cmake", "-S", str(SOURCE_DIR), "-B", str(build), "-G", "Ninja", *options,
                        "-DNODUS_BUILD_TESTS=OFF", "-DNODUS_BUILD_BENCHMARKS=OFF", "-DNODUS_WITH_PETSC=OFF"],
                       capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 0, p.stderr  # the rest of nodus builds, with or without the module
    return " ".join(p.stderr.split())


needs_cmake = pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("ninja") is None,
                                 reason="no cmake or ninja")


@needs_cmake
def test_configure_says_in_one_message_that_the_named_interpreter_has_no_numpy(tmp_path):
    fake = python_without_numpy(tmp_path / "bin")
    message = configure(tmp_path / "build", f"-DPython3_EXECUTABLE={fake}")
    assert (f"the Python module is not built: {fake} (Python {sys.version_info[0]}.{sys.version_info[1]}"
            in message), p.stderr
    assert "cannot import numpy" in message
    assert not (tmp_path / "build" / "python").exists()


@needs_cmake
@pytest.mark.skipif(not pathlib.Path("/usr/bin/python3").exists(), reason="no /usr/bin/python3")
def test_a_python3_on_path_without_numpy_gives_way_to_debian_s_said(tmp_path):
    fake = python_without_numpy(tmp_path / "bin")
    message = configure(tmp_path / "build", env=dict(os.environ, PATH=f"{fake.parent}:{os.environ['PATH']}"))
    assert (f"{fake}, the python3 first on PATH, cannot import numpy: the Python module is built for "
            "/usr/bin/python3" in message), message
    build_info = (tmp_path / "build" / "python" / "nodus" / "_build.py").read_text()
    assert 'executable = "/usr/bin/python3"' in build_info
