"""The machinery any report reuses: a document rendered to Markdown and self-contained HTML, its
numbers to JSON, its words formatted, its steps timed and its tasks run."""

import base64
import math
import re

import numpy as np
import pytest

from archquake.report import formatting
from archquake.report.paper import text
from archquake.report.render import (
    Document,
    Figure,
    Paragraph,
    Section,
    Table,
    jsonable,
    markdown,
    write_html,
    write_markdown,
)
from archquake.report.running import HERE, Background, Steps, Task, run_here

PNG = (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x01\x00\x00\x00\x01\x08\x06\x00\x00"
       b"\x00\x1f\x15\xc4\x89\x00\x00\x00\rIDATx\x9cc\xf8\x0f\x00\x00\x01\x01\x00\x05\x18\xd8N"
       b"\x00\x00\x00\x00IEND\xaeB`\x82")
"""A 1 x 1 pixel PNG."""


def _document(figure_file="one.png"):
    return Document("Tab title", "Heading", [
        Section("First", [Paragraph("A <b> & c."), Table(["a", "b|c"], [["1", "x|y"]])]),
        Section("Second", [Figure(figure_file, "Fig. 1", "Caption & more.", True),
                           Figure(figure_file, "Fig. 2", "Other.", None)]),
    ])


def test_markdown_of_a_document():
    assert markdown(_document()) == "\n".join([
        "# Heading", "",
        "## First", "",
        "A <b> & c.", "",
        "| a | b\\|c |", "|---|---|", "| 1 | x\\|y |", "",
        "## Second", "",
        "![Fig. 1](one.png)", "", "**Fig. 1** (agrees). Caption & more.", "",
        "![Fig. 2](one.png)", "", "**Fig. 2** (no comparison). Other.", "",
    ])


def test_html_embeds_the_figures_and_escapes_the_text(tmp_path):
    (tmp_path / "one.png").write_bytes(PNG)
    path = write_html(tmp_path / "page.html", _document())
    page = path.read_text()
    assert page.startswith("<!DOCTYPE html>") and "<title>Tab title</title>" in page
    assert "<h1>Heading</h1>" in page and "<h2>First</h2>" in page
    assert "<p>A &lt;b&gt; &amp; c.</p>" in page
    assert "<th>b|c</th>" in page and "<td>x|y</td>" in page
    embedded = re.findall(r"src='data:image/png;base64,([^']+)'", page)
    assert [base64.b64decode(e) for e in embedded] == [PNG, PNG]
    assert "<span class='agrees'>agrees</span>" in page
    assert "<span class='no'>no comparison</span>" in page
    assert "one.png" not in page  # no link to a file beside it


def test_markdown_file(tmp_path):
    path = write_markdown(tmp_path / "page.md", _document())
    assert path.read_text() == markdown(_document())


def test_figure_verdict_and_stem():
    assert Figure("fig16_failure_domain.png", "Fig. 16", "", False).verdict == "differs"
    assert Figure("fig16_failure_domain.png", "Fig. 16", "", True).stem == "fig16_failure_domain"


def test_jsonable():
    value = jsonable({("NA", 0.4): np.array([1.0, np.nan]), "n": np.int64(3),
                      "x": (np.float64(math.inf), 2.5), "ok": np.bool_(True)})
    assert value == {"('NA', 0.4)": [1.0, None], "n": 3, "x": [None, 2.5], "ok": True}
    assert type(value["n"]) is int and type(value["ok"]) is bool


def test_formatters():
    assert formatting.number(math.pi) == "3.1416" and formatting.number(float("nan")) == "-"
    assert formatting.number(None, 2) == "-" and formatting.number(2.0, 2) == "2.00"
    assert formatting.signed(-0.00005, 4) == "-0.0001" and formatting.signed(None) == "-"
    assert formatting.percent(0.0512) == "+5.1 %" and formatting.percent(None) == "-"
    assert (formatting.agree(True), formatting.agree(False)) == ("agrees", "differs")
    assert formatting.outcome_text("collapse", 2) == "collapse in half cycle 2"
    assert formatting.outcome_text("recovery", 0) == "recovery"
    assert text.restitution_label("paper", (0.875, 0.875)) == "c_v = 0.875 (paper's)"
    assert text.restitution_label("computed", [0.6449, 0.6449]) == "c_v = 0.645 (computed)"


def test_captions_state_the_verdict_they_are_given():
    for ok in (True, False):
        caption = text.free_vibration_caption("paper", (0.875, 0.875), ok)
        assert caption.endswith(f"Ours: {formatting.agree(ok)} for all three arches.")
        assert "Figs. 12-14" in caption and "c_v = 0.875 (paper's)" in caption
        assert text.comparison_caption(ok).endswith(f" - {formatting.agree(ok)}.")
    assert "Figs. 9-11" in text.free_vibration_caption("elastic", (1.0, 1.0), True)


def test_run_info_blocks():
    results = {"timings": {"a": 1.0, "report": 0.5, "total": 2.0},
               "background": {"task": {"ran on": HERE, "seconds": 1.25, "wall_seconds": 1.5}},
               "environment": {"python": "3"}, "settings": {"seed": 7}}
    blocks = text.run_info(results)
    assert [type(b) for b in blocks] == [Table, Paragraph, Table, Paragraph, Paragraph]
    assert blocks[0].rows == [["a", "1.00"], ["total", "2.00"]]
    assert blocks[2].rows == [["task", HERE, "1.25", "1.50"]]
    assert blocks[3].text == "python 3; seed 7." and blocks[4].text == "Settings: seed = 7."


def test_tasks_without_a_second_process_run_when_asked():
    calls = []
    task = Background().submit(calls.append, 1)
    assert calls == []  # deferred
    run = task.result()
    assert calls == [1] and task.result() is run and calls == [1]  # once
    assert run.ran_on == HERE and run.wall_seconds == run.seconds >= 0
    assert run.describe() == {"ran on": HERE, "seconds": run.seconds,
                              "wall_seconds": run.seconds}
    assert run_here(sum, (1, 2)).result == 3


def test_a_task_run_now_is_done_and_runs_once():
    calls = []
    deferred = Background().submit(calls.append, 0)
    assert not deferred.done and calls == []
    task = Task.run_now(calls.append, 1)
    assert calls == [1] and task.done  # run at once, here
    run = task.result()
    assert calls == [1] and run.ran_on == HERE and task.result() is run


def test_steps_time_every_step_in_order():
    steps = Steps(2, progress=False)
    with steps("b"):
        pass
    with pytest.raises(RuntimeError), steps("a"):
        raise RuntimeError
    with steps("a"):
        pass
    steps.close()
    assert list(steps.timings) == ["b", "a"] and all(v >= 0 for v in steps.timings.values())
