"""Speed of the rigid-block model on walls in running bond: the contact problem solved in the
contacts' impulses against the blocks' velocities, side by side.

    python benchmarks/rigid_block_wall.py [--pulse-time 0.2] [--amplitude 0.3]
                                          [--quiet-time 0.05] [--all]

Walls of 0.4 m x 0.2 m blocks (friction 0.6) of about 50, 100 and 200 blocks
(:func:`archquake.geometry.assembly.wall`: 4 x 12, 8 x 12, 10 x 19 blocks per course; the
200-block wall only with ``--all``), their joints renumbered by reverse Cuthill-McKee
(:func:`archquake.rigid_blocks.dynamics.joint_order`, half-bandwidth ``b`` in joints) and their
blocks too for the velocities (:func:`archquake.rigid_blocks.block_space.block_band`,
half-bandwidth ``kb`` in velocities). For each, simulated seconds per minute of wall time
(whole ``simulate_blocks`` calls, setup included, JIT excluded, one run each), with
``BlockSettings.unknowns`` ``"impulses"`` and ``"velocities"`` and their ratio:

- on a still ground, the first ``--quiet-time`` seconds: the static contact problem is solved
  at the first steps, and the steps that repeat the equilibrium are skipped up to the decision
  of rest (0.1 s; :func:`~archquake.rigid_blocks.solver.steady_steps`);
- under a sine pulse of ``--amplitude`` g and 0.5 s, the first ``--pulse-time`` seconds (every
  step solves the contact problem), with the solves a step and the steps solved by Lemke's
  algorithm; both runs take the same steps (asserted; the motions agree to round-off, tested in
  ``tests/rigid_blocks/test_block_space.py``).

Measured (2 shared cores, ``--all``):

======  ======  ===  ===  ==========================  ================================
blocks  joints  b    kb   still (impulses, velocities)  0.3 g pulse (impulses, velocities)
======  ======  ===  ===  ==========================  ================================
50      130     17   20   992, 1,960 (2.0x)             107, 282 (2.6x)
100     272     33   38   190, 562 (3.0x)               12.1, 60.4 (5.0x)
195     546     42   47   5.3, 42.6 (8.0x)              2.32, 12.4 (5.4x)
======  ======  ===  ===  ==========================  ================================

Under 0.3 g the walls do not slide (their friction is 0.6) and the steps take 0.7-1.5 solves,
none by Lemke's algorithm. With ``--amplitude 0.7`` the bed joints reach the limit of friction
together and the active-set method cycles at some steps (the same in either unknowns: at the
first step of a 4 x 6 wall under 0.7 g no state of the 60 solves is consistent), which are then
solved by Lemke's algorithm on a dense tableau of four unknowns a contact: seconds a step for
100 blocks.
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
from archquake.rigid_blocks import (  # noqa: E402
    BlockSettings,
    from_block_assembly,
    simulate_blocks,
)
from archquake.rigid_blocks.dynamics import (  # noqa: E402
    UNKNOWNS,
    contact_unknowns,
    joint_half_bandwidth,
    joint_order,
)

WALLS = ((4, 12), (8, 12), (10, 19))


def running_bond_wall(courses: int, blocks: int):
    """The rigid blocks of a wall of 0.4 x 0.2 m blocks, friction 0.6."""
    return from_block_assembly(geometry_wall(courses, blocks, 0.4, 0.2, friction=0.6))


def rate(wall, motion, t_end: float, unknowns: str) -> tuple[float, object]:
    """Simulated seconds per minute of wall time (the whole call, its setup included), and the
    outcome."""
    settings = BlockSettings(friction=0.6, unknowns=unknowns)
    start = time.perf_counter()
    history = simulate_blocks(wall, motion, settings, t_end=t_end, record_every=10**6)
    return 60.0 * t_end / (time.perf_counter() - start), history.outcome


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pulse-time", type=float, default=0.2,
                        help="time simulated under the pulse [s]")
    parser.add_argument("--amplitude", type=float, default=0.3,
                        help="amplitude of the sine pulse [g]")
    parser.add_argument("--all", action="store_true", help="the 200-block wall too")
    parser.add_argument("--quiet-time", type=float, default=0.05,
                        help="time simulated on a still ground [s]")
    args = parser.parse_args(argv)
    pulse = sine_pulse(args.amplitude * GRAVITY, 0.5)
    for unknowns in UNKNOWNS[1:]:  # JIT
        simulate_blocks(running_bond_wall(2, 2), pulse, BlockSettings(unknowns=unknowns),
                        t_end=0.01)
    print(f"{'blocks':>6} {'joints':>6} {'b':>4} {'kb':>4} | still ground sim s/min "
          f"(impulses, velocities, ratio) | {args.amplitude:g} g sine pulse sim s/min "
          f"(impulses, velocities, ratio), solves/step, Lemke steps")
    for courses, blocks in WALLS if args.all else WALLS[:2]:
        wall = running_bond_wall(courses, blocks)
        b = joint_half_bandwidth(wall.joint_bodies, wall.n_blocks, joint_order(wall))
        kb = contact_unknowns(wall, "velocities")[1]
        quiet = [rate(wall, None, args.quiet_time, u)[0] for u in UNKNOWNS[1:]]
        shaken = [rate(wall, pulse, args.pulse_time, u) for u in UNKNOWNS[1:]]
        assert shaken[0][1].steps == shaken[1][1].steps  # the same motion
        print(f"{wall.n_blocks:6d} {wall.n_joints:6d} {b:4d} {kb:4d} | "
              f"{quiet[0]:9.3g} {quiet[1]:9.3g} {quiet[1] / quiet[0]:6.1f}x | "
              f"{shaken[0][0]:9.3g} {shaken[1][0]:9.3g} {shaken[1][0] / shaken[0][0]:6.1f}x "
              f" {shaken[1][1].mean_iterations:5.1f}  {shaken[1][1].fallback_steps:4d}",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
