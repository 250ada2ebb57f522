"""The batch API against the command line: the same trial gives the same report, the same Monte Carlo
run the same lines, and a run folder reads into a DataFrame of one row per trial and method."""

import json
import subprocess

import pytest

import knotlab

# The wall-clock times differ from run to run; nothing else may.
WALL = {"wall_seconds"}


def without(d, keys):
    return {k: v for k, v in d.items() if k not in keys}


def test_run_trial_reports_what_the_command_line_reports(cli, skill):
    """One short trial at a moved, turned and tilted stitch: `run_trial` and `knotlab run --json`."""
    report = knotlab.run_trial(
        skill, seed=3, method="dmp", stitch_offset_m=(0.004, -0.002, 0.0), stitch_rotate_deg=7.0,
        stitch_tilt_deg=4.0, until_s=1.5,
    )
    printed = subprocess.run(
        [cli, "run", "--json", "--seed", "3", "--method", "dmp", "--stitch-offset", "0.004,-0.002,0",
         "--stitch-rotate", "7", "--stitch-tilt", "4", "--until", "1.5"],
        check=True, capture_output=True, text=True,
    ).stdout
    expected = json.loads(printed)
    assert without(report, WALL) == without(expected, WALL)
    assert report["sim_seconds"] >= 1.5 and report["method"] == "dmp"


def test_a_run_folder_reads_into_a_frame_of_trials_and_methods(cli, skill, tmp_path):
    """`run_mc` writes what `knotlab mc` writes for the same run, and `read_run` gives one row per
    trial and method with the drawn parameters as columns."""
    out = tmp_path / "py"
    progress = []
    summary = knotlab.run_mc(
        out, trials=3, seed=5, methods=["fluid", "replay"], jobs=2, skill=skill, until_s=0.5,
        progress=lambda line, done, total: progress.append((line["trial"], line["method"], done, total)),
    )
    assert sorted(p[2] for p in progress) == [1, 2, 3, 4, 5, 6] and {p[3] for p in progress} == {6}
    subprocess.run(
        [cli, "mc", "--trials", "3", "--seed", "5", "--method", "fluid", "--method", "replay", "--jobs", "1",
         "--until", "0.5", "--out", str(tmp_path / "cli")],
        check=True, capture_output=True,
    )
    lines = lambda d: sorted(
        (without(json.loads(line), WALL) for line in (tmp_path / d / "results.jsonl").read_text().splitlines()),
        key=lambda line: (line["trial"], line["method"]),
    )
    assert lines("py") == lines("cli")
    assert json.loads((tmp_path / "cli" / "summary.json").read_text()) == summary
    trials, read = knotlab.read_run(out)
    assert len(trials) == 6
    assert sorted(set(trials["method"])) == ["fluid", "replay"]
    for column in ["trial", "seed", "method", "verdict", "success", "knot", "wound_gap_m",
                   "draw.stitch_offset_m.x", "draw.stitch_offset_m.y", "draw.stitch_rotate_rad",
                   "draw.play_rad", "draw.thread_friction", "slid.long_end_m", "first_self_crossing.time_s",
                   "sim_seconds", "error"]:
        assert column in trials.columns, column
    assert read["run"]["seed"] == 5 and read["trials"] == summary["trials"]
    # The same trial drew the same for both methods.
    per_trial = trials.groupby("trial")["draw.stitch_offset_m.x"].nunique()
    assert (per_trial == 1).all()


def test_a_resumed_run_adds_only_the_trials_it_lacks(skill, tmp_path):
    out = tmp_path / "run"
    knotlab.run_mc(out, trials=2, seed=2, skill=skill, until_s=0.3, jobs=1)
    seen = []
    knotlab.run_mc(out, trials=3, seed=2, skill=skill, until_s=0.3, jobs=1,
                   progress=lambda line, done, total: seen.append(line["trial"]))
    assert seen == [2]
    with pytest.raises(knotlab.KnotlabError, match="another run"):
        knotlab.run_mc(out, trials=3, seed=9, skill=skill, until_s=0.3, jobs=1)


def test_bad_arguments_are_named(skill, tmp_path):
    with pytest.raises(ValueError, match="no such primitive"):
        knotlab.run_drawn_trial(skill=skill, method="replay", offsets={"nope": (0.0, 0.0, 0.0)}, until_s=0.1)
    with pytest.raises(ValueError, match="method \"nope\""):
        knotlab.run_trial(method="nope", until_s=0.1)
    with pytest.raises(ValueError, match="until_s"):
        knotlab.run_trial(until_s=-1.0)
    with pytest.raises(knotlab.KnotlabError, match="missing.toml"):
        knotlab.scene_info(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[tissue]\nyaw_rad = \"north\"\n")
    with pytest.raises(knotlab.KnotlabError, match="bad.toml"):
        knotlab.run_trial(scene=bad, until_s=0.1)
    with pytest.raises(knotlab.KnotlabError, match="no run here"):
        knotlab.read_run(tmp_path)
    assert "workspace" in knotlab.scene_info()["presets"]
