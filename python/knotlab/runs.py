"""A Monte Carlo run folder (``knotlab mc --out DIR`` or ``knotlab.run_mc(DIR, ...)``) as a pandas
DataFrame: one row per finished trial and method, in the order of ``results.jsonl``.

Columns: ``trial``, ``seed``, ``method``, ``verdict``, ``success`` (the verdict is ``success``),
``knot``, ``wound_gap_m``, the thread's health (``thread_max_stretch``, ``thread_stretched_s``,
``thread_self_crossings``, ``first_self_crossing.time_s``, ...), how far the knot slid in the holding
test (``slid.long_end_m``, ``slid.tail_m``), ``sim_seconds``, ``wall_seconds``, ``error``, and what the
trial drew, each as ``draw.NAME`` (a three-vector as ``draw.NAME.x``, ``.y``, ``.z``; the obstacles,
a list, as one column of lists).
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Tuple

from . import _knotlab

_AXES = ("x", "y", "z")
# Fields that are a small record or none: their columns are there either way.
_RECORDS = {"first_self_crossing": ("time_s", "segments"), "slid": ("long_end_m", "tail_m")}


def _flat(prefix: str, value: Any, row: Dict[str, Any]) -> None:
    if isinstance(value, dict):
        for key, inner in value.items():
            _flat(f"{prefix}.{key}" if prefix else key, inner, row)
    elif (
        isinstance(value, list)
        and len(value) == 3
        and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
    ):
        for axis, v in zip(_AXES, value):
            row[f"{prefix}.{axis}"] = v
    else:
        row[prefix] = value


def trials_frame(lines: List[Dict[str, Any]]):
    """The DataFrame of a run's lines (as ``read_run`` reads them from ``results.jsonl``)."""
    import pandas as pd

    rows = []
    for line in lines:
        row: Dict[str, Any] = {}
        for key, value in line.items():
            if key in _RECORDS and value is None:
                for field in _RECORDS[key]:
                    row[f"{key}.{field}"] = None
                continue
            _flat(key, value, row)
        row["success"] = line["verdict"] == "success"
        rows.append(row)
    frame = pd.DataFrame(rows)
    first = ["trial", "seed", "method", "verdict", "success"]
    if len(frame.columns):
        frame = frame[first + [c for c in frame.columns if c not in first]]
    return frame


def read_run(directory: "str | os.PathLike[str]") -> Tuple[Any, Dict[str, Any]]:
    """The run in ``directory``: ``(trials, summary)``, the trials a DataFrame (see the module's
    doc) and the summary a dict (what ``summary.json`` holds for the lines there, with ``run.json``
    under the key ``"run"``, None when the folder has none). Every line is checked to belong to the
    run, as a resumed run checks them; a line of another run raises ``KnotlabError``."""
    lines, info, summary = _knotlab.read_run(os.fspath(directory))
    summary = dict(summary)
    summary["run"] = info
    return trials_frame(lines), summary
