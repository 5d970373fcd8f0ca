"""The rigid-block model at scale: band solvers against a dense solve, a band whose width does
not grow with the number of blocks, an arch at the block limit at rest, and structures beyond
the limit refused before anything is built."""

import math

import numpy as np
import pytest

from archquake.cli import main
from archquake.geometry import circular_arch
from archquake.models import model_for
from archquake.rigid_blocks import (
    MAX_BLOCKS,
    BlockSettings,
    RigidBlockModel,
    block_outcome,
    from_arch,
)
from archquake.rigid_blocks.band import (
    ARCH_BANDWIDTH,
    arch_cholesky_solve,
    arch_lu_solve,
    band_cholesky_solve,
    band_lu_solve,
    band_solve,
)
from archquake.rigid_blocks.contact_problem import incidence
from archquake.rigid_blocks.dynamics import contact_arrays, simulate_blocks


def band_of(dense: np.ndarray, kl: int) -> np.ndarray:
    """The band storage of the solvers: A[i, j] at [i, j - i + kl], 3 kl + 1 columns."""
    n = dense.shape[0]
    band = np.zeros((n, 3 * kl + 1))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + kl + 1)):
            band[i, j - i + kl] = dense[i, j]
    return band


def random_band(rng, n: int, kl: int) -> np.ndarray:
    dense = rng.normal(size=(n, n))
    mask = np.abs(np.subtract.outer(np.arange(n), np.arange(n))) <= kl
    return np.where(mask, dense, 0.0)


@pytest.mark.parametrize("n, kl", [(1, 1), (4, 3), (30, 7), (97, 7), (60, 12)])
def test_band_solvers_match_a_dense_solve(n, kl):
    """Cholesky (symmetric positive definite), elimination without pivoting (diagonally
    dominant) and with partial pivoting (any regular matrix, here one with a zero diagonal
    entry) against numpy.linalg.solve."""
    rng = np.random.default_rng(n + kl)
    b = rng.normal(size=n)
    lower = random_band(rng, n, kl // 2)  # L L^T has half-bandwidth <= kl
    spd = lower @ lower.T + n * np.eye(n)
    x = b.copy()
    assert band_cholesky_solve(band_of(spd, kl), x, n, kl)
    np.testing.assert_allclose(x, np.linalg.solve(spd, b), rtol=1e-10, atol=1e-12)
    dominant = random_band(rng, n, kl) + 4 * kl * np.eye(n)
    x = b.copy()
    assert band_lu_solve(band_of(dominant, kl), x, n, kl, np.abs(np.diag(dominant)))
    np.testing.assert_allclose(x, np.linalg.solve(dominant, b), rtol=1e-10, atol=1e-12)
    if n == 1:
        return
    general = random_band(rng, n, kl)
    general[0, 0] = 0.0  # elimination must pivot
    x = b.copy()
    band_solve(band_of(general, kl), x, n, kl)
    np.testing.assert_allclose(x, np.linalg.solve(general, b), rtol=1e-8, atol=1e-10)
    x = b.copy()
    assert not band_lu_solve(band_of(general, kl), x, n, kl, np.ones(n))  # a zero pivot


@pytest.mark.parametrize("n", [1, 2, 7, 8, 24, 32, 61])
def test_arch_solvers_are_the_band_solvers_bit_for_bit(n):
    """The solvers written out for the half-bandwidth 7 of an arch make the same operations in
    the same order as the general band solvers: the same solutions to the last bit (so the
    outcomes of every analysis are unchanged), for every size, the last rows included."""
    kl = ARCH_BANDWIDTH
    rng = np.random.default_rng(n)
    lower = random_band(rng, n, kl // 2)
    spd = lower @ lower.T + n * np.eye(n)
    dominant = random_band(rng, n, kl) + 4 * kl * np.eye(n)
    if n >= 4:
        dominant[n // 2, n // 2 - 3] = 0.0  # a zero multiplier is skipped by both
    b = rng.normal(size=n)
    x_spd, x_dominant = b.copy(), b.copy()
    assert band_cholesky_solve(band_of(spd, kl), x_spd, n, kl)
    assert band_lu_solve(band_of(dominant, kl), x_dominant, n, kl, np.abs(np.diag(dominant)))
    y_spd, y_dominant = b.copy(), b.copy()
    assert arch_cholesky_solve(band_of(spd, kl), y_spd, n)
    assert arch_lu_solve(band_of(dominant, kl), y_dominant, n, np.abs(np.diag(dominant)))
    assert np.array_equal(y_spd, x_spd) and np.array_equal(y_dominant, x_dominant)
    np.testing.assert_allclose(y_spd, np.linalg.solve(spd, b), rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("voussoirs", [7, 70, 700])
def test_contact_band_of_an_arch_does_not_widen_with_its_voussoirs(voussoirs):
    """Each joint of an arch shares a block with its two neighbours only: contacts 2j, 2j + 1
    couple with 2j - 2 .. 2j + 3, a half-bandwidth of 3 contacts (7 impulses) for any number of
    voussoirs, so the work space of a step is linear in the blocks."""
    assembly = from_arch(circular_arch(10.0, math.radians(157.5), 1.5, voussoirs))
    arrays = contact_arrays(assembly)
    pointer, incident, half_bandwidth = incidence(arrays["contact_bodies"], voussoirs)
    assert half_bandwidth == 3
    assert np.all(np.diff(pointer) == 4)  # every voussoir touches two joints, four contacts


def test_arch_at_the_block_limit_rests_on_a_still_ground():
    """An arch of MAX_BLOCKS voussoirs carries its weight: nothing moves, one linear solve per
    step (the band contact problem at its largest; every step at h, so that a step is one
    contact problem)."""
    arch = circular_arch(10.0, math.radians(157.5), 1.5, MAX_BLOCKS)
    history = simulate_blocks(arch, None, BlockSettings(coarse_factor=1), t_end=0.05,
                              record_every=10)
    assert history.outcome.mean_iterations == 1.0
    assert history.outcome.max_rotation < 1e-8 and history.outcome.max_opening < 1e-9
    weight = arch.masses.sum() * 9.81
    support = history.normal_forces[-1][[0, -1]].sum()
    assert support > 0.4 * weight  # the springings carry the arch (thrust inclined)


def test_structure_beyond_the_block_limit_is_refused_up_front():
    """More than MAX_BLOCKS blocks: a ValueError naming the limit, from every entry point,
    before the arch is converted."""
    arch = circular_arch(10.0, math.radians(157.5), 1.5, MAX_BLOCKS + 1)
    for call in (lambda: block_outcome(arch, None), lambda: RigidBlockModel(arch),
                 lambda: model_for(arch, "rigid-blocks")):
        with pytest.raises(ValueError, match=f"at most {MAX_BLOCKS} blocks"):
            call()
    assert "_rigid_block_assembly" not in arch._cache


def test_cli_dem_refuses_a_thousand_voussoirs(capsys):
    """``archquake rigid-blocks --voussoirs 1000`` answers at once with a one-line error (it grew to
    gigabytes and printed nothing for minutes)."""
    assert main(["rigid-blocks", "--voussoirs", "1000"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and f"at most {MAX_BLOCKS} blocks" in err
    assert "voussoirs" in err and len(err.strip().splitlines()) == 1
