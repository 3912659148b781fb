#!/usr/bin/env python3
"""Held-out loss of exported RAE weights: the paper's loss (train.rae_loss with its default
weights) over N fixed batches of the dataset's eval split (no augmentation; batch i drawn with
random.Random(seed + i)), reported as the mean, with the first batch alone (= train.py's val_loss).

  python3 training/heldout_loss.py DATASET WEIGHTS.raew [...] [--batches 16] [--crop 64]
"""
import argparse
import os
import random
import sys

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rae_net  # noqa: E402
import train  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data")
    ap.add_argument("weights", nargs="+")
    ap.add_argument("--batches", type=int, default=16)
    ap.add_argument("--crop", type=int, default=64)
    ap.add_argument("--seed", type=int, default=12345)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args(argv)
    torch.set_num_threads(args.threads)
    val = train.Dataset(args.data, "eval")
    for w in args.weights:
        net, _ = rae_net.load_weights(w)
        losses = []
        with torch.no_grad():
            for i in range(args.batches):
                x, y = train.sample_batch(val, 4, args.crop, net.in_channels, random.Random(args.seed + i), augment=False)
                losses.append(train.rae_loss(net(x), y)[0].item())
        print(f"{w}: held-out loss {np.mean(losses):.4f} over {args.batches} batches of 4 "
              f"(first batch {losses[0]:.4f})", flush=True)


if __name__ == "__main__":
    main()
