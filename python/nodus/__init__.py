"""nodus: contact-friction mechanics of elastic fibre assemblies (Durville 2012), from Python.

Units are those of the scenario files: mm, N, MPa, s.

    import nodus
    scenario = nodus.Scenario.from_yaml("examples/bend_and_release.yaml")
    outcome = nodus.run(scenario, "out/bend", quiet=True)      # what `nodus run` does, the same files

    sim = nodus.Simulation(scenario)                            # or step it yourself, in memory
    while not sim.finished:
        record = sim.step()                                     # one converged load step (a dict)
    sim.positions                                               # (nodes, 3) numpy view of the state

See docs/python.md for the whole API and a tutorial.
"""

import copy as _copy
import os as _os
import re as _re

from . import _nodus
from ._nodus import ScenarioError, RunOutcome

__version__ = _nodus.version

__all__ = ["Scenario", "ScenarioError", "RunOutcome", "Simulation", "run", "keys", "strain_names",
           "contact_states", "knot_invariant", "min_self_distance", "__version__"]

#: Names of the 15 strain measures, in the order of the columns of Simulation.element_strains().
strain_names = tuple(_nodus.strain_names)
#: Names of the values of the `state` array of Simulation.contact_elements(): 0 open, 1 stick, 2 slip.
contact_states = tuple(_nodus.contact_states)

_MESSAGE = _re.compile(r"^(?P<file>.*?):(?:(?P<line>[0-9]+):)? (?P<key>[^:]*): expected (?P<expected>.*)$")


def _error_field(name):
    def get(self):
        match = _MESSAGE.match(str(self))
        if not match:
            return None
        value = match.group(name)
        return int(value) if name == "line" and value is not None else value
    get.__doc__ = f"The {name} of the message, or None."
    return property(get)


ScenarioError.__doc__ = (
    "Bad input: a scenario, a value, an output folder. A ValueError whose message is the command line's: "
    "'FILE:LINE: KEY: expected ..., got ...' for a file, '<dict>: KEY: expected ..., got ...' for a scenario "
    "built from Python data. The parts are attributes: file, line (None for a dict), key, expected.")
for _name in ("file", "line", "key", "expected"):
    setattr(ScenarioError, _name, _error_field(_name))


class Scenario:
    """A scenario: the loading program of a run, with the keys of the YAML file (docs/scenario.md).

    Built from a file (Scenario.from_yaml) or from Python data with the same keys (Scenario(dict)); read and
    checked by the same C++ reader either way, so bad input raises ScenarioError with the same message as
    `nodus check` (without line numbers for a dict). The data is kept: to_dict() gives a copy to change and
    build a new Scenario from; to_yaml() writes it as a scenario file.
    """

    def __init__(self, data):
        """A scenario from a dict with the keys of a scenario file (numpy arrays and scalars are accepted)."""
        if isinstance(data, Scenario):
            data = data.to_dict()
        self._core = _nodus.from_data(data)
        self._data = _nodus.yaml_to_data(_nodus.data_to_yaml(data))  # plain Python types only

    @classmethod
    def from_yaml(cls, path):
        """Reads the scenario file `path`; raises ScenarioError (FILE:LINE: KEY: ...) on bad input."""
        path = _os.fspath(path)
        self = cls.__new__(cls)
        self._core = _nodus.read_file(path)
        with open(path, encoding="utf-8") as f:
            self._data = _nodus.yaml_to_data(f.read())
        return self

    @property
    def path(self):
        """The file the scenario was read from, or None for one built from data."""
        return self._core.path or None

    @property
    def beams(self):
        """The beam names, in order."""
        return list(self._core.beams)

    @property
    def conditions(self):
        """The condition names, in order."""
        return list(self._core.conditions)

    @property
    def stages(self):
        """The stage names of the main run, in order."""
        return list(self._core.stages)

    @property
    def branches(self):
        """The branch names."""
        return list(self._core.branches)

    def to_dict(self):
        """A deep copy of the scenario's data: dicts, lists, numbers, bools and text."""
        return _copy.deepcopy(self._data)

    def to_yaml(self, path=None):
        """The scenario as YAML text; also written to `path` when given. Reading it back gives the same
        scenario (the same canonical_text())."""
        text = _nodus.data_to_yaml(self._data)
        if path is not None:
            with open(_os.fspath(path), "w", encoding="utf-8") as f:
                f.write(text)
        return text

    def validate(self):
        """Every check of `nodus check` (the reader's and the model's); raises ScenarioError. A Scenario is
        checked by the reader when built; this adds the checks that need the model (e.g. a node held by two
        conditions)."""
        self._core.validate()

    def describe(self):
        """The resolved settings (defaults filled in), as `nodus check` prints them."""
        return self._core.describe()

    def canonical_text(self):
        """Every value that shapes the results as KEY = VALUE lines: equal texts, equal runs."""
        return self._core.canonical_text()

    def __repr__(self):
        where = f" from {self.path!r}" if self.path else ""
        return (f"<nodus.Scenario{where}: {len(self.beams)} beams, {len(self.stages)} stages, "
                f"{len(self.branches)} branches>")


def _scenario(scenario):
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, dict):
        return Scenario(scenario)
    return Scenario.from_yaml(scenario)


def run(scenario, out, *, jobs=1, resume=False, quiet=False, verbose=False, branch=None,
        stop_after_steps=0):
    """Runs a scenario exactly as `nodus run SCENARIO --out OUT` does, with the same files, checkpoints,
    branches and resume, and returns a RunOutcome (converged, interrupted, already_complete).

    scenario: a Scenario, a dict, or the path of a scenario file.
    jobs: branches side by side, each in a process of the `nodus` executable built with this module (a
        scenario built from data has no file for them to read: its branches run here, one at a time; the
        results are the same).
    resume: continue the interrupted run in `out` from its newest checkpoint.
    quiet, verbose: as the command line's --quiet and --verbose (log lines go to stderr).
    branch: run only this branch (the main run must have reached its `from` stage).
    stop_after_steps: for tests, stop as if killed after that many converged steps.

    The GIL is released while nodus computes. Ctrl-C stops the run at the end of the current Newton iteration
    (the checkpoints already written let `resume=True` continue it) and raises KeyboardInterrupt. Bad input
    raises ScenarioError before anything is written.
    """
    scenario = _scenario(scenario)
    return _nodus.run(scenario._core, _os.fspath(out), jobs=max(1, int(jobs)), resume=resume, quiet=quiet,
                      verbose=verbose, branch=branch or "", stop_after_steps=stop_after_steps,
                      executable=_nodus.executable if _os.path.exists(_nodus.executable) else "")


class Simulation:
    """A scenario's main run, stepped from Python and kept in memory (no files: use nodus.run for those).

    step(), run_stage() and run() advance it; each converged load step can call a callback with the step's
    record (the columns of steps.csv as a dict, with `reactions` per condition). The state is read as numpy
    arrays: positions, d1 and d2 are read-only views of the last converged state without a copy (they follow
    the run: copy them to keep a state); the rest is computed when asked.

    The GIL is released while nodus computes. Ctrl-C stops at the end of the current Newton iteration and
    leaves the last converged state, raising KeyboardInterrupt; the run can go on with the next call.
    """

    def __init__(self, scenario):
        self.scenario = _scenario(scenario)
        self._sim = _nodus._Simulation(self.scenario._core)

    def step(self, steps=1, callback=None):
        """Advances by `steps` converged load steps (fewer at the end of the run); returns the last step's
        record, or None if the run had already finished. callback(record) is called after each step; if it
        returns False the run stops there."""
        self._sim.advance(max_steps=steps, callback=callback)
        return self._sim.last_step

    def run_stage(self, callback=None):
        """Advances to the end of the current stage; returns its last step's record."""
        self._sim.advance(to_stage_end=True, callback=callback)
        return self._sim.last_step

    def run(self, callback=None):
        """Advances to the end of the run (every stage); returns the number of steps converged."""
        return self._sim.advance(callback=callback)

    @property
    def finished(self):
        """Every stage done, or the run failed (see failure)."""
        return self._sim.finished

    @property
    def failure(self):
        """Why the run stopped early ('' if it did not)."""
        return self._sim.failure

    @property
    def time(self):
        """Load time of the last converged state [s]."""
        return self._sim.time

    @property
    def steps(self):
        """Converged load steps so far."""
        return self._sim.steps

    @property
    def stage(self):
        """The name of the stage in progress (or next to begin), None once every stage is done."""
        i = self._sim.stage_index
        stages = self.scenario.stages
        return stages[i] if i < len(stages) else None

    @property
    def last_step(self):
        """The record of the last converged step (a dict), or None before the first."""
        return self._sim.last_step

    @property
    def reactions(self):
        """{condition name: {'force': (3,) [N], 'moment': (3,) [N mm]}} at the last converged step: the
        reaction of a prescribed motion, the applied load of a load (as in steps.csv)."""
        last = self._sim.last_step
        return {} if last is None else last["reactions"]

    positions = property(lambda self: self._sim.positions,
                         doc="(nodes, 3) read-only view: the node positions r [mm].")
    d1 = property(lambda self: self._sim.d1, doc="(nodes, 3) read-only view: the section directors g1 [-].")
    d2 = property(lambda self: self._sim.d2, doc="(nodes, 3) read-only view: the section directors g2 [-].")
    state = property(lambda self: self._sim.state,
                     doc="Copy of the whole state vector: nine values (r, g1, g2) per node.")
    reference_positions = property(lambda self: self._sim.reference_positions,
                                   doc="(nodes, 3): the node positions of the reference (initial) state [mm].")
    node_beam = property(lambda self: self._sim.node_beam, doc="(nodes,): the beam index of each node.")
    element_beam = property(lambda self: self._sim.element_beam,
                            doc="(elements,): the beam index of each element.")
    element_nodes = property(lambda self: self._sim.element_nodes,
                             doc="(elements, 3): the three nodes of each element.")

    def element_strains(self, xi=0.0):
        """(elements, 15): the strain measures of each element at its local coordinate xi in [-1, 1] (0: its
        centre); columns named by nodus.strain_names."""
        return self._sim.element_strains(xi)

    def node_strains(self):
        """(nodes, 15): the strain measures at each node (mean of the elements that share it)."""
        return self._sim.node_strains()

    def contact_elements(self):
        """The contact elements of the last converged state as a dict of arrays, one row per element in the
        order of contact_final.csv: zone, beam_i, beam_j, element_i, element_j, zeta, abscissa_i, abscissa_j
        [mm], position_i, position_j, intermediate, normal (n, 3), gap [mm], normal_force R_N [N],
        friction_force (n, 3) on beam J [N], tangential_force |T| [N], state (0 open, 1 stick, 2 slip)."""
        return self._sim.contact_elements()

    def zones(self):
        """The proximity zones as a dict of arrays: beam_i, beam_j, a, b (interval on I), c, d (on J) [mm],
        first_element, contact_elements."""
        return self._sim.zones()

    def rigid_bodies(self):
        """The rigid bodies of the model: none until scenarios can declare them (issue 16)."""
        return {}

    def internal_energy(self):
        """Strain energy of the beams in the last converged state [N mm]."""
        return self._sim.internal_energy()

    def __repr__(self):
        return (f"<nodus.Simulation: {self.steps} steps, load time {self.time:g} s, stage {self.stage!r}"
                f"{', failed: ' + self.failure if self.failure else ''}>")


def keys():
    """The table of scenario keys (name, type, unit, default, range, help) as markdown, as `nodus keys`."""
    return _nodus.keys_markdown()


def knot_invariant(points):
    """Knot type of the open polyline `points` (n, 3) [mm], closed far away: a dict with the Alexander
    polynomial's coefficients and text, the determinant |Delta(-1)|, and flags unknot and trefoil."""
    return _nodus.knot_invariant(points)


def min_self_distance(points, arc_length, separation):
    """(distance, s1, s2): the smallest distance [mm] between two points of the polyline `points` whose
    reference arc lengths `arc_length` differ by at least `separation` [mm]."""
    return _nodus.min_self_distance(points, arc_length, separation)
