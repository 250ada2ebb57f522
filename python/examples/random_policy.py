"""A random policy evaluated over seeds in `knotlab/KnotTying-v0`: each episode a scene drawn from the
default randomization (seed S: trial 0 of `knotlab mc --seed S`), the right and the assistant keeping
hold of what they hold, the left moving at random; the verdict of each.

    python python/examples/random_policy.py --episodes 5 --steps 100
"""

import argparse

import gymnasium as gym
import numpy as np

import knotlab  # noqa: F401  (registers the environment)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=5)
    parser.add_argument("--steps", type=int, default=100, help="steps per episode before it is cut off")
    args = parser.parse_args()
    env = gym.make("knotlab/KnotTying-v0", time_limit_s=args.steps / 20.0)
    for seed in range(args.episodes):
        env.reset(seed=seed)
        rng = np.random.default_rng(seed)
        total = 0.0
        while True:
            action = rng.uniform(-0.2, 0.2, size=21)
            action[[13, 20]] = -1.0  # the right's and the assistant's jaws stay closed on what they hold
            _, reward, terminated, truncated, info = env.step(action)
            total += reward
            if terminated or truncated:
                break
        print(f"seed {seed}: {info['verdict']} ({info['ending']}), reward {total}")


if __name__ == "__main__":
    main()
