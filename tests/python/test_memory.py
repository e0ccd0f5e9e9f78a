"""7. No leak: 100 short runs in one process (a Simulation of a tiny scenario with contact, run to the end,
its arrays and contact arrays read) leave the resident memory flat after the first ones."""

import os

import nodus
from conftest import EXAMPLES

RUNS = 100
WARM_UP = 20
# Bound on the growth of the resident set from run 20 to run 100. A Simulation of this scenario kept alive
# costs about 0.38 MB (measured: 80 of them kept in a list, 30 MB), so leaking a whole run would pass the
# bound six times over; the bound leaves room for the allocator's and the interpreter's own caches.
BOUND_BYTES = 5 * 1024 * 1024


def resident_bytes():
    """Resident set size of this process from /proc/self/statm (second field, in pages)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def tiny_tool_drag():
    """tool_drag with 8 and 2 elements, 2 steps in each of press and drag: the tool ends in contact."""
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    d["beams"][0]["elements"] = 8
    d["beams"][1]["elements"] = 2
    d["stages"] = [st for st in d["stages"] if st["name"] in ("press", "drag")]
    for stage in d["stages"]:
        stage["steps"] = 2
    return d


def test_repeated_runs_do_not_leak():
    data = tiny_tool_drag()
    rss = {}
    for run in range(1, RUNS + 1):
        sim = nodus.Simulation(data)
        records = []
        sim.run(callback=records.append)
        assert sim.finished and sim.failure == "" and len(records) == 4
        contact = sim.contact_elements()
        assert len(contact["zone"]) > 0 and contact["normal_force"].sum() > 0
        sim.zones()
        sim.element_strains()
        positions = sim.positions  # a view that keeps the Simulation alive until it goes
        assert positions.shape == (len(sim.node_beam), 3)
        del sim, positions, contact, records
        if run in (1, WARM_UP, RUNS):
            rss[run] = resident_bytes()
    growth = rss[RUNS] - rss[WARM_UP]
    print(f"RSS after run 1: {rss[1] / 1e6:.2f} MB, run {WARM_UP}: {rss[WARM_UP] / 1e6:.2f} MB, "
          f"run {RUNS}: {rss[RUNS] / 1e6:.2f} MB; growth {growth / 1e3:.1f} kB (bound {BOUND_BYTES / 1e6:.1f} MB)")
    assert growth < BOUND_BYTES
