"""A run's folder (docs/output.md) as numpy arrays, without pandas.

    from nodus.results import Results
    run = Results("out/knot")
    run.steps["newton_iterations"]          # one value per converged step (numpy array)
    run.nodes().x                           # (nodes, 3) final centres [mm]; run.nodes("tighten"): a stage's end
    run.contact()["normal_force"]           # every contact element of the final state [N]
    run.stages                              # ["loop", "clamp", ...], the stages whose end was written
    run.branches["mu_0.30"].steps           # a branch's folder, read the same way
    run.picture(10)                         # vtk/step_000010.vtp (nodus.vtk.read_vtp)

Columns whose every value is a number become float arrays (integers stay exact below 2^53); the others (stage
names, cutback causes, beam names) arrays of str. Units are those of docs/output.md: mm, N, s.
"""

import csv
import json
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .vtk import read_vtp


def read_table(path):
    """The CSV file `path` (one header line, RFC 4180 quoting) as a dict of column name -> numpy array."""
    with open(path, newline="") as f:
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
        with open(self.folder / "summary.json") as f:
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
