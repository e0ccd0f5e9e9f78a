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

# OpenMP threads that wait by spinning slow everything down when another process wants their core (a 27-fibre
# factorisation 4.5x, docs/performance.md). libgomp reads the policy when it is loaded, which for most programs
# is with the extension below; if numpy (with Debian's OpenMP OpenBLAS) was imported first, it is already
# fixed. The user's own setting wins.
_os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _import_extension():
    """The extension, or an ImportError that names the interpreter it was built for where this is another."""
    import sys
    from . import _build
    here = f"{sys.executable} (Python {sys.version_info[0]}.{sys.version_info[1]})"
    built = f"{_build.executable} (Python {_build.python})"
    fix = (f"run it with {_build.executable}, or build nodus for this interpreter "
           f"(cmake -DPython3_EXECUTABLE={sys.executable} ..., with numpy installed for it)")
    same = _os.path.realpath(sys.executable) == _os.path.realpath(_build.executable)
    try:
        import numpy  # noqa: F401  (the extension's arrays)
    except ImportError as e:
        if same:
            raise
        raise ImportError(f"nodus was built for {built}; this is {here}, which cannot import numpy: {fix}") from e
    try:
        from . import _nodus as extension
    except ImportError as e:
        if same:
            raise
        raise ImportError(f"nodus was built for {built}; this is {here}, which cannot load it ({e}): {fix}") from e
    return extension


_nodus = _import_extension()  # after the wait policy
from ._nodus import ScenarioError, RunOutcome  # noqa: E402

__version__ = _nodus.version

__all__ = ["Scenario", "ScenarioError", "RunOutcome", "Simulation", "run", "keys", "strain_names",
           "contact_states", "knot_invariant", "min_self_distance", "min_distance_between", "knot_metrics", "tail_angle", "fit_circle",
           "rod_radius", "__version__"]

#: Names of the 15 strain measures, in the order of the columns of Simulation.element_strains().
strain_names = tuple(_nodus.strain_names)
#: Names of the values of the `state` array of Simulation.contact_elements(): 0 open, 1 stick, 2 slip.
contact_states = tuple(_nodus.contact_states)

_MESSAGE = _re.compile(
    r"^(?P<file>.*?):(?:(?P<line>[0-9]+):)? (?P<key>[^:]*): expected (?P<expected>.*?)(?:, got (?P<got>.*))?$")


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
    "built from Python data. The parts are attributes: file, line (None for a dict), key, expected, got.")
for _name in ("file", "line", "key", "expected", "got"):
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
        path = self._core.path
        return None if path in ("", "<dict>") else path

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
        stop_after_steps=0, timing_from=None):
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
    timing_from: the output folder of an earlier run of the same stages, as the command line's
        --timing-from: the progress lines estimate the time left from its timing.csv files.

    The GIL is released while nodus computes. Ctrl-C stops the run at the end of the current Newton iteration
    (the checkpoints already written let `resume=True` continue it) and raises KeyboardInterrupt. Bad input
    raises ScenarioError before anything is written.
    """
    scenario = _scenario(scenario)
    return _nodus.run(scenario._core, _os.fspath(out), jobs=max(1, int(jobs)), resume=resume, quiet=quiet,
                      verbose=verbose, branch=branch or "", stop_after_steps=stop_after_steps,
                      executable=_nodus.executable if _os.path.exists(_nodus.executable) else "",
                      timing_from=_os.fspath(timing_from) if timing_from else "")


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
        """Advances by `steps` (>= 1) converged load steps (fewer at the end of the run); returns the last
        step's record, or None if no step converged (the run had finished, or failed: see failure).
        callback(record) is called after each step; if it returns False the run stops there."""
        if int(steps) < 1:
            raise ValueError(f"steps: expected at least 1, got {steps}")
        done = self._sim.advance(max_steps=int(steps), callback=callback)
        return self._sim.last_step if done else None

    def run_stage(self, callback=None):
        """Advances to the end of the current stage; returns its last step's record (None if the run had
        already finished)."""
        done = self._sim.advance(to_stage_end=True, callback=callback)
        return self._sim.last_step if done else None

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

    def centreline(self, beam=0, segments_per_element=2):
        """(points (n, 3) [mm], arc_length (n,) [mm]): the axis of beam `beam` (index or name) as a polyline;
        with 2 segments per element its nodes, with more also points of each element's quadratic axis."""
        if isinstance(beam, str):
            beam = self.scenario.beams.index(beam)
        return self._sim.centreline(beam, segments_per_element)

    def contact_elements(self):
        """The contact elements of the last converged state as a dict of arrays, one row per element in the
        order of contact_final.csv: zone, beam_i, beam_j, element_i, element_j, zeta, abscissa_i, abscissa_j
        [mm], position_i, position_j, intermediate, normal (n, 3), gap [mm], normal_force R_N [N],
        friction_force (n, 3) on beam J [N], tangential_force |T| [N], state (0 open, 1 stick, 2 slip).
        Without contact forces (contact.forces: false, or before the first step) the forces are NaN and the
        state -1, as contact_final.csv leaves them empty."""
        return self._sim.contact_elements()

    def zones(self):
        """The proximity zones as a dict of arrays: beam_i, beam_j, a, b (interval on I), c, d (on J) [mm],
        first_element, contact_elements."""
        return self._sim.zones()

    def rigid_bodies(self):
        """{body name: {'position': (3,) c [mm], 'rotation': (3,) rotation vector theta [rad], 'force': (3,)
        [N], 'moment': (3,) [N mm] (what the body exerts on its bound sections, moment about c), 'error':
        the averaged conditions' penalty error [mm], 'tie': the tie's force [N]}} at the last converged step,
        as the BODY_* columns of steps.csv (docs/bodies.md); {} before the first step or without bodies."""
        last = self._sim.last_step
        return {} if last is None else last["bodies"]

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


def min_distance_between(points1, arc_length1, points2, arc_length2):
    """(distance, s1, s2): the smallest distance [mm] between the polylines `points1` and `points2` (two fibres),
    and the reference arc lengths of its ends on each (`arc_length1`, `arc_length2` of their vertices)."""
    return _nodus.min_distance_between(points1, arc_length1, points2, arc_length2)



def _centreline(nodes):
    if isinstance(nodes, Simulation):
        return nodes.centreline(0)
    if isinstance(nodes, tuple):
        return nodes
    if isinstance(nodes, dict):
        import numpy as np
        return np.column_stack([nodes["x"], nodes["y"], nodes["z"]]), nodes["s"]
    raise TypeError("nodes: expected a Simulation, (points, arc_length) or a dict with s, x, y, z")


def _contact_columns(contact):
    """A contact table with `state` and the beams as numbers (contact_final.csv has them as text: the beams
    are then numbered in the order their names first appear)."""
    import numpy as np
    contact = dict(contact)
    state = contact.get("state")
    if state is not None and len(state) and isinstance(state[0], str):
        contact["state"] = np.array([contact_states.index(s) for s in state])
    beams = [contact.get("beam_i"), contact.get("beam_j")]
    if all(b is not None for b in beams) and len(beams[0]) and isinstance(beams[0][0], str):
        names = list(dict.fromkeys(list(beams[0]) + list(beams[1])))
        for key, column in zip(("beam_i", "beam_j"), beams):
            contact[key] = np.array([names.index(b) for b in column])
    return contact


def knot_metrics(nodes, contact=None, *, beam=0, tail_chord=2.0, min_spacing=0.05, min_loop_nodes=5):
    """The metrics of a knot state (docs/knot.md; scripts/knot_report.py prints them):

    nodes: a Simulation (then its beam `beam` and all its contact elements are used, those with other beams
        included, as knot_report.py uses the whole contact_final.csv), or (points (n, 3),
        arc_length (n,)) of the rod's nodes in order, or a dict with columns s, x, y, z (final_nodes.csv of one
        beam, sorted by s);
    contact: a dict of columns, one entry per contact element: Simulation.contact_elements() or the columns of
        contact_final.csv (zone, zeta, abscissa_i, abscissa_j, x_i .. z_j, gap, normal_force,
        tangential_force, state).

    Returns a dict: zones, contact_elements, elements_in_contact; s_a, s_b (the arc length [mm] the elements
    in contact span: the knot); intermediate_length (sum over zones of the span of the elements in contact
    along the intermediate geometry) [mm]; max_normal, total_normal, max_tangential, total_tangential [N];
    tail_angle [deg] (180: tails pulled apart); loop_radius, loop_length [mm]; max_penetration [mm]; and
    `reactions`, per element sorted by (zone, zeta): element (index in `contact`), zone, zeta, abscissa
    along the intermediate geometry [mm], s_i, s_j, midpoint (n, 3), normal, tangential [N], state. NaN where
    a value is undefined (no element in contact, a loop covered by contact)."""
    if isinstance(nodes, Simulation):
        if contact is None:
            contact = nodes.contact_elements()
        nodes = nodes.centreline(beam)
    if contact is None:
        raise TypeError("contact: expected a dict of columns (contact_final.csv or Simulation.contact_elements())")
    points, s = _centreline(nodes)
    return _nodus.analyse_knot(points, s, _contact_columns(contact), tail_chord, min_spacing, min_loop_nodes)


def tail_angle(points, arc_length, s_a, s_b, tail_chord=2.0):
    """Angle [deg] between the tails leaving the knot [s_a, s_b] of the polyline `points` (n, 3) with
    reference arc lengths `arc_length`: between the chords c(s_a) -> c(s_a - tail_chord) and c(s_b) ->
    c(s_b + tail_chord). NaN for a chord of zero length."""
    return _nodus.tail_angle(points, arc_length, s_a, s_b, tail_chord)


def fit_circle(points):
    """Radius [mm] of the least-squares circle through the 3-D points (n, 3): their plane by SVD, then the
    algebraic (Kasa) fit in it. NaN for fewer than three points."""
    return _nodus.fit_circle(points)


def rod_radius(states, default_radius=0.1):
    """The rod radius [mm] measured from contact tables: the median distance of the particles x_i from the
    centreline at their abscissa, over `states` = [(nodes, contact), ...] (nodes as in knot_metrics: a
    Simulation gives its beam 0, and its contact elements when contact is None); `default_radius` when there
    is no contact element."""
    pairs = [(n, n.contact_elements() if c is None and isinstance(n, Simulation) else c) for n, c in states]
    centrelines = [tuple(_centreline(n)) for n, _ in pairs]
    return _nodus.rod_radius(centrelines, [_contact_columns(c) for _, c in pairs], default_radius)
