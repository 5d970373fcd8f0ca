"""Speed of the rigid-block model on walls in running bond: natural against renumbered joints.

    python benchmarks/rigid_block_wall.py [--pulse-time 0.002] [--quiet-time 0.05] [--all]

Walls of 0.4 m x 0.2 m blocks (friction 0.6) of about 50, 100 and 200 blocks
(:func:`archquake.geometry.assembly.wall`: 4 x 12, 8 x 12, 10 x 19 blocks per course; the
200-block wall only with ``--all``: it takes many minutes, see below), their joints numbered
as the geometry lists them and renumbered (reverse Cuthill-McKee,
:func:`archquake.rigid_blocks.dynamics.joint_order`). For each: the half-bandwidth in joints,
and simulated seconds per minute
of wall time (JIT excluded, one run each)

- on a still ground, the first ``--quiet-time`` seconds: the static contact problem is solved
  at the first steps, and the steps that repeat the equilibrium are skipped up to the decision
  of rest (0.1 s; :func:`~archquake.rigid_blocks.solver.steady_steps`), so the figure is that
  of a few solves of the whole static problem (after the decision a recorded run solves it at
  every step);
- under a sine pulse of 0.3 g and 0.5 s, the first ``--pulse-time`` seconds (every step solves
  the contact problem: the cost of a step as the wall is shaken).

Measured (2 shared cores; natural -> renumbered joints, simulated s per minute):

======  ==========  ===============  ===========  ==============  ===================
blocks  b (joints)  still, before    still        pulse, before   pulse (solves/step)
======  ==========  ===============  ===========  ==============  ===================
50      37 -> 17    319 -> 1090      284 -> 1130  4.0 -> 15.3     6.2 -> 25.2 (2.5)
100     37 -> 33    0.048 -> 0.056   108 -> 211   0.004 -> 0.003  1.9 -> 3.7 (3.0)
195     58 -> 42    not run          1.7 -> 4.8   not run         0.27 -> 0.88 (3.0)
======  ==========  ===============  ===========  ==============  ===================

"before": with the switching tests' velocity tolerance at 1e-12 g h, below the residuals that
the contact problem's compliance leaves in the velocities
(:data:`archquake.rigid_blocks.contact_problem.SWITCH_VELOCITY`, now 1e-9 g h): from about
100 blocks the active-set method then cycled at nearly every step, even at rest (a head joint,
carrying no normal force, found closing at -1e-14 m/s when open and pulling when held; 336-540
solves per step), and fell back to Lemke's algorithm on a dense tableau of 4 unknowns per
contact. Now the steps take about 3 solves and the cost left is the band's: Gaussian
elimination on a half-bandwidth that grows with the courses' length (42 joints, about 170 impulses,
for 19 blocks a course), which keeps the 195-block wall under the pulse near 1 simulated s per
minute.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake.geometry import GRAVITY  # noqa: E402
from archquake.geometry.assembly import wall as geometry_wall  # noqa: E402
from archquake.ground_motion import sine_pulse  # noqa: E402
from archquake.rigid_blocks import from_block_assembly, simulate_blocks  # noqa: E402
from archquake.rigid_blocks.dynamics import joint_half_bandwidth, joint_order  # noqa: E402

WALLS = ((4, 12), (8, 12), (10, 19))


def running_bond_wall(courses: int, blocks: int):
    """The rigid blocks of a wall of 0.4 x 0.2 m blocks, friction 0.6."""
    return from_block_assembly(geometry_wall(courses, blocks, 0.4, 0.2, friction=0.6))


def rate(wall, motion, t_end: float, reorder: bool) -> tuple[float, object]:
    """Simulated seconds per minute of wall time, and the outcome."""
    start = time.perf_counter()
    history = simulate_blocks(wall, motion, t_end=t_end, record_every=10**6, reorder=reorder)
    return 60.0 * t_end / (time.perf_counter() - start), history.outcome


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pulse-time", type=float, default=0.002,
                        help="time simulated under the pulse [s]")
    parser.add_argument("--all", action="store_true", help="the 200-block wall too")
    parser.add_argument("--quiet-time", type=float, default=0.05,
                        help="time simulated on a still ground [s]")
    args = parser.parse_args(argv)
    pulse = sine_pulse(0.3 * GRAVITY, 0.5)
    simulate_blocks(running_bond_wall(2, 2), pulse, t_end=0.01)  # JIT
    print(f"{'blocks':>6} {'joints':>6} {'b nat':>6} {'b RCM':>6} | still ground sim s/min "
          f"(nat, RCM) | 0.3 g sine pulse sim s/min (nat, RCM), solves/step")
    for courses, blocks in WALLS if args.all else WALLS[:2]:
        wall = running_bond_wall(courses, blocks)
        b_nat = joint_half_bandwidth(wall.joint_bodies, wall.n_blocks)
        b_rcm = joint_half_bandwidth(wall.joint_bodies, wall.n_blocks, joint_order(wall))
        quiet = [rate(wall, None, args.quiet_time, r)[0] for r in (False, True)]
        shaken = [rate(wall, pulse, args.pulse_time, r) for r in (False, True)]
        print(f"{wall.n_blocks:6d} {wall.n_joints:6d} {b_nat:6d} {b_rcm:6d} | "
              f"{quiet[0]:10.3g} {quiet[1]:10.3g}   | {shaken[0][0]:10.3g} {shaken[1][0]:10.3g}"
              f"  {shaken[0][1].mean_iterations:5.1f} {shaken[1][1].mean_iterations:5.1f}",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
