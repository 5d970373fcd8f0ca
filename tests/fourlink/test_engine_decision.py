"""The end-of-excitation decision checks every arrival until the energy can only decrease."""

import math

import pytest

from archquake.fourlink import engine
from archquake.fourlink.engine import rules
from archquake.fourlink.engine import tables as compiled_tables
from archquake.fourlink.mechanism import mechanisms
from archquake.geometry import irregular_arch


def _state_returning_with(kinetic_at_theta_u, table, scal_row, pack, m):
    """(theta, theta') just below theta_u, moving back, with the given kinetic energy there."""
    scal = pack[0]
    th = scal[m, 0] - 1e-9
    mass = compiled_tables.table_function(th, compiled_tables.ROW_M, m, pack)
    v = compiled_tables.table_function(th, compiled_tables.ROW_V, m, pack)
    v_u = compiled_tables.table_function(scal[m, 0], compiled_tables.ROW_V, m, pack)
    return th, math.sqrt(2.0 * (kinetic_at_theta_u + v_u - v) / mass)


@pytest.mark.parametrize("seed", [0, 1, 3])
def test_collapse_on_second_arrival_is_not_called_recovery(nominal, seed):
    # elastic impacts (c = 1): the energy at every arrival into a mechanism is the same, so an
    # arch returning with more than its own barrier must collapse when it comes back to it,
    # even if it survives the excursion into the other mechanism in between
    mech = mechanisms(irregular_arch(nominal, 0.1, rng=seed))
    tables = [engine.tabulate(x) for x in mech]
    pack = engine.pack_pair(*tables)
    scal = pack[0]

    def barrier_and_mass(m):
        v = lambda th: compiled_tables.table_function(th, compiled_tables.ROW_V, m, pack)  # noqa: E731
        mass = compiled_tables.table_function(scal[m, 0], compiled_tables.ROW_M, m, pack)
        return v(scal[m, 1]) - v(scal[m, 0]), mass

    (b0, m0), (b1, m1) = barrier_and_mass(0), barrier_and_mass(1)
    # choose the mechanism m whose barrier per unit mass is the smaller one
    m = 0 if b0 / m0 < b1 / m1 else 1
    b, mm, b_other, m_other = (b0, m0, b1, m1) if m == 0 else (b1, m1, b0, m0)
    kinetic = 1.0001 * b                      # above its own barrier
    assert kinetic * m_other / mm < b_other   # ... but survives the other mechanism
    th, thd = _state_returning_with(kinetic, tables, scal, pack, m)
    status, extra, _, _ = rules.decide_outcome(m, th, thd, pack, 1.0, 1.0)
    assert status == engine.STATUS_COLLAPSE and extra == 2
    # and just below its own barrier it recovers
    th, thd = _state_returning_with(0.999 * b, tables, scal, pack, m)
    status, _, _, _ = rules.decide_outcome(m, th, thd, pack, 1.0, 1.0)
    assert status == engine.STATUS_RECOVERY
