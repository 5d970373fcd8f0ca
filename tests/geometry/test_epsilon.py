"""One check of the paper's epsilon (eq. (1)), used by every place that takes it: the irregular
draw, the arch sample of the studies, and both reports' settings."""

import pytest

from archquake.geometry import check_epsilon, irregular_arch
from archquake.reference_arches import oppenheim
from archquake.report import ReproductionSettings
from archquake.report.assess.settings import AssessmentSettings
from archquake.studies.arch_sample import ArchSample


@pytest.mark.parametrize("good, value", [(0, 0.0), (0.1, 0.1), ("0.25", 0.25)])
def test_a_number_in_zero_one_is_taken(good, value):
    assert check_epsilon(good) == value


@pytest.mark.parametrize("bad", [1.0, -0.1, float("nan"), float("inf"), "x", None, True])
def test_every_place_refuses_the_same_values_with_the_same_message(bad):
    message = f"epsilon must be in [0, 1), got {bad!r}"
    for make in (lambda: check_epsilon(bad), lambda: irregular_arch(oppenheim(), bad, rng=0),
                 lambda: ArchSample(oppenheim(), bad, 0),
                 lambda: ReproductionSettings(epsilon=bad),
                 lambda: AssessmentSettings(epsilon=bad)):
        with pytest.raises(ValueError) as exc:
            make()
        assert str(exc.value) == message
