"""Lists of values written as text (archquake.ranges): the numbers and ranges a user writes, read
the same way for the command line and the page, refused naming what was read."""

import pytest

from archquake.ranges import inclusive_range, parse_values, range_text
from archquake.studies import failure_domain


def test_numbers_and_ranges_in_the_order_written():
    assert parse_values("0.5, 0.1:0.3:0.1,0.05", "durations") == [0.5, 0.1, 0.2, 0.3, 0.05]
    assert parse_values("0.2:1.0:0.01", "amplitudes") == [round(0.2 + 0.01 * i, 2)
                                                        for i in range(81)]


@pytest.mark.parametrize("text, message", [
    ("", "amplitudes must not be empty"),
    ("0.1:0.3", "amplitudes: a range is start:stop:step, got '0.1:0.3'"),
    ("x", "amplitudes: cannot read 'x'; give numbers separated by commas or a range "
          "start:stop:step"),
    ("0.3:0.1:0.1", "amplitudes: range stop must be >= start, got 0.3:0.1"),
    ("inf", "amplitudes must be finite numbers, got [inf]"),
])
def test_a_refusal_names_what_was_read(text, message):
    for name in ("amplitudes", "--amplitudes"):  # the page's field, the command line's option
        with pytest.raises(ValueError) as refused:
            parse_values(text, name)
        assert str(refused.value) == message.replace("amplitudes", name, 1)


def test_a_default_shown_reads_back_to_its_grid():
    values = (0.1, 2.0, 0.05)
    assert parse_values(range_text(values), "durations") == inclusive_range(*values).tolist()


def test_the_studies_use_the_same_range():
    assert failure_domain.inclusive_range is inclusive_range
