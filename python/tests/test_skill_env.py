"""The Gymnasium environment `knotlab/KnotSkill-v0`: one trial an episode, the learned skill's
primitives moved by the action. It passes Gymnasium's checker, pickles, and an action of zeros is the
method's own trial as a Monte Carlo run runs it."""

import json
import pickle
from concurrent.futures import ThreadPoolExecutor

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import knotlab


def test_the_skill_environment_passes_gymnasiums_checker_and_pickles(skill):
    env = gym.make("knotlab/KnotSkill-v0", skill=skill, until_s=0.5)
    check_env(env.unwrapped)
    assert env.unwrapped.primitives == [name for _, name in skill.primitives()]
    assert env.action_space.shape == (3 * len(skill.primitives()),)
    observation, info = env.reset(seed=4, options={"trial": 2})
    copy = pickle.loads(pickle.dumps(env.unwrapped))
    again, _ = copy.reset(seed=4, options={"trial": 2})
    assert np.array_equal(observation, again)
    with pytest.raises(ValueError, match=r"\[-1, 1\]"):
        env.step(np.full(env.action_space.shape, 2.0))


def test_no_offset_is_the_methods_own_trial_of_a_monte_carlo_run(skill, tmp_path):
    """Trial 1 of a run seeded 6, by dmp: the environment with an action of zeros and `run_mc`."""
    env = knotlab.KnotSkillEnv(method="dmp", skill=skill, until_s=1.0)
    observation, info = env.reset(seed=6, options={"trial": 1})
    _, reward, terminated, truncated, info = env.step(np.zeros(env.action_space.shape))
    assert terminated and not truncated
    knotlab.run_mc(tmp_path, trials=2, seed=6, methods=["dmp"], skill=skill, until_s=1.0, jobs=1)
    line = [json.loads(l) for l in (tmp_path / "results.jsonl").read_text().splitlines() if json.loads(l)["trial"] == 1][0]
    assert info["drawn"] == line["draw"]
    assert observation.tolist() == [*line["draw"]["stitch_offset_m"], line["draw"]["stitch_rotate_rad"], line["draw"]["stitch_tilt_rad"]]
    report = info["report"]
    assert report["verdict"] == line["verdict"] and report["wound_gap_m"] == line["wound_gap_m"]
    assert report["thread_most_stretched"]["ratio"] == line["thread_max_stretch"]
    assert reward == (1.0 if line["verdict"] == "success" else 0.0)


def test_an_offset_changes_the_trial(skill):
    """The right's winding (R2) moved 5 mm across the wound: the thread ends elsewhere."""
    k = knotlab.KnotSkillEnv(skill=skill, until_s=12.0).primitives.index("R2")
    action = np.zeros(3 * len(skill.primitives()))
    action[3 * k + 1] = 1.0

    def episode(action):
        env = knotlab.KnotSkillEnv(skill=skill, until_s=12.0)
        env.reset(seed=0)
        return env.step(action)[4]

    # Both episodes at once, each in its own thread (a step lets go of the GIL while it simulates).
    with ThreadPoolExecutor(max_workers=2) as pool:
        still, moved = pool.map(episode, [np.zeros_like(action), action])
    assert still["report"]["thread_most_stretched"] != moved["report"]["thread_most_stretched"]
