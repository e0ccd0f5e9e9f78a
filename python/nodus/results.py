"""A run's folder (docs/output.md) as numpy arrays, without pandas.

    from nodus.results import Results
    run = Results("out/knot")
    run.steps["newton_iterations"]          # one value per converged step (numpy array)
    run.nodes().x                           # (nodes, 3) final centres [mm]; run.nodes("tighten"): a stage's end
    run.contact()["normal_force"]           # every contact element of the final state [N]
    run.stages                              # ["loop", "clamp", ...], the stages whose end was written
    run.branches["mu_0.30"].steps           # a branch's folder, read the same way
    run.picture(10)                         # vtk/step_000010.vtp (nodus.vtk.read_vtp)

or from the run's result.h5, every output state in one file (needs h5py: Debian's python3-h5py):

    import nodus.results
    r = nodus.results.open("out/knot")
    r.steps["normal_force"]                 # the step table of steps.csv, column by column
    r.states[-1].centre                     # (nodes, 3) centres of the last output state [mm]
    r.states[i].contact["normal_force"]     # its contact elements, columns of contact_final.csv
    r.branches["mu_0.30"]                   # a branch's result.h5, read the same way

Columns whose every value is a number become float arrays (integers stay exact below 2^53); the others (stage
names, cutback causes, beam names) arrays of str. Units are those of docs/output.md: mm, N, s.
"""

import builtins
import csv
import json
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .vtk import read_vtp


def read_table(path):
    """The CSV file `path` (one header line, RFC 4180 quoting) as a dict of column name -> numpy array."""
    with builtins.open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    columns = {}
    for k, name in enumerate(header):
        values = [row[k] if k < len(row) else "" for row in rows]
        try:
            columns[name] = np.array([float(v) for v in values])
        except ValueError:
            columns[name] = np.array(values, dtype=str)
    return columns


@dataclass
class Nodes:
    """The nodes of a state: per node its beam's name, its index within the beam, its reference arc length s
    [mm], its centre x (n, 3) [mm] and directors g1, g2 (n, 3)."""

    beam: np.ndarray
    node: np.ndarray
    s: np.ndarray
    x: np.ndarray
    g1: np.ndarray
    g2: np.ndarray

    def of(self, beam):
        """The nodes of beam `beam` (its name), in order."""
        mine = self.beam == beam
        if not mine.any():
            raise KeyError(f"no beam named {beam!r} (beams: {sorted(set(self.beam))})")
        return Nodes(*(getattr(self, f)[mine] for f in ("beam", "node", "s", "x", "g1", "g2")))


class Results:
    """The files of one run's folder (a branch's folder too). Raises FileNotFoundError naming what is missing."""

    def __init__(self, folder):
        self.folder = Path(folder)
        if not (self.folder / "steps.csv").is_file():
            raise FileNotFoundError(f"{self.folder}: expected a run's folder with steps.csv (docs/output.md)")

    @property
    def steps(self):
        """steps.csv: one value per converged step for every column."""
        return read_table(self.folder / "steps.csv")

    @property
    def summary(self):
        """summary.json as a dict (written when the run ends)."""
        with builtins.open(self.folder / "summary.json") as f:
            return json.load(f)

    def _stage_file(self, stage, kind):
        """stages/NNN_STAGE_KIND.csv of `stage` (its name or its index NNN)."""
        for path in sorted((self.folder / "stages").glob(f"*_{kind}.csv")):
            index, name = path.name[:-len(f"_{kind}.csv")].split("_", 1)
            if stage in (name, int(index)):
                return path
        raise FileNotFoundError(f"{self.folder}/stages: no {kind} table of stage {stage!r} (stages: {self.stages})")

    @property
    def stages(self):
        """The names of the stages whose end tables were written, in order."""
        names = []
        for path in sorted((self.folder / "stages").glob("*_nodes.csv")):
            match = re.fullmatch(r"(\d+)_(.*)_nodes\.csv", path.name)
            if match:
                names.append(match.group(2))
        return names

    def nodes(self, stage=None):
        """The nodes of the final state (final_nodes.csv), or of the end of `stage` (name or index)."""
        path = self.folder / "final_nodes.csv" if stage is None else self._stage_file(stage, "nodes")
        t = read_table(path)
        xyz = lambda *c: np.column_stack([t[k] for k in c])  # noqa: E731
        return Nodes(t["beam"].astype(str), t["node"].astype(int), t["s"], xyz("x", "y", "z"),
                     xyz("g1x", "g1y", "g1z"), xyz("g2x", "g2y", "g2z"))

    def contact(self, stage=None):
        """The contact elements of the final state (contact_final.csv), or of the end of `stage`."""
        return read_table(self.folder / "contact_final.csv" if stage is None else self._stage_file(stage, "contact"))

    @property
    def zones(self):
        """zones_final.csv: the proximity zones of the final state."""
        return read_table(self.folder / "zones_final.csv")

    @property
    def branches(self):
        """The branches' folders (branches/NAME/), each a Results, by name."""
        folder = self.folder / "branches"
        return {p.name: Results(p) for p in sorted(folder.iterdir()) if (p / "steps.csv").is_file()} \
            if folder.is_dir() else {}

    def picture(self, step):
        """The VTK picture of the beams at converged step `step` (vtk/step_NNNNNN.vtp, nodus.vtk.Picture)."""
        return read_vtp(self.folder / "vtk" / f"step_{step:06d}.vtp")

    def contact_picture(self, step):
        """The VTK picture of the contact geometry at converged step `step` (vtk/contact_NNNNNN.vtp)."""
        return read_vtp(self.folder / "vtk" / f"contact_{step:06d}.vtp")


def _h5py():
    """h5py, or an ImportError that says how to install it."""
    try:
        import h5py
    except ImportError as e:
        raise ImportError("nodus.results.open reads result.h5 with h5py, which this Python lacks: install "
                          "Debian's python3-h5py (scripts/setup.sh does), or `pip install h5py`") from e
    return h5py


def _columns(group):
    """The 1-D datasets of an HDF5 group as a dict of name -> numpy array (strings as str)."""
    out = {}
    for name, dataset in group.items():
        out[name] = dataset.asstr()[()] if dataset.dtype.kind == "O" else dataset[()]
        if dataset.dtype.kind == "O":
            out[name] = np.array(out[name], dtype=str)
    return out


class State:
    """One output state of result.h5 (/states/NNNNNN): `step`, `load_time` [s] and `stage` at once; its arrays
    read from the file when first asked for: `centre`, `g1`, `g2`, `displacement` (nodes, 3) [mm, -, -, mm],
    `fields` (the fifteen strain measures by name, as the VTK files), `contact` and `zones` (dicts of columns as
    contact_final.csv and zones_final.csv, beams as indices; None without contact)."""

    def __init__(self, path, name, step, load_time, stage):
        self._path, self._name = path, name
        self.step, self.load_time, self.stage = step, load_time, stage
        self._data = None

    def _load(self):
        if self._data is None:
            with _h5py().File(self._path, "r") as f:
                g = f["states"][self._name]
                data = {k: g[k][()] for k in g if isinstance(g[k], _h5py().Dataset)}
                data["contact"] = _columns(g["contact"]) if "contact" in g else None
                data["zones"] = _columns(g["zones"]) if "zones" in g else None
            self._data = data
        return self._data

    centre = property(lambda self: self._load()["centre"])
    g1 = property(lambda self: self._load()["g1"])
    g2 = property(lambda self: self._load()["g2"])
    displacement = property(lambda self: self._load()["displacement"])
    contact = property(lambda self: self._load()["contact"])
    zones = property(lambda self: self._load()["zones"])

    @property
    def fields(self):
        return {k: v for k, v in self._load().items()
                if k not in ("centre", "g1", "g2", "displacement", "contact", "zones")}

    def __repr__(self):
        return f"State(step={self.step}, load_time={self.load_time}, stage={self.stage!r})"


class Result:
    """A run's result.h5 (docs/output.md, "result.h5"): `name` ("main" or the branch), `attrs` (the root
    attributes: format, units, provenance), `scenario` (the resolved settings as text), `beams`, `stages`, `steps`
    (dicts of columns), `segments` (E, 2) node pairs of the centrelines, `states` (list of State, in step
    order) and `branches` (dict of Result by name)."""

    def __init__(self, folder):
        h5py = _h5py()
        self.folder = Path(folder)
        self.path = self.folder / "result.h5"
        if not self.path.is_file():
            raise FileNotFoundError(f"{self.path}: expected a nodus result file (result.h5), got none")
        try:
            f = h5py.File(self.path, "r")
        except OSError as e:
            raise OSError(f"{self.path}: expected an HDF5 file (a nodus result.h5), got one HDF5 cannot open") from e
        with f:
            if f.attrs.get("format") != "nodus-result":
                raise ValueError(f"{self.path}: expected a nodus result (root attribute format = 'nodus-result')")
            self.attrs = dict(f.attrs)
            self.name = self.attrs.get("run", "main")
            self.scenario = f["scenario"].asstr()[()]
            self.beams = _columns(f["beams"])
            self.stages = _columns(f["stages"])
            self.steps = _columns(f["steps"])
            self.segments = f["mesh"]["segments"][()]
            states = []
            for name, g in f["states"].items():
                states.append(State(self.path, name, int(g.attrs["step"]), float(g.attrs["load_time"]),
                                    str(g.attrs["stage"])))
            self.states = sorted(states, key=lambda s: s.step)
            names = list(f["branches"].keys()) if "branches" in f else []
        self.branches = {n: Result(self.folder / "branches" / n) for n in names
                         if (self.folder / "branches" / n / "result.h5").is_file()}

    def state(self, step):
        """The state of converged step `step`; KeyError naming the steps there are if it has none."""
        for s in self.states:
            if s.step == step:
                return s
        raise KeyError(f"{self.path}: no state of step {step} (steps: {[s.step for s in self.states]})")

    def __repr__(self):
        return f"Result({str(self.folder)!r}, {len(self.states)} states, branches {list(self.branches)})"


def open(folder):  # noqa: A001 (nodus.results.open, as h5py.File or builtins.open: a file by its path)
    """The result.h5 of the run in `folder` as a Result (numpy arrays from h5py). Raises ImportError if h5py is
    missing, FileNotFoundError if the folder has no result.h5, OSError or ValueError if it is not one."""
    return Result(folder)
