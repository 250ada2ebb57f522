"""The shipped expert's demonstration played back through `knotlab/KnotTying-v0`'s `step`: the scene
as the demonstration was recorded in it (no randomization, seed 0), the recorded tip poses and jaws
turned into the environment's actions at its control rate, and the knot's verdict (open loop,
where the knot comes to rest is chaotic: see docs/python.md).

    python python/examples/replay_demonstration.py
"""

import time

import knotlab


def main() -> None:
    env = knotlab.KnotTyingEnv(randomize=False)
    actions = knotlab.demonstration_actions(env=env)
    env.reset(seed=0)
    started = time.perf_counter()
    for step, action in enumerate(actions, start=1):
        _, reward, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            break
    wall_s = time.perf_counter() - started
    print(f"{step} steps ({step / 20.0:.2f} s simulated) in {wall_s:.1f} s: {step / wall_s:.0f} steps a second")
    print(f"{info['ending']}: {info['verdict']}, reward {reward}")


if __name__ == "__main__":
    main()
