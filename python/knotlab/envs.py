"""Gymnasium environments on knotlab's simulator.

``knotlab/KnotTying-v0`` (``KnotTyingEnv``): the whole knot-tying task, step by step. ``reset(seed=S)``
draws the scene as trial 0 of a Monte Carlo run seeded ``S`` draws it (``options={"trial": K}`` for
trial K; the same draw as ``knotlab mc --seed S``), in the task's initial condition: the right
instrument holds the needle through both flaps, the assistant holds the tail, the left is parked.

Action: 21 numbers in [-1, 1], seven per instrument (left, right, assist): the tip's velocity (three,
along the world's axes, times ``max_speed_mps``), its rate of turn (three, about the world's axes,
times ``max_turn_rad_s``) and the jaw's opening (-1 closed to 1 at ``max_jaw_rad``). Each step lasts
``1 / control_hz`` s (20 Hz by default: the task's finest motions, a 0.3 s jaw closing and 1 cm
winding circles, are resolved within 0.03 mm by 50 ms straight chords); the controller runs the
targets at every 1 ms cycle in between exactly as it runs a learned skill (the arm's inverse
kinematics with the shaft through its trocar, the joints' speed limits). A step's target that the
arm cannot reach through its trocar is not taken (``info["out_of_reach"]`` names the instrument).
An action outside the action space raises ``ValueError``.

Observation (a dict, world frame, instruments in the order left, right, assist):
``tip_position_m`` (3, 3), ``tip_quaternion_xyzw`` (3, 4), ``jaw_rad`` (3,), ``grasp`` (3,: 0 open,
1 holding the thread or needle, 2 closed on nothing, 3 slipped), ``force_n`` (3, 3: what each
instrument's strain gauges read), ``wound_gap_m`` (1,), ``thread_m`` (``thread_points``, 3: the
thread's centreline from the needle end to the tail's end at evenly spaced points) and ``time_s``
(1,).

The episode ends (``terminated``) when no instrument holds the thread or the needle any more (the
knot's verdict is then final) or when a device faults, and is cut off (``truncated``) at
``time_limit_s``; either way the knot is then judged as a trial's is, with the holding test, and
``info["verdict"]`` says how (``success`` or the failure mode). Reward: 1 at the end for an accepted
knot, else 0; optional shaping terms, off by default, per step: ``shaping={"wound_gap": w}`` adds
``-w`` times the wound's gap in m, ``shaping={"out_of_reach": w}`` adds ``-w`` per instrument whose
target was out of reach.

``render()`` (``render_mode="rgb_array"``) returns the scene drawn from above, the front and the side,
an array of shape (``render_pixels``, 3 * ``render_pixels``, 3).

The environment pickles: what it holds is its settings, its reset's seed and the actions since, and
unpickling replays them (the simulation is deterministic), so ``AsyncVectorEnv`` can run copies in
processes.
"""

from __future__ import annotations

import copy
import os
from typing import Any, Dict, List, Optional, Tuple

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from . import _knotlab

ARMS = ("left", "right", "assist")
SHAPING_TERMS = ("wound_gap", "out_of_reach")
# The step's settings by default (see KnotTyingEnv).
DEFAULTS = dict(control_hz=20.0, max_speed_mps=0.15, max_turn_rad_s=4.0, max_jaw_rad=0.8)


class KnotTyingEnv(gym.Env):
    """The knot-tying task step by step (see the module's documentation)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self,
        scene: "Optional[str | os.PathLike[str]]" = None,
        preset: Optional[str] = None,
        randomize: bool = True,
        control_hz: float = 20.0,
        time_limit_s: float = 60.0,
        max_speed_mps: float = 0.15,
        max_turn_rad_s: float = 4.0,
        max_jaw_rad: float = 0.8,
        thread_points: int = 32,
        shaping: Optional[Dict[str, float]] = None,
        render_mode: Optional[str] = None,
        render_pixels: int = 160,
    ) -> None:
        shaping = dict(shaping or {})
        unknown = sorted(set(shaping) - set(SHAPING_TERMS))
        if unknown:
            raise ValueError(f"shaping: unknown terms {unknown}; the terms are {list(SHAPING_TERMS)}")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode {render_mode!r}: None or 'rgb_array'")
        self._settings = dict(
            scene=None if scene is None else os.fspath(scene),
            preset=preset,
            randomize=randomize,
            control_hz=float(control_hz),
            time_limit_s=float(time_limit_s),
            max_speed_mps=float(max_speed_mps),
            max_turn_rad_s=float(max_turn_rad_s),
            max_jaw_rad=float(max_jaw_rad),
            thread_points=int(thread_points),
        )
        self._shaping = shaping
        self.render_mode = render_mode
        self._render_pixels = int(render_pixels)
        self.metadata = dict(self.metadata, render_fps=control_hz)
        self.action_space = spaces.Box(-1.0, 1.0, shape=(7 * len(ARMS),), dtype=np.float32)
        inf = np.inf
        self.observation_space = spaces.Dict(
            {
                "tip_position_m": spaces.Box(-inf, inf, shape=(3, 3), dtype=np.float64),
                "tip_quaternion_xyzw": spaces.Box(-1.0, 1.0, shape=(3, 4), dtype=np.float64),
                "jaw_rad": spaces.Box(-inf, inf, shape=(3,), dtype=np.float64),
                "grasp": spaces.MultiDiscrete([4, 4, 4]),
                "force_n": spaces.Box(-inf, inf, shape=(3, 3), dtype=np.float64),
                "wound_gap_m": spaces.Box(-inf, inf, shape=(1,), dtype=np.float64),
                "thread_m": spaces.Box(-inf, inf, shape=(int(thread_points), 3), dtype=np.float64),
                "time_s": spaces.Box(0.0, inf, shape=(1,), dtype=np.float64),
            }
        )
        # Checked once here, so that a bad setting fails at construction, not at the first reset.
        self._episode: Optional[Any] = _knotlab.Episode(**self._settings, seed=0, trial=0)
        self._episode = None
        self._reset_args: Optional[Tuple[int, int]] = None
        self._actions: List[np.ndarray] = []
        self._ended = False

    # -- the task ----------------------------------------------------------------------------------

    def reset(self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None):
        super().reset(seed=seed)
        if seed is None:
            seed = int(self.np_random.integers(0, 2**63 - 1))
        trial = int((options or {}).get("trial", 0))
        self._start(int(seed), trial)
        return self._observation(), self._info(None, [])

    def _start(self, seed: int, trial: int) -> None:
        self._episode = _knotlab.Episode(**self._settings, seed=seed, trial=trial)
        self._reset_args = (seed, trial)
        self._actions = []
        self._ended = False

    def step(self, action):
        if self._episode is None:
            raise RuntimeError("reset the environment before stepping it")
        if self._ended:
            raise RuntimeError("the episode has ended; reset the environment")
        action = np.asarray(action, dtype=np.float64).reshape(-1)
        if action.shape != (7 * len(ARMS),):
            raise ValueError(f"an action has {7 * len(ARMS)} numbers, not {action.size}")
        if not np.all(np.isfinite(action)) or np.any(np.abs(action) > 1.0 + 1e-6):
            raise ValueError(f"an action's numbers lie in [-1, 1]: {action.tolist()}")
        ending, out_of_reach = self._episode.step(self._command(action))
        self._actions.append(action.copy())
        observation = self._observation()
        reward = -self._shaping.get("wound_gap", 0.0) * float(observation["wound_gap_m"][0])
        reward -= self._shaping.get("out_of_reach", 0.0) * len(out_of_reach)
        verdict = None
        if ending is not None:
            self._ended = True
            verdict = self._episode.evaluation()["verdict"]
            reward += 1.0 if verdict == "success" else 0.0
        terminated = ending is not None and ending != "time_limit"
        truncated = ending == "time_limit"
        return observation, float(reward), terminated, truncated, self._info(ending, out_of_reach, verdict)

    def _command(self, action: np.ndarray) -> List[float]:
        s = self._settings
        command: List[float] = []
        for k in range(len(ARMS)):
            a = action[7 * k : 7 * (k + 1)]
            # Within [-1, 1] but for round-off (checked in step).
            a = np.clip(a, -1.0, 1.0)
            command.extend((a[0:3] * s["max_speed_mps"]).tolist())
            command.extend((a[3:6] * s["max_turn_rad_s"]).tolist())
            command.append(float((a[6] + 1.0) * 0.5 * s["max_jaw_rad"]))
        return command

    def _observation(self) -> Dict[str, np.ndarray]:
        o = self._episode.observation()
        grasp = {"open": 0, "holding": 1, "closed_empty": 2, "slipped": 3}
        return {
            "tip_position_m": np.array(o["world_tip_position_m"], dtype=np.float64),
            "tip_quaternion_xyzw": np.array(o["world_tip_quaternion_xyzw"], dtype=np.float64),
            "jaw_rad": np.array(o["jaw_rad"], dtype=np.float64),
            "grasp": np.array([grasp[g] for g in o["grasp"]], dtype=np.int64),
            "force_n": np.array(o["world_force_n"], dtype=np.float64),
            "wound_gap_m": np.array([o["wound_gap_m"]], dtype=np.float64),
            "thread_m": np.array(o["thread_m"], dtype=np.float64),
            "time_s": np.array([o["time_s"]], dtype=np.float64),
        }

    def _info(self, ending, out_of_reach, verdict=None) -> Dict[str, Any]:
        info: Dict[str, Any] = {"out_of_reach": list(out_of_reach), "drawn": self._episode.drawn()}
        if ending is not None:
            info["ending"] = ending
            info["verdict"] = verdict
            info["evaluation"] = self._episode.evaluation()
        return info

    def render(self):
        if self.render_mode != "rgb_array" or self._episode is None:
            return None
        rgb, width, height = self._episode.render(self._render_pixels)
        return np.frombuffer(bytes(rgb), dtype=np.uint8).reshape(height, width, 3)

    # -- pickling: the settings, the reset and the actions, replayed -------------------------------

    def __getstate__(self):
        return {
            "settings": self._settings,
            "shaping": self._shaping,
            "render_mode": self.render_mode,
            "render_pixels": self._render_pixels,
            "reset_args": self._reset_args,
            "actions": [a.tolist() for a in self._actions],
            "np_random": None if self._np_random is None else self._np_random.bit_generator.state,
        }

    def __setstate__(self, state):
        self.__init__(
            **state["settings"],
            shaping=state["shaping"],
            render_mode=state["render_mode"],
            render_pixels=state["render_pixels"],
        )
        if state["np_random"] is not None:
            self._np_random = np.random.Generator(np.random.PCG64())
            self._np_random.bit_generator.state = state["np_random"]
        if state["reset_args"] is not None:
            self._start(*state["reset_args"])
            for a in state["actions"]:
                ending, _ = self._episode.step(self._command(np.asarray(a, dtype=np.float64)))
                self._actions.append(np.asarray(a, dtype=np.float64))
                self._ended = ending is not None


def demonstration_actions(demo: "Optional[str | os.PathLike[str]]" = None, env: Optional[KnotTyingEnv] = None):
    """The actions that play the demonstration in ``demo`` (the shipped one when None) back through
    ``env`` (its control rate and bounds; the default environment's when None): an array of shape
    (steps, 21). Reset the environment with ``randomize=False`` and seed 0 (the scene as the shipped
    demonstration was recorded in it) to play it back. Open loop, where the knot comes to rest is
    chaotic: actions a part in 1e9 apart can leave it a millimetre higher or lower, so one playback
    may end over the 2 mm the verdict allows where most tie it."""
    s = env._settings if env is not None else DEFAULTS
    steps = _knotlab.demonstration_steps(
        None if demo is None else os.fspath(demo), s["control_hz"], s["max_jaw_rad"]
    )
    actions = []
    for command in steps:
        action = []
        for k in range(len(ARMS)):
            c = command[7 * k : 7 * (k + 1)]
            action.extend(np.asarray(c[0:3]) / s["max_speed_mps"])
            action.extend(np.asarray(c[3:6]) / s["max_turn_rad_s"])
            action.append(c[6] / s["max_jaw_rad"] * 2.0 - 1.0)
        actions.append(action)
    return np.asarray(actions, dtype=np.float64)


class KnotSkillEnv(gym.Env):
    """``knotlab/KnotSkill-v0``: one trial an episode, the learned skill's primitives moved by the
    action, for residual and black-box methods that build on the paper's method.

    ``reset(seed=S)`` draws the scene as trial 0 of a Monte Carlo run seeded ``S`` (``options=
    {"trial": K}`` for trial K), the same draw as ``knotlab mc --seed S`` and ``KnotTying-v0``'s.
    The observation is what a surgeon sees of the site: the stitch's shift (x, y, z, m), its turn about
    the tissue's normal and its tilt about the wound (rad), a (5,) array. The action holds three
    numbers in [-1, 1] per primitive of the skill (``primitives``, in the order of ``Skill.primitives()``):
    the primitive's offset along the stitch frame's x (along the wound), y (across it) and z (out of
    the tissue), times ``max_offset_m`` (5 mm); an instrument's keys within a primitive move by its
    offset, between two of its primitives the offset blends from the one to the next. The step runs
    the trial as ``knotlab mc`` runs it (synthesis by ``method``, the previews, the simulated rig, the
    knot's evaluation) and ends the episode: reward 1 for an accepted knot, else 0;
    ``info["report"]`` is the trial's report (``knotlab run --json``'s fields but the wall-clock time).
    An action of zeros is the method's own trial: its verdict is that of ``knotlab mc``'s trial line.
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        scene: "Optional[str | os.PathLike[str]]" = None,
        preset: Optional[str] = None,
        method: str = "fluid",
        max_offset_m: float = 0.005,
        skill: Optional[Any] = None,
        until_s: Optional[float] = None,
    ) -> None:
        if not (np.isfinite(max_offset_m) and max_offset_m > 0):
            raise ValueError(f"max_offset_m {max_offset_m}: a positive length")
        self._settings = dict(
            scene=None if scene is None else os.fspath(scene),
            preset=preset,
            method=method,
            max_offset_m=float(max_offset_m),
            until_s=until_s,
        )
        self._skill = skill if skill is not None else _knotlab.learn()
        self.primitives = [name for _, name in self._skill.primitives()]
        _knotlab.draw_trial(self._settings["scene"], preset, 0, 0)  # a bad scene or preset fails here
        self.action_space = spaces.Box(-1.0, 1.0, shape=(3 * len(self.primitives),), dtype=np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(5,), dtype=np.float64)
        self._reset_args: Optional[Tuple[int, int]] = None
        self._done = False

    def reset(self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None):
        super().reset(seed=seed)
        if seed is None:
            seed = int(self.np_random.integers(0, 2**63 - 1))
        trial = int((options or {}).get("trial", 0))
        self._reset_args = (int(seed), trial)
        self._done = False
        drawn = _knotlab.draw_trial(self._settings["scene"], self._settings["preset"], int(seed), trial)
        self._drawn = drawn
        return self._observation(drawn), {"drawn": copy.deepcopy(drawn)}

    @staticmethod
    def _observation(drawn: Dict[str, Any]) -> np.ndarray:
        return np.array(
            [*drawn["stitch_offset_m"], drawn["stitch_rotate_rad"], drawn["stitch_tilt_rad"]], dtype=np.float64
        )

    def step(self, action):
        if self._reset_args is None:
            raise RuntimeError("reset the environment before stepping it")
        if self._done:
            raise RuntimeError("the episode (one trial) has ended; reset the environment")
        action = np.asarray(action, dtype=np.float64).reshape(-1)
        if action.shape != self.action_space.shape:
            raise ValueError(f"an action has {self.action_space.shape[0]} numbers (3 per primitive), not {action.size}")
        if not np.all(np.isfinite(action)) or np.any(np.abs(action) > 1.0 + 1e-6):
            raise ValueError(f"an action's numbers lie in [-1, 1]: {action.tolist()}")
        offsets = {
            name: tuple(float(x) for x in np.clip(action[3 * k : 3 * k + 3], -1.0, 1.0) * self._settings["max_offset_m"])
            for k, name in enumerate(self.primitives)
        }
        seed, trial = self._reset_args
        report = _knotlab.run_drawn_trial(
            self._skill, self._settings["scene"], self._settings["preset"], seed, trial,
            self._settings["method"], offsets, self._settings["until_s"],
        )
        self._done = True
        # The same seed and action give the same info: the wall-clock time is left out.
        report.pop("wall_seconds", None)
        reward = 1.0 if report["success"] else 0.0
        info = {"drawn": copy.deepcopy(self._drawn), "verdict": report["verdict"], "report": report}
        return self._observation(self._drawn), reward, True, False, info

    def __getstate__(self):
        return {
            "settings": self._settings,
            "skill": self._skill,
            "reset_args": self._reset_args,
            "done": self._done,
            "np_random": None if self._np_random is None else self._np_random.bit_generator.state,
        }

    def __setstate__(self, state):
        self.__init__(**state["settings"], skill=state["skill"])
        if state["np_random"] is not None:
            self._np_random = np.random.Generator(np.random.PCG64())
            self._np_random.bit_generator.state = state["np_random"]
        if state["reset_args"] is not None:
            seed, trial = state["reset_args"]
            self.reset(seed=seed, options={"trial": trial})
            self._done = state["done"]
