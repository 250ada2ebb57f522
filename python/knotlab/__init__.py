"""knotlab from Python: surgical knot tying from one demonstration, on knotlab's simulator.

The batch API runs what the ``knotlab`` command line runs, on the same engine:

- ``learn(demo=None, pattern=None)`` / ``load_skill(path)``: a learned skill (``Skill``);
- ``scene_info(path=None, preset=None)``: a scene file's presets and randomization;
- ``run_trial(...)``: one trial, reported as ``knotlab run --json`` reports it (a dict);
- ``run_mc(out, trials, ...)``: a Monte Carlo run into a folder, as ``knotlab mc`` makes it
  (resumable, sharded, the same results whatever the number of jobs); its summary (a dict);
- ``read_run(dir)``: a run folder as a pandas DataFrame (one row per trial and method, the drawn
  parameters as columns) and its summary;
- ``draw_trial`` / ``run_drawn_trial``: a Monte Carlo run's trial, its primitives moved by offsets.

Two Gymnasium environments are registered: ``knotlab/KnotTying-v0`` (``KnotTyingEnv``, the task step
by step) and ``knotlab/KnotSkill-v0`` (``KnotSkillEnv``, one trial an episode, the learned skill's
primitives moved by the action); see ``knotlab.envs``.

Every file argument defaults to the shipped one (``scenarios/default.toml``, the shipped
demonstration and task pattern), built into the module. Errors of knotlab's crates are raised as
``KnotlabError`` with the message the command line gives (the file, line, field and value).
"""

from ._knotlab import (
    KnotlabError,
    Skill,
    __version__,
    draw_trial,
    learn,
    load_skill,
    run_drawn_trial,
    run_mc,
    run_trial,
    scene_info,
)
from .runs import read_run, trials_frame

__all__ = [
    "KnotlabError",
    "Skill",
    "__version__",
    "draw_trial",
    "learn",
    "load_skill",
    "run_drawn_trial",
    "read_run",
    "run_mc",
    "run_trial",
    "scene_info",
    "trials_frame",
]

import gymnasium as _gym

from .envs import KnotSkillEnv, KnotTyingEnv, demonstration_actions

__all__ += ["KnotSkillEnv", "KnotTyingEnv", "demonstration_actions"]

if "knotlab/KnotTying-v0" not in _gym.registry:
    _gym.register(id="knotlab/KnotTying-v0", entry_point="knotlab.envs:KnotTyingEnv")
if "knotlab/KnotSkill-v0" not in _gym.registry:
    _gym.register(id="knotlab/KnotSkill-v0", entry_point="knotlab.envs:KnotSkillEnv")
